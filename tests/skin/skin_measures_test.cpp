// tests/skin/skin_measures_test.cpp: the skin's area and volume integrated over
// the exact patches (skin/skin_measures.h) against closed forms, against an
// independent integration of the definition for two balls (a surface of
// revolution), against a volume counted along lines from the skin function,
// for invariance under translation and thread count, and, summed window by
// window, against one loop over every cell; the areas per atom (atom_areas)
// against the profile cut at the power bisector, against the whole skin's
// area, and for symmetry, redundancy, translation and thread count.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "skin/skin_measures.h"
#include "tests/skin/skin_test_util.h"

using namespace skinmesh;
using geometry::WeightedPoint;

namespace {

/// Area and volume of the skin of two weighted points from the definition,
/// without the mixed complex: the skin is a surface of revolution about the
/// line of the centres. On that line (coordinate t, distance r from it) the
/// skin function is the minimum over λ in [0, 1] of the shrunk convex
/// combination's power distance,
///   g(λ) = (t - λd)² + r² - ((1-λ) w1 + λ (w2 - d²) + λ² d²) / 2,
/// a convex quadratic in λ. The profile r(t) (g = 0) is found by bisection on
/// n + 1 points; the volume is the trapezoid sum of π r² and the area the
/// surface of the polyline's frusta.
/// With `t_split`, the area is that of the part t <= t_split only (the
/// polyline cut there, r interpolated linearly).
std::pair<double, double> two_ball_profile_measures(double d, double w1, double w2, int n,
                                                    double t_split = std::numeric_limits<double>::infinity()) {
  const auto skin_f = [&](double t, double r) {
    const double A = 0.5 * d * d, B = -2 * t * d + 0.5 * (w1 - w2 + d * d), C = t * t + r * r - 0.5 * w1;
    const double l = std::clamp(-B / (2 * A), 0.0, 1.0);
    return A * l * l + B * l + C;
  };
  const double t0 = -std::sqrt(w1 / 2), t1 = d + std::sqrt(w2 / 2);
  const double rmax = std::sqrt(std::max(w1, w2));
  std::vector<double> ts(n + 1), rs(n + 1);
  for (int i = 0; i <= n; ++i) {
    const double t = t0 + (t1 - t0) * i / n;
    double lo = 0, hi = rmax;
    if (skin_f(t, 0) > 0) hi = 0;
    for (int k = 0; k < 200 && hi > 0; ++k) {
      const double m = 0.5 * (lo + hi);
      (skin_f(t, m) > 0 ? hi : lo) = m;
    }
    ts[i] = t, rs[i] = 0.5 * (lo + hi);
  }
  double area = 0, volume = 0;
  for (int i = 0; i < n; ++i) {
    const double dt = ts[i + 1] - ts[i], dr = rs[i + 1] - rs[i];
    volume += 0.5 * kPi * (rs[i] * rs[i] + rs[i + 1] * rs[i + 1]) * dt;
    if (ts[i + 1] <= t_split) {
      area += kPi * (rs[i] + rs[i + 1]) * std::hypot(dt, dr);
    } else if (ts[i] < t_split) {
      const double u = (t_split - ts[i]) / dt, r_split = rs[i] + u * dr;
      area += kPi * (rs[i] + r_split) * std::hypot(u * dt, u * dr);
    }
  }
  return {area, volume};
}

/// The enclosed volume counted along lines parallel to z through an n × n
/// grid of (x, y) cell centres: each line's length inside the body (f <= 0,
/// from SkinSurface::sample) by sampling and bisection. Independent of the
/// patch quadrature; first-order accurate at the silhouette.
double line_volume(const skin::SkinSurface& skin, Vec3 lo, Vec3 hi, int n) {
  const double hx = (hi.x() - lo.x()) / n, hy = (hi.y() - lo.y()) / n;
  const int samples = 200;
  const double hz = (hi.z() - lo.z()) / samples;
  double volume = 0;
  Index hint = kInvalidIndex;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = lo.x() + (i + 0.5) * hx, y = lo.y() + (j + 0.5) * hy;
      const auto f = [&](double z) {
        const skin::SkinSample s = skin.sample(Vec3(x, y, z), hint);
        hint = s.cell;
        return s.f;
      };
      double prev_z = lo.z(), prev_f = f(prev_z), inside_from = 0;
      REQUIRE(prev_f > 0);  // the box encloses the body
      for (int k = 1; k <= samples; ++k) {
        const double z = lo.z() + k * hz, fz = f(z);
        if ((prev_f > 0) != (fz > 0)) {
          double a = prev_z, b = z;
          for (int it = 0; it < 60; ++it) {
            const double m = 0.5 * (a + b);
            ((f(m) > 0) == (prev_f > 0) ? a : b) = m;
          }
          const double crossing = 0.5 * (a + b);
          if (prev_f > 0)
            inside_from = crossing;
          else
            volume += (crossing - inside_from) * hx * hy;
        }
        prev_z = z, prev_f = fz;
      }
    }
  return volume;
}

