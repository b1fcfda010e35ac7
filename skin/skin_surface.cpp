// skin/skin_surface.cpp: evaluation and projection on the skin surface.
// papers/skin/skin_math.md §3 (patches), §4.1 (curvature), §7.2 (normal-line
// projection), §7.3 (gradient–Newton pull-back).
#include "skin/skin_surface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/errors.h"

namespace skinmesh::skin {

namespace {

/// Relative size below which the quadratic's leading coefficient counts as
/// zero (the equation is then solved as linear). [derived] a few units in the
/// last place of the coefficients, which are sums of a few products.
constexpr double kLinearThreshold = 1e-14;
/// Step past a cell's wall when the projection walks into the next cell, and
/// slack on the distances compared (units of the skin's length scale).
/// [derived] above the walk's rounding, far below any feature of the skin.
constexpr double kWallStep = 1e-12;
/// Most cells the projection along one line crosses on each side of its
/// start. [measured] a line within delta of the skin crosses at most a handful.
constexpr int kMaxCellsAlongLine = 64;
/// A line through an edge or a vertex of a mixed cell meets it in one point,
/// and locate() may report a point within its tolerance of a wall in either
/// cell: the walk then steps past the wall again, each time 16 times farther,
/// at most this often (up to 16^8 wall steps, 4e-3 L). [derived] locate()'s
/// tolerance is 1e-9 L (skin/mixed_complex.h).
constexpr int kMaxWallRetries = 8;
constexpr double kWallRetryGrowth = 16;
/// Newton steps of pull_back() before it gives up. [measured] it converges
/// quadratically in a few steps from any point within rho of the skin.
constexpr int kMaxPullBackSteps = 100;
/// Distance to the skin (units of its length scale) that pull_back() accepts
/// after its last step when its tolerance was not met. [derived] a few units
/// in the last place of f / |grad f| at the skin's size.
constexpr double kPullBackFallback = 1e-11;

}  // namespace

SkinSurface::SkinSurface(std::vector<geometry::WeightedPoint> points, int threads) : points_(std::move(points)) {
  if (points_.empty()) throw InputError("", 0, "no weighted points (no atoms)");
  for (const auto& p : points_)
    if (!p.z.allFinite() || !std::isfinite(p.w)) throw InputError("", 0, "non-finite weighted point");
  rt_ = std::make_unique<geometry::RegularTriangulation>(points_);
  mc_ = std::make_unique<MixedComplex>(*rt_, threads);
}

SkinSample SkinSurface::sample(const Vec3& x, Index hint) const {
  SkinSample s;
  s.cell = mc_->locate(x, hint);
  s.f = mc_->f(s.cell, x);
  s.gradient = mc_->gradient(s.cell, x);
  s.rho = mc_->rho(s.cell, x);
  return s;
}

Vec3 SkinSurface::normal(const Vec3& x, Index hint) const { return sample(x, hint).gradient.normalized(); }

PrincipalCurvatures SkinSurface::curvatures(Index c, const Vec3& x) const {
  const MixedCell& m = mc_->cell(c);
  const double r = mc_->rho(c, x);
  const double k_mer = m.focus_weight / (2.0 * r * r * r);
  switch (m.dim) {
    case 0:
      return {1.0 / r, 1.0 / r};
    case 1:
      return {1.0 / r, k_mer};
    case 2:
      return {-1.0 / r, k_mer};
    default:
      return {-1.0 / r, -1.0 / r};
  }
}

double SkinSurface::distance_estimate(const Vec3& x, Index hint) const {
  const SkinSample s = sample(x, hint);
  return std::abs(s.f) / s.gradient.norm();
}

Index SkinSurface::atom_of(Index c, const Vec3& x) const {
  // The simplex, not the cell: the output asks for every vertex's atom after
  // the made cells have gone back, and the geometry is not read here.
  const CellSimplex& m = mc_->simplex(c);
  Index best = kInvalidIndex;
  double best_pow = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= m.dim; ++i) {
    const Index v = m.vertices[i];
    if (rt_->is_bounding(v)) continue;
    const double pw = geometry::power_distance(rt_->point(v), x);
    if (pw < best_pow) {
      best_pow = pw;
      best = v;
    }
  }
  return best;
}

// Projection Along a Line

namespace {

/// Roots of a t² + 2 b t + c = 0 in [lo, hi] (numerically stable form);
/// returns how many were written to r (sorted).
int quadratic_roots(double a, double b, double c, double lo, double hi, double r[2]) {
  int n = 0;
  double cand[2];
  int nc = 0;
  const double scale = std::max({std::abs(a), std::abs(b), 1e-300});
  if (std::abs(a) <= kLinearThreshold * scale) {
    if (b != 0) cand[nc++] = -c / (2 * b);
  } else {
    const double disc = b * b - a * c;
    if (disc < 0) return 0;
    const double sq = std::sqrt(disc);
    const double qv = -(b + std::copysign(sq, b));
    if (qv != 0) {
      cand[nc++] = qv / a;
      cand[nc++] = c / qv;
    } else {
      cand[nc++] = 0;  // b = 0 and disc = 0: double root at 0 (c = 0)
    }
  }
  for (int i = 0; i < nc; ++i)
    if (cand[i] >= lo && cand[i] <= hi) r[n++] = cand[i];
  if (n == 2 && r[0] > r[1]) std::swap(r[0], r[1]);
  return n;
}

}  // namespace

