// dynamic/level_set.cpp: level sets of the skin function.
#include "dynamic/level_set.h"

#include <algorithm>
#include <cmath>

#include "skin/mixed_complex.h"

namespace skinmesh::dynamic {

LevelSet::LevelSet(const skin::SkinSurface& skin, double c) : skin_(&skin), c_(c) {
  const auto& pts = skin.points();
  lo_ = hi_ = pts.front().z;
  double r = 0;
  for (const auto& p : pts) {
    lo_ = lo_.cwiseMin(p.z);
    hi_ = hi_.cwiseMax(p.z);
    r = std::max(r, std::sqrt(std::max(p.w, 0.0)));
  }
  // A margin of rounding size: points at the box's face are still located.
  constexpr double kHullSlack = 1e-9;  // [derived] relative, and times L: rounding size
  const double margin = r * (1 + kHullSlack) + kHullSlack * length_scale();
  lo_.array() -= margin;
  hi_.array() += margin;
}

bool LevelSet::outside_hull(const Vec3& x) const {
  return (x.array() < lo_.array()).any() || (x.array() > hi_.array()).any();
}

double LevelSet::value(const Vec3& x, Index& cell) const {
  if (outside_hull(x)) {
    const Vec3 clamped = x.cwiseMax(lo_).cwiseMin(hi_);
    return (x - clamped).squaredNorm() + 1.0;
  }
  const skin::MixedComplex& mc = skin_->mixed_complex();
  cell = mc.locate(x, cell);
  return mc.f(cell, x) - c_;
}

bool LevelSet::project(const Vec3& x0, Vec3& out, Index& cell, double& rho) const {
  const skin::MixedComplex& mc = skin_->mixed_complex();
  // [derived] Newton's step converges quadratically: 1e-14 L is reached in a
  // few steps from a sample's previous position; the last step accepts 1e-11 L.
  constexpr double kNewtonTolerance = 1e-14, kNewtonLastTolerance = 1e-11;
  constexpr int kNewtonSteps = 100;  // [measured] the iteration limit of the projection
  const double tol = kNewtonTolerance * length_scale();
  Vec3 x = x0;
  for (int it = 0; it <= kNewtonSteps; ++it) {
    if (outside_hull(x)) return false;
    cell = mc.locate(x, cell);
    const double v = mc.f(cell, x) - c_;
    const Vec3 g = mc.gradient(cell, x);
    const double g2 = g.squaredNorm();
    if (!(g2 > 0)) return false;
    const double dist = std::abs(v) / std::sqrt(g2);
    if (dist <= tol || (it == kNewtonSteps && dist <= kNewtonLastTolerance * length_scale())) {
      out = x;
      rho = mc.rho(cell, x);
      return true;
    }
    x -= (v / g2) * g;
  }
  return false;
}

bool LevelSet::crossing(const Vec3& p, const Vec3& q, double vp, double vq, Vec3& out, Index& cell, double& rho) const {
  const Vec3 d = q - p;
  const double len = d.norm();
  constexpr double kBracketTolerance = 1e-12;  // [derived] times L: a few ulps
  constexpr int kBracketSteps = 200;           // [derived] bisection halves the bracket at least every third step
  const double tol = kBracketTolerance * length_scale();
  double a = 0, b = 1, fa = vp, fb = vq;
  int side = 0;
  Index hint = cell;
  for (int it = 0; it < kBracketSteps && (b - a) * len > tol; ++it) {
    double t = it % 3 == 2 ? 0.5 * (a + b) : (a * fb - b * fa) / (fb - fa);
    if (!(t > a && t < b)) t = 0.5 * (a + b);
    const double ft = value(p + t * d, hint);
    if (ft == 0) {
      a = b = t;
      break;
    }
    if ((ft < 0) == (fa < 0)) {
      a = t;
      fa = ft;
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      b = t;
      fb = ft;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
  }
  cell = hint;
  return project(p + (0.5 * (a + b)) * d, out, cell, rho);
}

}  // namespace skinmesh::dynamic
