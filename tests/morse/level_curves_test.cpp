// tests/morse/level_curves_test.cpp: the level curves of the height function
// (the decomposed sweep's cut curves, papers/morse/level_curves.md) against
// circles of spheres and against a brute-force count of the curves from the
// skin function sampled on a fine grid of the cutting plane.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "morse/level_curves.h"
#include "morse/morse_smale_complex.h"
#include "skin/molecule_io.h"
#include "skin/skin_surface.h"
#include "tests/skin/skin_test_util.h"

using namespace skinmesh;

namespace {

/// The number of closed curves of F ∩ {e·x = c} by brute force: the body's
/// section {f < 0} sampled at the centres of a square grid of spacing g on
/// the plane (padded so that the border is outside); its boundary curves are
/// the section's components (4-connected) plus its holes (components of the
/// outside, 8-connected, that do not reach the border).
int brute_force_curve_count(const skin::SkinSurface& skin, const Vec3& e, double c, double g) {
  Vec3 u = e.unitOrthogonal(), v = e.cross(u);
  double lo_u = 1e300, hi_u = -1e300, lo_v = 1e300, hi_v = -1e300;
  for (const auto& p : skin.points()) {
    const double r = std::sqrt(std::max(p.w, 0.0));
    lo_u = std::min(lo_u, p.z.dot(u) - r), hi_u = std::max(hi_u, p.z.dot(u) + r);
    lo_v = std::min(lo_v, p.z.dot(v) - r), hi_v = std::max(hi_v, p.z.dot(v) + r);
  }
  lo_u -= 2 * g, lo_v -= 2 * g, hi_u += 2 * g, hi_v += 2 * g;
  const int nu = static_cast<int>(std::ceil((hi_u - lo_u) / g)), nv = static_cast<int>(std::ceil((hi_v - lo_v) / g));
  std::vector<char> inside(static_cast<std::size_t>(nu) * nv);
  Index hint = kInvalidIndex;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int ii = j % 2 ? nu - 1 - i : i;  // serpentine, so that the hint stays close
      const Vec3 q = (lo_u + (ii + 0.5) * g) * u + (lo_v + (j + 0.5) * g) * v + c * e;
      const auto s = skin.sample(q, hint);
      hint = s.cell;
      inside[static_cast<std::size_t>(j) * nu + ii] = s.f < 0;
    }
  std::vector<int> label(inside.size(), -1);
  auto flood = [&](int start, bool in, bool eight, bool& border) {
    std::vector<int> stack{start};
    label[start] = 1;
    border = false;
    while (!stack.empty()) {
      const int k = stack.back();
      stack.pop_back();
      const int i = k % nu, j = k / nu;
      if (i == 0 || j == 0 || i == nu - 1 || j == nv - 1) border = true;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          if ((di == 0 && dj == 0) || (!eight && di != 0 && dj != 0)) continue;
          const int a = i + di, b = j + dj;
          if (a < 0 || b < 0 || a >= nu || b >= nv) continue;
          const int kk = b * nu + a;
          if (label[kk] < 0 && static_cast<bool>(inside[kk]) == in) label[kk] = 1, stack.push_back(kk);
        }
    }
  };
  int count = 0;
  for (int k = 0; k < nu * nv; ++k) {
    if (label[k] >= 0) continue;
    bool border = false;
    const bool in = inside[k];
    flood(k, in, /*eight=*/!in, border);
    if (in || !border) ++count;
  }
  return count;
}

