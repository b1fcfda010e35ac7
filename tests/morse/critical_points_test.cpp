// tests/morse/critical_points_test.cpp: analytic critical points and the Morse
// count #min - #saddle + #max = chi(skin) = 2 chi(K0) (skin-math §5, §10).
#include <doctest/doctest.h>

#include <random>

#include "morse/critical_points.h"
#include "skin/dual_complex.h"
#include "tests/skin/skin_test_util.h"

using namespace skinmesh;
using morse::CriticalKind;

TEST_SUITE("morse") {

TEST_CASE("two balls, e = y: the critical points of examples.txt") {
  skin::SkinSurface skin(test::two_balls());
  const auto cps = morse::critical_points(skin, Vec3(0, 1, 0));
  const auto m = morse::count_critical_points(cps);
  CHECK(m.minima == 2);
  CHECK(m.saddles == 2);
  CHECK(m.maxima == 2);
  auto has = [&](CriticalKind k, Vec3 p) {
    for (const auto& c : cps)
      if (c.kind == k && (c.position - p).norm() < 1e-9) return true;
    return false;
  };
  CHECK(has(CriticalKind::Maximum, Vec3(0, 1, 0)));
  CHECK(has(CriticalKind::Maximum, Vec3(2, 1, 0)));
  CHECK(has(CriticalKind::Minimum, Vec3(0, -1, 0)));
  CHECK(has(CriticalKind::Minimum, Vec3(2, -1, 0)));
  CHECK(has(CriticalKind::Saddle, Vec3(1, std::sqrt(0.5), 0)));
  CHECK(has(CriticalKind::Saddle, Vec3(1, -std::sqrt(0.5), 0)));
  // Every critical point is on the skin with normal ±e.
  for (const auto& c : cps) {
    const auto s = skin.sample(c.position, c.cell);
    CHECK(std::abs(s.f) < 1e-12);
    CHECK(std::abs(std::abs(s.gradient.normalized().y()) - 1.0) < 1e-12);
  }
  // Upper saddle of a neck: the meridian (towards the balls, along x) ascends.
  for (const auto& c : cps)
    if (c.kind == CriticalKind::Saddle && c.position.y() > 0) {
      CHECK(std::abs(c.ascent.x()) == doctest::Approx(1.0));
      CHECK(std::abs(c.descent.z()) == doctest::Approx(1.0));
    }
}

TEST_CASE("steepest directions raise and lower the height") {
  std::mt19937 rng(11);
  auto cfg = test::random_points(10, 4.0, 0.8, 2.5, rng);
  skin::SkinSurface skin(cfg);
  const Vec3 e = morse::default_height_direction();
  int saddles = 0;
  for (const auto& c : morse::critical_points(skin, e)) {
    if (c.kind != CriticalKind::Saddle) continue;
    ++saddles;
    const double h = 1e-3 * c.rho;
    for (int sg = -1; sg <= 1; sg += 2) {
      Index cell = c.cell;
      const Vec3 up = skin.pull_back(c.position + sg * h * c.ascent, cell);
      const Vec3 dn = skin.pull_back(c.position + sg * h * c.descent, cell);
      CHECK(e.dot(up) > c.height);
      CHECK(e.dot(dn) < c.height);
    }
  }
  CHECK(saddles > 0);
}

TEST_CASE("Morse count equals 2 chi(K0) for several directions and configurations") {
  const unsigned seed = 99;
  INFO("seed = " << seed);
  std::mt19937 rng(seed);
  struct Case {
    const char* name;
    std::vector<geometry::WeightedPoint> pts;
    int expected_chi;  // designed topology, -1000 if not designed
  };
  std::vector<Case> cases = {
      {"two balls", test::two_balls(), 2},
      {"tetrahedron void", test::tetrahedron_void(), 4},
      {"three-ball ring", test::three_ball_ring(), 0},
      {"cube corners (Figure 4)", test::cube_corners(1.4), -1000},
      {"cube corners, closed", test::cube_corners(2.2), -1000},
      {"random 20", test::random_points(20, 6.0, 0.5, 2.5, rng), -1000},
      {"random 30", test::random_points(30, 7.0, 0.5, 2.5, rng), -1000},
  };
  for (const auto& cs : cases) {
    INFO(cs.name);
    skin::SkinSurface skin(cs.pts);
    const auto topo = skin::dual_complex_topology(skin.mixed_complex());
    if (cs.expected_chi != -1000) CHECK(topo.euler_skin() == cs.expected_chi);
    std::vector<Vec3> dirs = {morse::default_height_direction(), Vec3(0, 0.6, 0.8)};
    for (int i = 0; i < 4; ++i) dirs.push_back(test::random_rotation(rng) * Vec3(0, 1, 0));
    for (const Vec3& e : dirs) {
      const auto m = morse::count_critical_points(morse::critical_points(skin, e));
      CHECK(m.euler() == topo.euler_skin());
      CHECK(m.minima >= topo.components());
      CHECK(m.maxima >= topo.components());
    }
  }
}

TEST_CASE("three-ball ring, e = (0, .6, .8): 3 minima, 6 saddles, 3 maxima") {
  skin::SkinSurface skin(test::three_ball_ring());
  const auto m = morse::count_critical_points(morse::critical_points(skin, Vec3(0, 0.6, 0.8)));
  CHECK(m.minima == 3);
  CHECK(m.saddles == 6);
  CHECK(m.maxima == 3);
}

TEST_CASE("tetrahedron void, e = y: 3 minima, 2 saddles, 3 maxima") {
  skin::SkinSurface skin(test::tetrahedron_void());
  const auto m = morse::count_critical_points(morse::critical_points(skin, Vec3(0, 1, 0)));
  CHECK(m.minima == 3);
  CHECK(m.saddles == 2);
  CHECK(m.maxima == 3);
}

}  // TEST_SUITE