/// Two weighted points at distance d (Å) with weights w1, w2 (Å²), along a
/// generic direction so that the edge's hyperboloid is not axis-aligned.
struct TwoBalls {
  double d, w1, w2;
  const char* what;
  std::vector<WeightedPoint> points() const {
    const Vec3 axis(0.48, -0.6, 0.64), z1(0.1, 0.2, -0.3);
    return {{z1, w1}, {z1 + d * axis, w2}};
  }
};
const TwoBalls kTwoBalls[] = {{2.0248, 2 * 1.5 * 1.5, 2 * 1.2 * 1.2, "overlapping spheres"},
                              {3.0, 2 * 1.2 * 1.2, 2 * 1.0 * 1.0, "spheres apart, joined by a thin neck"},
                              {2.0, 2.0, 2.0, "the skin-math configuration two_balls: equal balls"}};

std::vector<WeightedPoint> moved(std::vector<WeightedPoint> p, const Vec3& by) {
  for (auto& q : p) q.z += by;
  return p;
}

}  // namespace

TEST_CASE("one ball: the area and volume of a sphere, wherever it is") {
  const double R = 1.7;
  for (const Vec3& centre : {Vec3(0, 0, 0), Vec3(0.3, -0.2, 0.1), Vec3(1000.5, -250.25, 77)}) {
    const skin::SkinSurface skin({{centre, 2 * R * R}});
    const skin::SkinMeasures m = skin::skin_measures(skin);
    CHECK(m.patch_cells == 1);
    CHECK(m.area == doctest::Approx(4 * kPi * R * R).epsilon(1e-12));
    // Far from the origin, x·n is large and cancels over the closed sphere.
    CHECK(m.volume == doctest::Approx(4.0 / 3.0 * kPi * R * R * R).epsilon(centre.norm() > 10 ? 1e-9 : 1e-12));
  }
}

TEST_CASE("two balls: the patch quadrature agrees with the profile of the definition") {
  for (const TwoBalls& c : kTwoBalls) {
    CAPTURE(c.what);
    const skin::SkinSurface skin(c.points());
    const skin::SkinMeasures m = skin::skin_measures(skin);
    const auto [area, volume] = two_ball_profile_measures(c.d, c.w1, c.w2, 40000);
    CHECK(m.patch_cells == 3);  // two sphere patches and the hyperboloid
    CHECK(m.area == doctest::Approx(area).epsilon(1e-7));
    CHECK(m.volume == doctest::Approx(volume).epsilon(1e-8));
  }
}