/// Every property a cut curve must have: samples on the skin and on the
/// plane, edges within the sampling window, oriented by n × e, and no two
/// curves (or two non-adjacent edges of one) closer than their spacing.
void check_curves(const skin::SkinSurface& skin, const Vec3& e, double c, const std::vector<morse::LevelCurve>& curves,
                  const morse::LevelCurveOptions& opt) {
  const double tol = 1e-9 * skin.length_scale();
  for (const auto& curve : curves) {
    const std::size_t n = curve.points.size();
    REQUIRE(n >= 3);
    REQUIRE(curve.rho.size() == n);
    REQUIRE(curve.cells.size() == n);
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& p = curve.points[i];
      const Vec3& q = curve.points[(i + 1) % n];
      const auto s = skin.sample(p, curve.cells[i]);
      CHECK(std::abs(s.f) / s.gradient.norm() < tol);
      CHECK(std::abs(e.dot(p) - c) < tol);
      CHECK(s.rho == doctest::Approx(curve.rho[i]).epsilon(1e-12));
      // The spacing in the metric of rho: about the target at most (the
      // sampler integrates 1 / rho along the fine polyline, this reads rho at
      // the two ends only: a few per cent apart where rho bends between
      // cells), at least three quarters of it.
      const double ratio = (q - p).norm() / (opt.spacing * 0.5 * (curve.rho[i] + curve.rho[(i + 1) % n]));
      CHECK(ratio <= 1.05);
      CHECK(ratio >= 0.7);
      // Oriented: the edge runs along n × e.
      CHECK((q - p).dot(s.gradient.normalized().cross(e)) > 0);
    }
  }
  // Distinct curves, and distinct parts of one curve, stay apart: a curve
  // traced twice, or two curves merged, would bring samples together.
  for (std::size_t a = 0; a < curves.size(); ++a)
    for (std::size_t b = a; b < curves.size(); ++b) {
      const auto& A = curves[a];
      const auto& B = curves[b];
      for (std::size_t i = 0; i < A.points.size(); ++i)
        for (std::size_t j = a == b ? i + 1 : 0; j < B.points.size(); ++j) {
          const std::size_t n = A.points.size();
          if (a == b && (j - i <= 2 || n - (j - i) <= 2)) continue;
          CHECK((A.points[i] - B.points[j]).norm() > 0.25 * opt.spacing * std::min(A.rho[i], B.rho[j]));
        }
    }
}

}  // namespace

