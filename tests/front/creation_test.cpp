// tests/front/creation_test.cpp: creation() (Figure 5) gives a bowl of six
// triangles and one front loop, its rim on the projected tangent circle.
// Through the sweep's state and operations (front/operations.h), on small
// synthetic skins; after every step the partial mesh keeps its invariants
// (tests/front/front_fixture.h).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/errors.h"
#include "morse/critical_points.h"
#include "morse/morse_smale_complex.h"
#include "skin/skin_surface.h"
#include "tests/front/front_fixture.h"
#include "tests/skin/skin_test_util.h"

using namespace skinmesh;
using namespace skinmesh::front::detail;
using namespace skinmesh::test;

TEST_SUITE("front operations") {

TEST_CASE("creation on a single sphere: six triangles and one front loop of six") {
  Fixture fx({{Vec3(0.3, -0.2, 0.1), w_of(1.6, 1.4)}});
  FrontState s(fx.skin, fx.ms, fx.opt);
  const Index c = fx.first_live(morse::CriticalKind::Minimum);
  REQUIRE(c != kInvalidIndex);
  creation(s, c);
  CHECK(s.mesh.n_faces() == 6);
  CHECK(s.mesh.n_vertices() == 7);
  const auto loops = s.mesh.boundary_loops();
  REQUIRE(loops.size() == 1);
  CHECK(loops[0].size() == 6);
  CHECK(euler(s) == 1);  // a disc
  check_partial_mesh(s, fx.skin);
  // The rim lies on the tangent circle of radius r = disc_factor · rho,
  // projected: r <= |p_i - p_0| <= r / cos(asin(r / rho)) on a sphere.
  const double rho = fx.ms.critical[c].rho, r = fx.opt.disc_factor * rho;
  const Vec3 p0 = fx.ms.critical[c].position;
  for (const auto h : loops[0]) {
    const double d = (s.mesh.position(s.mesh.to_vertex(h)) - p0).norm();
    CHECK(d >= r * (1 - 1e-9));
    CHECK(d <= r / std::cos(std::asin(r / rho)) * (1 + 1e-9));
    // Outside the bowl: each rim vertex sees 360° - 2 · 60° of hole.
    CHECK(corner(s, s.mesh.to_vertex(h)).angle / kDegree == doctest::Approx(240).epsilon(0.02));
  }
}

}  // TEST_SUITE