TEST_CASE("a cavity counts negative: the volume counted along lines agrees") {
  // Four balls about a void (the configuration tetrahedron_void) and random clusters.
  std::mt19937 rng(5);
  std::vector<std::vector<WeightedPoint>> inputs{test::tetrahedron_void(), test::random_points(12, 4.0, 1.5, 4.0, rng),
                                                 test::cube_corners(2.2)};
  for (const auto& pts : inputs) {
    const skin::SkinSurface skin(pts);
    const skin::SkinMeasures m = skin::skin_measures(skin);
    Vec3 lo = pts[0].z, hi = lo;
    double rmax = 0;
    for (const auto& p : pts) lo = lo.cwiseMin(p.z), hi = hi.cwiseMax(p.z), rmax = std::max(rmax, std::sqrt(p.w));
    lo -= Vec3::Constant(rmax), hi += Vec3::Constant(rmax);
    const double counted = line_volume(skin, lo, hi, 90);
    CHECK(m.volume == doctest::Approx(counted).epsilon(3e-3));
  }
  // The void really is there: the four balls' skin holds a cavity sphere, so
  // the enclosed volume is less than the same skin's volume without it.
  const skin::SkinSurface skin(test::tetrahedron_void());
  double cavity_area = 0, cavity_volume = 0;
  for (Index c = 0; c < skin.mixed_complex().num_cells(); ++c)
    if (skin.mixed_complex().cell(c).dim == 3 && !skin.mixed_complex().cell(c).bounding) {
      const skin::PatchMeasure p = skin::patch_measure(skin.mixed_complex(), c);
      cavity_area += p.area, cavity_volume += p.volume;
    }
  CHECK(cavity_area > 0);
  CHECK(cavity_volume < 0);  // about the origin, the void's centre: x·n < 0 inside
}

TEST_CASE("translation and thread count leave the measures unchanged") {
  std::mt19937 rng(11);
  const std::vector<WeightedPoint> pts = test::random_points(40, 8.0, 1.0, 5.0, rng);
  const skin::SkinSurface a(pts), b(moved(pts, Vec3(123.25, -77.5, 31.125)));
  const skin::SkinMeasures ma = skin::skin_measures(a, 1), mb = skin::skin_measures(b, 1);
  REQUIRE(ma.patch_cells > 10);
  CHECK(mb.patch_cells == ma.patch_cells);
  CHECK(mb.area == doctest::Approx(ma.area).epsilon(1e-10));
  // Summed over the closed skin, the origin's share z·∫n dA vanishes only if
  // every patch piece is there: a missing or doubled piece shows here.
  CHECK(mb.volume == doctest::Approx(ma.volume).epsilon(1e-9));
  const skin::SkinMeasures m2 = skin::skin_measures(a, 2);
  CHECK(m2.area == ma.area);
  CHECK(m2.volume == ma.volume);
}

TEST_CASE("summed window by window, the measures are the loop over every cell, and no cell stays made") {
  std::mt19937 rng(5);
  const std::vector<WeightedPoint> pts = test::random_points(3000, 60.0, 1.0, 6.0, rng);
  const skin::SkinSurface skin(pts, 2);
  const skin::MixedComplex& mc = skin.mixed_complex();
  REQUIRE(mc.num_cells() > 70000);  // more than one window of cells
  mc.release_made();
  const skin::SkinMeasures m = skin::skin_measures(skin, 2);
  CHECK(mc.made_bytes() == 0);  // every cell and its planes made without being kept
  double area = 0, volume = 0;
  Index patches = 0;
  for (Index c = 0; c < mc.num_cells(); ++c) {
    const skin::PatchMeasure p = skin::patch_measure(mc, c);
    area += p.area;
    volume += p.volume;
    patches += p.nonempty ? 1 : 0;
  }
  REQUIRE(patches > 1000);
  CHECK(m.patch_cells == patches);
  CHECK(m.area == area);  // the same sums in the same order: the same bits
  CHECK(m.volume == volume);
}