TEST_SUITE("morse") {

TEST_CASE("level curves of one ball: the circle at every height, traced from the only minimum") {
  const double R = 1.7;
  const Vec3 centre(0.3, -0.2, 0.1);
  const skin::SkinSurface skin({{centre, 2 * R * R}});
  std::mt19937 rng(5);
  for (int k = 0; k < 5; ++k) {
    const Vec3 e = test::random_rotation(rng).col(0);
    const morse::MorseSmaleComplex ms = morse::build_morse_smale_complex(skin, e);
    REQUIRE(ms.critical.size() == 2);  // no saddle: the seed comes from the ascent
    for (double t : {-0.9, -0.4, 0.0, 0.55, 0.85}) {
      const double c = e.dot(centre) + t * R;
      CAPTURE(c);
      const auto curves = morse::level_curves(skin, ms, c);
      REQUIRE(curves.size() == 1);
      const double radius = R * std::sqrt(1 - t * t);
      CHECK(curves[0].length == doctest::Approx(2 * kPi * radius).epsilon(1e-3));
      for (const Vec3& p : curves[0].points) CHECK((p - (centre + t * R * e)).norm() == doctest::Approx(radius));
      // Samples at 0.185 rho = 0.185 R: ceil of the circle's length over that.
      CHECK(curves[0].points.size() == static_cast<std::size_t>(std::ceil(2 * kPi * radius / (0.185 * R) - 1e-9)));
      check_curves(skin, e, c, curves, {});
    }
    // Above the maximum and below the minimum: no curve.
    CHECK(morse::level_curves(skin, ms, e.dot(centre) + 1.01 * R).empty());
    CHECK(morse::level_curves(skin, ms, e.dot(centre) - 1.01 * R).empty());
  }
}

TEST_CASE("level curves of four balls apart: one curve each, every seed from an ascent") {
  std::mt19937 rng(7);
  for (int k = 0; k < 3; ++k) {
    const Vec3 e = test::random_rotation(rng).col(1);
    const Vec3 u = e.unitOrthogonal(), v = e.cross(u);
    // Centres in the plane normal to e, 3 Å apart at least: weighted balls of
    // radius sqrt(2) do not meet, so the skin is four unit spheres.
    const std::vector<geometry::WeightedPoint> balls{
        {3 * u, 2.0}, {-3 * u, 2.0}, {3 * v, 2.0}, {-3 * v + 0.25 * e, 2.0}};
    const skin::SkinSurface skin(balls);
    const morse::MorseSmaleComplex ms = morse::build_morse_smale_complex(skin, e);
    REQUIRE(ms.lines.empty());
    for (double c : {-0.5, 0.1, 0.6}) {
      CAPTURE(c);
      const auto curves = morse::level_curves(skin, ms, c);
      CHECK(curves.size() == 4);
      check_curves(skin, e, c, curves, {});
    }
  }
}

TEST_CASE("level curves: the count of a brute-force section, on rings, separate balls and crambin") {
  struct Case {
    std::string what;
    std::vector<geometry::WeightedPoint> points;
    std::size_t most = 1;  ///< the largest count some cut must show
  };
  std::vector<Case> cases;
  {
    // A ring of 12 balls (a torus: two curves where a cut crosses both sides).
    std::vector<geometry::WeightedPoint> ring;
    for (int i = 0; i < 12; ++i) {
      const double a = 2 * kPi * i / 12;
      ring.push_back({Vec3(4 * std::cos(a), 4 * std::sin(a), 0), 2 * 1.4 * 1.4});
    }
    cases.push_back({"a ring of 12 balls", ring, 2});
    // Three balls apart (three sphere-like components, no saddles) and a pair
    // joined by a neck.
    cases.push_back({"three balls apart and a joined pair",
                     {{Vec3(0, 0, 0), 2.0},
                      {Vec3(5, 0.5, 0), 2.5},
                      {Vec3(0, 5, 1), 1.5},
                      {Vec3(-6, 0, 0), 2 * 1.2 * 1.2},
                      {Vec3(-8.6, 0.3, 0), 2 * 1.2 * 1.2}}});
  }
  const skin::Molecule crambin = skin::read_molecule(std::string(SKINMESH_DATA) + "/crambin_1crn.pdb");
  cases.push_back({"crambin, probe 1.4", skin::weighted_points(crambin, 1.4)});
  cases.push_back({"crambin, probe 0", skin::weighted_points(crambin, 0.0), 2});

  std::mt19937 rng(26);
  for (const Case& cs : cases) {
    CAPTURE(cs.what);
    const skin::SkinSurface skin(cs.points);
    for (int k = 0; k < 2; ++k) {
      const Vec3 e = test::random_rotation(rng).col(2);
      const morse::MorseSmaleComplex ms = morse::build_morse_smale_complex(skin, e);
      double lo = 1e300, hi = -1e300;
      for (const auto& p : ms.critical) lo = std::min(lo, p.height), hi = std::max(hi, p.height);
      int tried = 0;
      std::size_t most = 0;
      // In each sixth of the height range, the height farthest from the
      // critical points (in units of their rho, past their protecting spheres).
      for (int w = 0; w < 6; ++w) {
        double c = 0, best = -1e300;
        for (int i = 0; i < 64; ++i) {
          const double h = lo + (hi - lo) * (w + (i + 0.5) / 64) / 6;
          if (const double cl = morse::cut_clearance(ms, h); cl > best) best = cl, c = h;
        }
        if (best <= 0) continue;
        ++tried;
        CAPTURE(c);
        const auto curves = morse::level_curves(skin, ms, c);
        const int expected = brute_force_curve_count(skin, e, c, 0.04);
        CHECK(static_cast<int>(curves.size()) == expected);
        check_curves(skin, e, c, curves, {});
        most = std::max(most, curves.size());
      }
      CHECK(tried >= 2);
      CHECK(most >= cs.most);  // the cuts do meet several curves where the input has them
    }
  }
}

}  // TEST_SUITE
