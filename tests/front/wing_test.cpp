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
#include <limits>
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
  NarrowCorner nc;
  REQUIRE(nc.v.is_valid());
  Fixture& fx = nc.fx;
  FrontState& s = nc.s;
  const Vertex target = nc.v;
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

TEST_CASE("a wing over a front vertex of another front part is refused, and so is the one-triangle fan") {
  // Fronts that meet outside a protecting sphere can put a vertex of one
  // front inside the triangle (v, w, u) over another's narrow corner (PDB
  // 3P3W at probe 0: 0.008 Å off its plane, just inside its new edge). Here a
  // small separate triangle is planted inside a narrow corner's triangle.
  NarrowCorner nc;
  REQUIRE(nc.v.is_valid());
  FrontState& s = nc.s;
  const Vertex v = nc.v;
  nc.fx.opt.forced_wing_angle_deg = 180;
  const Corner k = corner(s, v);
  REQUIRE(!covered_front_vertex(s, v, k.w, k.u).is_valid());
  const Vec3 pv = s.mesh.position(v), n = s.normal[v];
  const double t = 0.4 * std::min((s.mesh.position(k.w) - pv).norm(), (s.mesh.position(k.u) - pv).norm());
  const double half = k.angle / 2;
  const Vertex a = new_vertex(s, project_tangent(s, v, rotate(k.dw, n, half), t), kInvalidIndex);
  const Vertex b = new_vertex(s, project_tangent(s, v, rotate(k.dw, n, 0.8 * half), 1.3 * t), kInvalidIndex);
  const Vertex c = new_vertex(s, project_tangent(s, v, rotate(k.dw, n, 1.2 * half), 1.3 * t), kInvalidIndex);
  s.add_triangle(a, b, c);  // counter-clockwise about n: it faces outwards
  CHECK_NOTHROW(s.mesh.check_consistency());
  const Vertex covered = covered_front_vertex(s, v, k.w, k.u);
  CHECK(covered == a);  // the nearest to v
  CHECK(std::string(wing_refusal(s, v, false)) == "it would cover a front vertex");
  CHECK_FALSE(wing(s, v, false));
  // The departure at v would make the same triangle as a fan of one: the
  // collision net takes it instead (here a contact joins v's front to the
  // planted triangle's), and the triangle (v, w, u) is never made.
  CHECK(fan_collision(s, v, k, 1));
  CHECK(s.stats.collisions == 1);
  CHECK(s.stats.contacts == 1);
  CHECK_FALSE(s.mesh.find_halfedge(k.u, k.w).is_valid());
  CHECK_NOTHROW(s.mesh.check_consistency());
}

TEST_CASE("covered_front_vertex agrees with a brute-force scan at every front corner of a sweep") {
  Fixture fx(test::three_ball_ring());
  FrontState s(fx.skin, fx.ms, fx.opt);
  create_initial_front(s);
  std::size_t corners = 0, hits = 0;
  for (int step = 0; departure_step(s); ++step) {
    if (step % 25 != 0) continue;
    for (Vertex v : s.mesh.vertices()) {
      if (s.mesh.is_deleted(v) || s.mesh.is_isolated(v) || !s.mesh.is_boundary(v)) continue;
      const Corner k = corner(s, v);
      const Vec3 pv = s.mesh.position(v), pw = s.mesh.position(k.w), pu = s.mesh.position(k.u), n = s.normal[v];
      if ((pw - pv).cross(pu - pv).dot(n) <= 0) continue;  // no triangle to cover with
      Vertex expected;
      double best = std::numeric_limits<double>::infinity();
      const double reach = std::max((pw - pv).norm(), (pu - pv).norm());
      for (Vertex x : s.mesh.vertices()) {
        if (x == v || x == k.w || x == k.u || s.mesh.is_deleted(x) || s.mesh.is_isolated(x)) continue;
        if (s.state[x] == VState::Interior || s.normal[x].dot(n) <= fx.opt.min_normal_cosine) continue;
        const Vec3 px = s.mesh.position(x);
        if ((px - pv).norm() > reach) continue;
        auto left = [&](const Vec3& p, const Vec3& q) { return (q - p).cross(px - p).dot(n) > 0; };
        if (!left(pv, pw) || !left(pw, pu) || !left(pu, pv)) continue;
        const double d = (px - pv).squaredNorm();
        if (d < best || (d == best && x.idx() < expected.idx())) best = d, expected = x;
      }
      ++corners, hits += expected.is_valid();
      CHECK(covered_front_vertex(s, v, k.w, k.u) == expected);
    }
  }
  CHECK(corners > 100);
  MESSAGE(hits << " of " << corners << " corners' triangles cover a front vertex");
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
