// tests/geometry/tangent_angles_test.cpp: the front's angle numerics
// (geometry/kernel/tangent_angles.h) against the exact atan2 angles: the
// coarse polynomial arctangent's accuracy, the pseudo-angles' monotonicity and
// slope bounds, and pseudo_exceeds never contradicting the angles.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/kernel/tangent_angles.h"

using namespace skinmesh;

namespace {

/// Uniform doubles in [0, 1) from a 64-bit linear congruential generator
/// (Knuth's MMIX constants): the same sequence on every platform.
struct Uniform {
  std::uint64_t seed;
  explicit Uniform(std::uint64_t s) : seed(s) {}
  double operator()() {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return double(seed >> 11) / double(1ull << 53);
  }
};

}  // namespace

TEST_SUITE("geometry") {

TEST_CASE("coarse_ccw_angle: within 2e-5 rad of ccw_angle for tangents of any length, 0 for a zero tangent") {
  // Random unit normals and tangent pairs at random lengths (1e-9 to 1e3),
  // plus the octant boundaries (angles k * 45°), against the exact angle.
  Uniform uniform(12345);
  double worst = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 n = Vec3(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5).normalized();
    const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    const double ta = 2 * kPi * uniform();
    const double tb = i % 10 == 0 ? ta + (i / 10 % 8) * kPi / 4 : 2 * kPi * uniform();
    const Vec3 a = std::cos(ta) * t1 + std::sin(ta) * t2, b = std::cos(tb) * t1 + std::sin(tb) * t2;
    const double la = std::pow(10.0, -9 + 12 * uniform()), lb = std::pow(10.0, -9 + 12 * uniform());
    const double exact = geometry::ccw_angle(a, b, n);
    const double coarse = geometry::coarse_ccw_angle(la * a, lb * b, n);
    CHECK(coarse >= 0);
    CHECK(coarse < 2 * kPi);
    // Angles near 0 and 2 pi are the same direction.
    const double d = std::abs(coarse - exact);
    worst = std::max(worst, std::min(d, 2 * kPi - d));
  }
  CHECK(worst < 2e-5);
  CHECK(geometry::coarse_ccw_angle(Vec3::Zero(), Vec3(1, 0, 0), Vec3(0, 0, 1)) == 0.0);
}

TEST_CASE(
    "pseudo_angle: monotone in the angle with slope between 1 and 2; pseudo_exceeds never contradicts the angles") {
  // Random tangent pairs plus the axis directions with signed zeros; for
  // every pair of directions the angle difference lies between the
  // pseudo-angle difference and twice it, and a certain verdict of
  // pseudo_exceeds agrees with the angles for tolerances from 1e-9 to 1.
  Uniform uniform(777);
  const Vec3 n(0, 0, 1), e(1, 0, 0);
  std::vector<Vec3> dirs = {Vec3(1, 0.0, 0), Vec3(1, -0.0, 0), Vec3(-1, 0.0, 0), Vec3(-1, -0.0, 0),
                            Vec3(0.0, 1, 0), Vec3(-0.0, 1, 0), Vec3(0.0, -1, 0), Vec3(-0.0, -1, 0)};
  for (int i = 0; i < 400; ++i) {
    const double t = 2 * kPi * uniform();
    dirs.push_back(Vec3(std::cos(t), std::sin(t), 0));
    dirs.push_back(Vec3(std::cos(t), std::sin(t) * 1e-9, 0).normalized());  // near the reference direction
  }
  for (const Vec3& a : dirs) {
    const double ta = geometry::ccw_angle(e, a, n);
    const double pa = geometry::pseudo_angle(e.cross(a).dot(n), e.dot(a));
    CHECK(pa >= 0);
    CHECK(pa <= 4);
    for (const Vec3& b : dirs) {
      const double tb = geometry::ccw_angle(e, b, n);
      const double pb = geometry::pseudo_angle(e.cross(b).dot(n), e.dot(b));
      if (pb >= pa) {
        CHECK(tb - ta >= (pb - pa) - 1e-12);
        CHECK(tb - ta <= 2 * (pb - pa) + 1e-12);
      }
      for (double tol : {1e-9, 1e-6, 1e-3, 0.1, 1.0}) {
        const geometry::PseudoVerdict verdict = geometry::pseudo_exceeds(pb, pa, tol);
        if (verdict != geometry::PseudoVerdict::Undecided)
          CHECK((verdict == geometry::PseudoVerdict::Holds) == (tb - ta > tol));
      }
    }
  }
  CHECK(geometry::pseudo_angle(0.0, 0.0) == 0.0);
  CHECK(std::isnan(geometry::pseudo_angle(std::nan(""), 1.0)));
  CHECK(geometry::pseudo_exceeds(std::nan(""), 0.0, 1e-6) == geometry::PseudoVerdict::Undecided);
}

TEST_CASE("coarse_atan2: within kCoarseAtan2Error of atan2 taken in [0, 2 pi), on every octant") {
  Uniform uniform(4242);
  double worst = 0;
  for (int i = 0; i < 100000; ++i) {
    const double t = 2 * kPi * uniform(), len = std::pow(10.0, -6 + 12 * uniform());
    const double y = len * std::sin(t), x = len * std::cos(t);
    double exact = std::atan2(y, x);
    if (exact < 0) exact += 2 * kPi;
    const double d = std::abs(geometry::coarse_atan2(y, x) - exact);
    worst = std::max(worst, std::min(d, 2 * kPi - d));
  }
  CHECK(worst < geometry::kCoarseAtan2Error);
  CHECK(worst > 0);  // a polynomial, not atan2
  CHECK(geometry::coarse_atan2(0.0, 0.0) == 0.0);
  CHECK(geometry::coarse_atan2(0.0, -1.0) == doctest::Approx(kPi));
}

}  // TEST_SUITE
