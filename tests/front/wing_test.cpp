// tests/front/wing_test.cpp: wing() (Figure 7) closes a front angle below 90°
// without changing the topology of the partial mesh; after every departure no
// wing is left undone.
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

TEST_CASE("wing closes a front angle below 90°") {
  // Sweep with wings switched off until some free front vertex has a front
  // angle below 90°, then wing it with the paper's threshold.
  Fixture fx({{Vec3(0, 0, 0), w_of(1.6, 1.4)}, {Vec3(2.4, 0.3, 0.2), w_of(1.7, 1.4)}});
  fx.opt.wing_angle_deg = 0;
  fx.opt.forced_wing_angle_deg = 0;
  FrontState s(fx.skin, fx.ms, fx.opt);
  const Vertex target = sweep_to_narrow_corner(fx, s);
  REQUIRE(target.is_valid());
  fx.opt.wing_angle_deg = 90;
  const front::detail::Corner k = corner(s, target);
  // The new edge u-w is bounded by wing_max_edge_factor times the larger disc
  // radius of u and w: with the bound set just below its length the wing is
  // refused, and at the default it is taken.
  const double uw = (s.mesh.position(k.u) - s.mesh.position(k.w)).norm();
  const double r_uw = std::max(s.disc_radius(k.u), s.disc_radius(k.w));
  CHECK(uw <= fx.opt.wing_max_edge_factor * r_uw);
  const double default_factor = fx.opt.wing_max_edge_factor;
  fx.opt.wing_max_edge_factor = 0.99 * uw / r_uw;
  CHECK(std::string(wing_refusal(s, target, false)) == "the new edge u-w would be too long");
  fx.opt.wing_max_edge_factor = default_factor;
  const std::size_t faces = s.mesh.n_faces(), loops = front_loops(s);
  const long chi = euler(s);
  CHECK(wing(s, target, false));
  CHECK(s.mesh.n_faces() == faces + 1);
  CHECK(s.state[target] == VState::Interior);
  CHECK_FALSE(s.mesh.is_boundary(target));
  CHECK(s.mesh.find_halfedge(k.w, k.u).is_valid());  // the new front edge u -> w
  CHECK(s.mesh.is_boundary(s.mesh.find_halfedge(k.u, k.w)));
  CHECK(front_loops(s) == loops);
  CHECK(euler(s) == chi);
  CHECK(s.stats.wings == 1);
  CHECK(std::abs(fold_excess(s, k.u)) < 1 * kDegree);
  CHECK(std::abs(fold_excess(s, k.w)) < 1 * kDegree);
  // A second wing at the same place is refused: target is interior now.
  CHECK_FALSE(wing(s, target, false));
}

TEST_CASE("after every departure no free front angle below 90° is left that wing() would take") {
  Fixture fx(test::three_ball_ring());
  FrontState s(fx.skin, fx.ms, fx.opt);
  create_initial_front(s);
  while (departure_step(s))
    for (Vertex v : s.mesh.vertices())
      if (!s.mesh.is_deleted(v) && s.mesh.is_boundary(v) && s.state[v] == VState::Front)
        REQUIRE(wing_refusal(s, v, false) != nullptr);
  CHECK(s.stats.wings > 0);
}

}  // TEST_SUITE
