// tests/front/collision_net_test.cpp: the collision safety net (not in the
// paper): a contact joins two front parts that meet outside every protecting
// sphere; the fan-collision test agrees with a brute-force search of the fan
// points' neighbourhoods, and a fan that would reach the other bowl's front
// at a neck is joined to it instead.
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

namespace {

/// Brute force over every vertex, for the fan of m triangles at v (corner k):
/// the first fan point (in fan order) within collision_radius · r of a vertex
/// other than u, v, w (on the same sheet: normals within acos
/// min_normal_cosine), and the nearest such vertex (ties to the lower index);
/// invalid if none.
Vertex brute_force_fan_hit(const FrontState& s, Vertex v, const Corner& k, int m) {
  const double r = s.disc_radius(v), reach = s.opt.collision_radius * r;
  const Vec3 pv = s.mesh.position(v), n = s.normal[v];
  for (int i = 1; i < m; ++i) {
    const Vec3 q = pv + r * rotate(k.dw, n, i * k.angle / m);
    Vertex hit;
    double best = std::numeric_limits<double>::infinity();
    for (Vertex x : s.mesh.vertices()) {
      if (x == v || x == k.u || x == k.w || s.mesh.is_deleted(x) || s.mesh.is_isolated(x)) continue;
      if (s.normal[x].dot(n) <= s.opt.min_normal_cosine) continue;
      const double d = (s.mesh.position(x) - q).norm();
      if (d < reach && d < best) best = d, hit = x;
    }
    if (hit.is_valid()) return hit;
  }
  return Vertex();
}

/// True if some vertex lies within a relative 1e-6 of the distance
/// collision_radius · r from a fan point (where rounding may decide).
bool near_the_edge(const FrontState& s, Vertex v, const Corner& k, int m) {
  const double r = s.disc_radius(v), reach = s.opt.collision_radius * r;
  const Vec3 pv = s.mesh.position(v), n = s.normal[v];
  for (int i = 1; i < m; ++i) {
    const Vec3 q = pv + r * rotate(k.dw, n, i * k.angle / m);
    for (Vertex x : s.mesh.vertices())
      if (!s.mesh.is_deleted(x) && std::abs((s.mesh.position(x) - q).norm() - reach) < 1e-6 * reach) return true;
  }
  return false;
}

}  // namespace