TEST_CASE("atom areas: one ball's sphere; two balls' profile cut at the power bisector") {
  const double R = 1.7;
  const std::vector<double> one = skin::atom_areas(std::vector<WeightedPoint>{{Vec3(5, -3, 2), 2 * R * R}});
  REQUIRE(one.size() == 1);
  CHECK(one[0] == doctest::Approx(4 * kPi * R * R).epsilon(1e-12));
  for (const TwoBalls& c : kTwoBalls) {
    CAPTURE(c.what);
    const std::vector<WeightedPoint> pts = c.points();
    const std::vector<double> areas = skin::atom_areas(pts);
    REQUIRE(areas.size() == 2);
    // power(x, 1) = power(x, 2) at t = (d² + w1 - w2) / (2d) along the axis.
    const double t_split = (c.d * c.d + c.w1 - c.w2) / (2 * c.d);
    const double first = two_ball_profile_measures(c.d, c.w1, c.w2, 40000, t_split).first;
    const double all = two_ball_profile_measures(c.d, c.w1, c.w2, 40000).first;
    CHECK(areas[0] == doctest::Approx(first).epsilon(1e-7));
    CHECK(areas[1] == doctest::Approx(all - first).epsilon(1e-7));
    CHECK(areas[0] + areas[1] == doctest::Approx(skin::skin_measures(pts).area).epsilon(1e-10));
    if (c.w1 == c.w2) CHECK(areas[0] == doctest::Approx(areas[1]).epsilon(1e-10));
  }
}

TEST_CASE("atom areas sum to the skin's area; symmetric atoms get equal areas, buried and redundant ones none") {
  std::mt19937 rng(7);
  for (const auto& pts : {test::random_points(40, 8.0, 1.0, 5.0, rng), test::tetrahedron_void(),
                          test::three_ball_ring(), test::random_points(300, 20.0, 1.0, 6.0, rng)}) {
    const skin::SkinSurface skin(pts);
    const std::vector<double> areas = skin::atom_areas(skin, 1);
    REQUIRE(areas.size() == pts.size());
    double sum = 0;
    for (double a : areas) {
      CHECK(a >= 0);
      sum += a;
    }
    CHECK(sum == doctest::Approx(skin::skin_measures(skin).area).epsilon(1e-9));
    CHECK(skin::atom_areas(skin, 2) == areas);  // bit for bit, whatever the threads
    const std::vector<double> far = skin::atom_areas(moved(pts, Vec3(1000.25, -500.5, 250.125)), 1);
    for (std::size_t i = 0; i < areas.size(); ++i) CHECK(far[i] == doctest::Approx(areas[i]).scale(sum).epsilon(1e-9));
  }
  // The eight corners of a cube: every atom the same share.
  const std::vector<double> cube = skin::atom_areas(test::cube_corners(2.2));
  for (double a : cube) CHECK(a == doctest::Approx(cube[0]).epsilon(1e-9));
  // A small ball inside a big one is redundant (no vertex of the regular
  // triangulation): no skin, no area; so is a ball buried among others.
  const std::vector<double> nested =
      skin::atom_areas(std::vector<WeightedPoint>{{Vec3(0, 0, 0), 8.0}, {Vec3(0.2, 0.1, 0), 0.5}});
  CHECK(nested[1] == 0);
  CHECK(nested[0] == doctest::Approx(4 * kPi * 4.0).epsilon(1e-12));
}

TEST_CASE("a patch's atom areas sum to its area, cell by cell") {
  std::mt19937 rng(3);
  const skin::SkinSurface skin(test::random_points(60, 10.0, 1.0, 5.0, rng));
  const skin::MixedComplex& mc = skin.mixed_complex();
  int split = 0;
  for (Index c = 0; c < mc.num_cells(); ++c) {
    const skin::PatchMeasure whole = skin::patch_measure(mc, c);
    const std::array<double, 4> parts = skin::patch_atom_areas(mc, c);
    const int dim = mc.simplex(c).dim;
    for (int i = dim + 1; i < 4; ++i) CHECK(parts[i] == 0);
    const double sum = parts[0] + parts[1] + parts[2] + parts[3];
    CHECK(sum == doctest::Approx(whole.area).scale(1.0).epsilon(1e-9));
    if (dim > 0 && whole.area > 0) ++split;
  }
  CHECK(split > 50);  // hyperboloid and concave patches were cut
}