bool SkinSurface::project_along_line(const Vec3& q, const Vec3& n, double delta, Vec3& out, Index& cell) const {
  const MixedComplex& mc = *mc_;
  const double eta = kWallStep * mc.length_scale();
  // Parametric interval [lo, hi] of the line q + t n inside cell c.
  auto interval = [&](Index c, double& lo, double& hi) {
    lo = -std::numeric_limits<double>::infinity();
    hi = std::numeric_limits<double>::infinity();
    Index exit_hi = kInvalidIndex, exit_lo = kInvalidIndex;
    const std::span<const CellPlane> ps = mc.planes(c);
    const std::span<const Index> across = mc.neighbors(c);
    for (std::size_t i = 0; i < ps.size(); ++i) {
      const CellPlane& p = ps[i];
      const double dn = p.normal.dot(n);
      const double rhs = p.offset - p.normal.dot(q);
      if (dn > 0) {
        const double t = rhs / dn;
        if (t < hi) hi = t, exit_hi = across[i];
      } else if (dn < 0) {
        const double t = rhs / dn;
        if (t > lo) lo = t, exit_lo = across[i];
      }
    }
    return std::pair<Index, Index>{exit_lo, exit_hi};
  };
  // Roots of f_c(q + t n) on [lo, hi] ∩ [-delta, delta].
  auto roots_in = [&](Index c, double lo, double hi, double r[2]) {
    const Vec3 y = q - mc.cell(c).focus;
    const Mat3 A = mc.quadric_matrix(c);
    const Vec3 An = A * n;
    return quadratic_roots(n.dot(An), y.dot(An), mc.f(c, q), std::max(lo, -delta) - eta, std::min(hi, delta) + eta, r);
  };

  const Index c0 = mc.locate(q, cell);
  double best_t = std::numeric_limits<double>::infinity();
  Index best_c = kInvalidIndex;
  // Walk outwards from t = 0 in both directions, cell by cell; the first root
  // met on each side is that side's closest. The second side stops as soon
  // as it is no nearer to t = 0 than the first side's root (a root there
  // could not win: ties go to the first side).
  double lo0, hi0;
  const auto ex0 = interval(c0, lo0, hi0);
  for (int dir = +1; dir >= -1; dir -= 2) {
    Index c = c0;
    double lo = lo0, hi = hi0;
    auto ex = ex0;
    double r[2];
    for (int guard = 0; guard < kMaxCellsAlongLine; ++guard) {
      const double seg_lo = dir > 0 ? std::max(lo, 0.0) : lo;
      const double seg_hi = dir > 0 ? hi : std::min(hi, 0.0);
      if ((dir > 0 ? seg_lo : -seg_hi) - eta > std::abs(best_t)) break;
      const int nr = roots_in(c, seg_lo, seg_hi, r);
      if (nr > 0) {
        const double t = dir > 0 ? r[0] : r[nr - 1];
        if (std::abs(t) < std::abs(best_t)) best_t = t, best_c = c;
        break;
      }
      const double t_exit = dir > 0 ? hi : lo;
      if (std::abs(t_exit) >= delta || !std::isfinite(t_exit) || std::abs(t_exit) - eta > std::abs(best_t)) break;
      const Index next = dir > 0 ? ex.second : ex.first;
      if (next == kInvalidIndex) break;
      c = mc.locate(q + (t_exit + dir * eta) * n, next);
      ex = interval(c, lo, hi);
      // No progress (a cell the line meets in one point, or the cell it left):
      // step past the wall again, farther (kMaxWallRetries).
      double step = eta;
      for (int retry = 0; retry < kMaxWallRetries && (dir > 0 ? !(hi > t_exit) : !(lo < t_exit)); ++retry) {
        step *= kWallRetryGrowth;
        c = mc.locate(q + (t_exit + dir * step) * n, c);
        ex = interval(c, lo, hi);
      }
    }
  }
  if (best_c == kInvalidIndex) return false;
  out = q + best_t * n;
  cell = mc.locate(out, best_c);
  return true;
}

Vec3 SkinSurface::pull_back(const Vec3& x0, Index& cell, SkinSample* at_result, double tolerance) const {
  Vec3 x = x0;
  const double tol = tolerance * length_scale();
  for (int it = 0; it < kMaxPullBackSteps; ++it) {
    const SkinSample s = sample(x, cell);
    cell = s.cell;
    const double g2 = s.gradient.squaredNorm();
    if (g2 <= 0) break;
    const double dist = std::abs(s.f) / std::sqrt(g2);
    if (dist <= tol) {
      if (at_result) *at_result = s;
      return x;
    }
    x -= (s.f / g2) * s.gradient;
  }
  const SkinSample s = sample(x, cell);
  cell = s.cell;
  if (std::abs(s.f) / s.gradient.norm() <= kPullBackFallback * length_scale()) {
    if (at_result) *at_result = s;
    return x;
  }
  throw GeometryError("pull_back did not converge near (" + std::to_string(x0.x()) + ", " + std::to_string(x0.y()) +
                      ", " + std::to_string(x0.z()) + ")");
}

}  // namespace skinmesh::skin