TEST_SUITE("front operations") {

TEST_CASE("contact: without the saddle's hold, the safety net joins the two fronts at the neck") {
  Fixture fx({{Vec3(0, 0, 0), w_of(1.6, 1.4)}, {Vec3(4.5, 0.8, 0.3), w_of(1.6, 1.4)}});
  // Silence every saddle: nothing holds the fronts, which meet outside any
  // protecting sphere, the situation the safety net exists for.
  for (std::size_t i = 0; i < fx.ms.critical.size(); ++i)
    if (fx.ms.critical[i].kind == morse::CriticalKind::Saddle) fx.ms.live[i] = 0;
  FrontState s(fx.skin, fx.ms, fx.opt);
  create_initial_front(s);
  REQUIRE(front_loops(s) == 2);
  bool seen = false;
  for (int step = 0; step < 20000 && !seen; ++step) {
    const std::size_t contacts = s.stats.contacts, loops = front_loops(s);
    const long chi = euler(s);
    REQUIRE(departure_step(s));
    if (s.stats.contacts == contacts) continue;
    seen = true;
    CHECK(s.stats.contacts == contacts + 1);
    CHECK(front_loops(s) == loops - 1);  // the two bowls' fronts are one now
    CHECK(euler(s) == chi - 1);          // one ladder row: 3 edges, 2 faces
    check_partial_mesh(s, fx.skin);
  }
  CHECK(seen);
}

TEST_CASE("fan_collision: clear on a fresh bowl; for any radius it agrees with a brute-force search") {
  const std::vector<geometry::WeightedPoint> one_sphere{{Vec3(0.3, -0.2, 0.1), w_of(1.6, 1.4)}};
  Fixture fx(one_sphere);
  const Index c = fx.first_live(morse::CriticalKind::Minimum);
  REQUIRE(c != kInvalidIndex);
  std::size_t hits = 0, misses = 0;
  for (int tenth = 1; tenth <= 25; ++tenth) {
    fx.opt.collision_radius = 0.1 * tenth;
    CAPTURE(fx.opt.collision_radius);
    for (std::size_t i = 0; i < 6; ++i) {
      CAPTURE(i);
      FrontState s(fx.skin, fx.ms, fx.opt);
      creation(s, c);
      const auto loop = s.mesh.boundary_loops().front();
      const Vertex v = s.mesh.to_vertex(loop[i]);
      const Corner k = corner(s, v);
      const int m = static_cast<int>(std::ceil(k.angle / (fx.opt.fan_angle_deg * kDegree)));
      if (near_the_edge(s, v, k, m)) continue;
      const Vertex hit = brute_force_fan_hit(s, v, k, m);
      const std::size_t faces = s.mesh.n_faces();
      const bool collided = fan_collision(s, v, k, m);
      CHECK(collided == hit.is_valid());
      CHECK(s.stats.collisions == (collided ? 1u : 0u));
      if (!collided) {
        // Nothing changes: v is still free to creep.
        ++misses;
        CHECK(s.stats.deferred == 0);
        CHECK(s.deferrals[v] == 0);
        CHECK(s.state[v] == VState::Front);
        CHECK(s.mesh.n_faces() == faces);
        continue;
      }
      ++hits;
      if (!s.mesh.is_boundary(hit)) {
        // The bowl's centre: meshed surface, no contact possible: deferred.
        CHECK(s.stats.deferred == 1);
        CHECK(s.deferrals[v] == 1);
        CHECK(s.mesh.n_faces() == faces);
      } else {
        // Another rim vertex: joined by a contact (one ladder row), or deferred.
        CHECK(s.stats.contacts + s.stats.deferred == 1);
        CHECK(s.mesh.n_faces() == faces + 2 * s.stats.contacts);
      }
      check_partial_mesh(s, fx.skin);
    }
    // At the default radius every rim vertex is clear.
    if (tenth == 5) CHECK(hits == 0);
  }
  CHECK(hits > 0);
  CHECK(misses > 0);
}

TEST_CASE("fan_collision at a neck: with contacts off, a fan reaching the other bowl's front joins it instead") {
  Fixture fx({{Vec3(0, 0, 0), w_of(1.6, 1.4)}, {Vec3(4.5, 0.8, 0.3), w_of(1.6, 1.4)}});
  // As in the contact test, no saddle holds the fronts; and no contact is
  // looked for before the fan, so that the fans themselves reach the other front.
  for (std::size_t i = 0; i < fx.ms.critical.size(); ++i)
    if (fx.ms.critical[i].kind == morse::CriticalKind::Saddle) fx.ms.live[i] = 0;
  fx.opt.contact_radius = 0;
  Vertex departed;
  fx.opt.observer = [&departed](const front::SweepEvent& ev) {
    if (ev.op == front::SweepOperation::Creep) departed = ev.vertex;
  };
  FrontState s(fx.skin, fx.ms, fx.opt);
  create_initial_front(s);
  REQUIRE(front_loops(s) == 2);
  bool seen = false;
  for (int step = 0; step < 2000 && !seen; ++step) {
    const front::SweepStats before = s.stats;
    const std::size_t loops = front_loops(s), nv = s.mesh.vertices_size();
    const long chi = euler(s);
    departed = Vertex();
    REQUIRE(departure_step(s));
    check_partial_mesh(s, fx.skin);
    if (s.stats.collisions == before.collisions) {
      CHECK(s.stats.contacts == before.contacts);  // contacts are off but for the net
      continue;
    }
    seen = true;
    CHECK(s.stats.collisions == before.collisions + 1);
    REQUIRE(departed.is_valid());
    // The fan was not built: no new vertex, no creep counted.
    CHECK(s.stats.creeps == before.creeps);
    CHECK(s.mesh.vertices_size() == nv);
    // Here the other front is free, so the net joined the two fronts by a contact.
    CHECK(s.stats.contacts == before.contacts + 1);
    CHECK(front_loops(s) == loops - 1);
    CHECK(euler(s) == chi - 1);  // one ladder row: 3 edges, 2 faces
    // The ladder row has v at a corner; v itself stays on the (joined) front.
    std::size_t at_v = 0;
    for (geometry::Face f : s.mesh.faces(departed)) at_v += f.idx() >= s.mesh.faces_size() - 2;
    CHECK(at_v >= 1);
    CHECK(s.mesh.is_boundary(departed));
    CHECK(s.state[departed] != VState::Interior);
  }
  CHECK(seen);
}

}  // TEST_SUITE
