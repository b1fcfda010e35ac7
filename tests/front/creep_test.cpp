// tests/front/creep_test.cpp: creep() in its two parts — plan_creep (the
// Figure 7 test and its verdict) and build_fan (the fan of Figure 6): the
// fan's size ceil(theta / fan angle), its points on the projected tangent
// circle at equal apex angles, the topology it keeps; the verdicts other
// than Build (wing, defer, stuck, hold, collision) and the m ± 1 rescue once
// the deferrals are used up; every creep of a sweep keeps the invariants.
// Through the sweep's state and operations (front/operations.h), on small
// synthetic skins; after every step the partial mesh keeps its invariants
// (tests/front/front_fixture.h).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
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

// One sphere of radius 3 (atom 1.6 + probe 1.4) centred off the origin.
const Vec3 kCentre(0.3, -0.2, 0.1);
constexpr double kRadius = 3.0;

std::vector<geometry::WeightedPoint> one_sphere() { return {{kCentre, w_of(1.6, 1.4)}}; }

/// The rim of the bowl made by creation() at the first live minimum.
std::vector<Vertex> bowl_rim(FrontState& s, const Fixture& fx) {
  const Index c = fx.first_live(morse::CriticalKind::Minimum);
  REQUIRE(c != kInvalidIndex);
  creation(s, c);
  const auto loops = s.mesh.boundary_loops();
  REQUIRE(loops.size() == 1);
  std::vector<Vertex> rim;
  for (const auto h : loops[0]) rim.push_back(s.mesh.to_vertex(h));
  return rim;
}

/// Where a fan point of v at angle t from d_w lands on the sphere: v + r
/// rot(d_w, t) moved along v's normal line onto the sphere (an oracle
/// independent of project_tangent: |q - C|² = R² + r² on the tangent plane).
Vec3 sphere_fan_point(const FrontState& s, Vertex v, const Corner& k, double t) {
  const Vec3 n = s.normal[v];
  const double r = s.disc_radius(v);
  const Vec3 q = s.mesh.position(v) + r * rotate(k.dw, n, t);
  return q - (kRadius - std::sqrt(kRadius * kRadius - r * r)) * n;
}

/// The faces of the fan at v, as build_fan lays them out: (v, fan[i-1],
/// fan[i]) for fan = w, the new points in order, u.
void check_fan_faces(const FrontState& s, Vertex v, const std::vector<Vertex>& fan) {
  for (std::size_t i = 1; i < fan.size(); ++i) {
    const geometry::Halfedge h = s.mesh.find_halfedge(v, fan[i - 1]);
    REQUIRE(h.is_valid());
    REQUIRE_FALSE(s.mesh.is_boundary(h));
    CHECK(s.mesh.to_vertex(s.mesh.next(h)) == fan[i]);
  }
}

/// The apex angles in T_v of consecutive fan spokes v -> fan[i-1], v -> fan[i].
std::vector<double> apex_angles(const FrontState& s, Vertex v, const std::vector<Vertex>& fan) {
  const Vec3 pv = s.mesh.position(v), n = s.normal[v];
  std::vector<double> a;
  for (std::size_t i = 1; i < fan.size(); ++i)
    a.push_back(
        ccw_angle(tangent_dir(pv, n, s.mesh.position(fan[i - 1])), tangent_dir(pv, n, s.mesh.position(fan[i])), n));
  return a;
}

}  // namespace

TEST_SUITE("front operations") {

TEST_CASE("creep at a bowl's rim: plan Build with ceil(theta / fan angle) triangles, a fan on the tangent circle") {
  for (const double fan_deg : {60.0, 72.0, 45.0}) {
    CAPTURE(fan_deg);
    Fixture fx(one_sphere());
    fx.opt.fan_angle_deg = fan_deg;
    FrontState probe(fx.skin, fx.ms, fx.opt);
    const std::size_t rim_size = bowl_rim(probe, fx).size();
    for (std::size_t i = 0; i < rim_size; ++i) {
      CAPTURE(i);
      FrontState s(fx.skin, fx.ms, fx.opt);
      const std::vector<Vertex> rim = bowl_rim(s, fx);
      const Vertex v = rim[i];
      const Corner k0 = corner(s, v);
      const int expected = static_cast<int>(std::ceil(k0.angle / (fan_deg * kDegree)));
      const std::size_t nv = s.mesh.vertices_size(), nf = s.mesh.n_faces();
      const CreepPlan plan = plan_creep(s, v);
      REQUIRE(plan.verdict == CreepVerdict::Build);
      CHECK(plan.triangles == expected);
      CHECK(plan.corner.u == k0.u);
      CHECK(plan.corner.w == k0.w);
      // The plan changes nothing.
      CHECK(s.mesh.vertices_size() == nv);
      CHECK(s.mesh.n_faces() == nf);
      CHECK(s.state[v] == VState::Front);
      CHECK(s.stats.creeps == 0);
      CHECK(s.stats.collisions == 0);
      CHECK(s.stats.deferred == 0);

      build_fan(s, v, plan);
      CHECK(s.stats.creeps == 1);
      CHECK(s.mesh.n_faces() == nf + static_cast<std::size_t>(expected));
      CHECK(s.mesh.vertices_size() == nv + static_cast<std::size_t>(expected - 1));
      CHECK(s.state[v] == VState::Interior);
      CHECK_FALSE(s.mesh.is_boundary(v));
      CHECK(euler(s) == 1);  // still a disc
      CHECK(front_loops(s) == 1);
      check_partial_mesh(s, fx.skin);

      std::vector<Vertex> fan{k0.w};
      for (std::size_t x = nv; x < s.mesh.vertices_size(); ++x) fan.push_back(Vertex(static_cast<Index>(x)));
      fan.push_back(k0.u);
      check_fan_faces(s, v, fan);
      // Figure 6: the apex angles are all theta / m; the new points lie on the
      // tangent circle of radius r projected onto the sphere along n_v.
      for (const double a : apex_angles(s, v, fan)) CHECK(a == doctest::Approx(k0.angle / expected).epsilon(1e-9));
      const double r = s.disc_radius(v), rho = s.rho[v];
      CHECK(rho == doctest::Approx(kRadius).epsilon(1e-9));
      for (std::size_t j = 1; j + 1 < fan.size(); ++j) {
        const double d = (s.mesh.position(fan[j]) - s.mesh.position(v)).norm();
        CHECK(d >= r * (1 - 1e-9));
        CHECK(d <= r / std::cos(std::asin(r / rho)) * (1 + 1e-9));
        CHECK((s.mesh.position(fan[j]) - kCentre).norm() == doctest::Approx(kRadius).epsilon(1e-9));
        CHECK(s.state[fan[j]] == VState::Front);
      }
    }
  }
}

TEST_CASE("every creep of a sweep builds a fan of equal apex angles and keeps chi, the loops and the invariants") {
  for (int input = 0; input < 2; ++input) {
    CAPTURE(input);
    Fixture fx(input == 0 ? test::three_ball_ring()
                          : std::vector<geometry::WeightedPoint>{{Vec3(0, 0, 0), w_of(1.6, 1.4)},
                                                                 {Vec3(4.5, 0.8, 0.3), w_of(1.6, 1.4)}});
    // The departure vertex of each creep, and the mesh's sizes right after it
    // (before the wings the step drains).
    Vertex creep_v;
    std::size_t creep_faces = 0, creep_vertices = 0;
    fx.opt.observer = [&](const front::SweepEvent& ev) {
      if (ev.op != front::SweepOperation::Creep) return;
      creep_v = ev.vertex;
      creep_faces = ev.mesh.faces_size();
      creep_vertices = ev.mesh.vertices_size();
    };
    FrontState s(fx.skin, fx.ms, fx.opt);
    create_initial_front(s);
    std::size_t fans = 0;
    for (int step = 0; step < 250; ++step) {
      const front::SweepStats before = s.stats;
      const std::size_t nv = s.mesh.vertices_size(), loops = front_loops(s);
      const long chi = euler(s);
      creep_v = Vertex();
      if (!departure_step(s)) break;
      check_partial_mesh(s, fx.skin);
      if (s.stats.creeps == before.creeps) continue;
      REQUIRE(s.stats.creeps == before.creeps + 1);
      REQUIRE(creep_v.is_valid());
      ++fans;
      // A fan (and the wings around it) neither changes the topology nor splits the front.
      if (s.stats.contacts == before.contacts && s.stats.held == before.held && s.stats.bridges == before.bridges) {
        CHECK(euler(s) == chi);
        CHECK(front_loops(s) == loops);
      }
      const Vertex v = creep_v;
      CHECK(s.state[v] == VState::Interior);
      CHECK_FALSE(s.mesh.is_boundary(v));
      // The fan: the last m faces before the wings, its m - 1 new points
      // between w and u (read off the first and the last fan face).
      const std::size_t m = creep_vertices - nv + 1;
      REQUIRE(creep_faces >= m);
      std::vector<Vertex> fan;
      for (std::size_t f = creep_faces - m; f < creep_faces; ++f) {
        std::vector<Vertex> c;
        for (Vertex x : s.mesh.vertices(geometry::Face(static_cast<Index>(f)))) c.push_back(x);
        REQUIRE(c.size() == 3);
        std::rotate(c.begin(), std::find(c.begin(), c.end(), v), c.end());
        REQUIRE(c[0] == v);
        if (fan.empty()) fan.push_back(c[1]);
        CHECK(c[1] == fan.back());
        fan.push_back(c[2]);
      }
      for (std::size_t j = 1; j + 1 < fan.size(); ++j) CHECK(fan[j].idx() == nv + j - 1);
      const std::vector<double> a = apex_angles(s, v, fan);
      for (const double x : a) CHECK(x == doctest::Approx(a.front()).epsilon(1e-9));
      // Unless the deferrals ran out (then m ± 1 may be taken), m = ceil(theta / 60°).
      if (s.deferrals[v] < fx.opt.max_deferrals) {
        CHECK(a.front() <= fx.opt.fan_angle_deg * kDegree * (1 + 1e-9));
        CHECK(a.front() * static_cast<double>(m) >
              fx.opt.fan_angle_deg * kDegree * static_cast<double>(m - 1) * (1 - 1e-9));
      }
      // The new points: at the tangent-disc radius from v in T_v (moved along n_v only).
      const Vec3 pv = s.mesh.position(v), n = s.normal[v];
      for (std::size_t j = 1; j + 1 < fan.size(); ++j) {
        Vec3 d = s.mesh.position(fan[j]) - pv;
        d -= d.dot(n) * n;
        CHECK(d.norm() == doctest::Approx(s.disc_radius(v)).epsilon(1e-9));
      }
    }
    CHECK(fans > 20);
  }
}

TEST_CASE("plan_creep: a front angle below wing_angle_deg gives the verdict Wing") {
  // As in wing_test.cpp: sweep without wings until some free front vertex has
  // a front angle below 85° that wing() would close.
  NarrowCorner nc;
  REQUIRE(nc.v.is_valid());
  Fixture& fx = nc.fx;
  FrontState& s = nc.s;
  const Vertex target = nc.v;
  const Corner k = corner(s, target);
  const std::size_t faces = s.mesh.n_faces(), nv = s.mesh.vertices_size(), loops = front_loops(s);
  const long chi = euler(s);
  const front::SweepStats before = s.stats;
  const CreepPlan plan = plan_creep(s, target);
  CHECK(plan.verdict == CreepVerdict::Wing);
  CHECK(s.mesh.n_faces() == faces + 1);
  CHECK(s.mesh.vertices_size() == nv);
  CHECK(s.state[target] == VState::Interior);
  CHECK(s.mesh.find_halfedge(k.w, k.u).is_valid());
  CHECK(s.stats.wings == before.wings + 1);
  CHECK(s.stats.creeps == before.creeps);
  CHECK(front_loops(s) == loops);
  CHECK(euler(s) == chi);
  check_partial_mesh(s, fx.skin);
}

TEST_CASE("plan_creep: a fan that cannot keep clear of w's other neighbour defers, then is stuck or rescued") {
  // On a fresh bowl the fan at a rim vertex v has m = 4 triangles. Its
  // points' distance to the second front neighbours w2, u2 is tested against
  // fan_clearance · r (Figure 7); the neighbours (240°) cannot be winged.
  Fixture fx(one_sphere());

  SUBCASE("clearance never met: Defer while deferrals are left") {
    fx.opt.fan_clearance = 100;
    FrontState s(fx.skin, fx.ms, fx.opt);
    const Vertex v = bowl_rim(s, fx)[2];
    const std::size_t faces = s.mesh.n_faces(), nv = s.mesh.vertices_size();
    const std::uint32_t stamp = s.stamp[v];
    for (int j = 1; j <= fx.opt.max_deferrals; ++j) {
      CAPTURE(j);
      const CreepPlan plan = plan_creep(s, v);
      CHECK(plan.verdict == CreepVerdict::Defer);
      CHECK(s.deferrals[v] == j);
      CHECK(s.stats.deferred == static_cast<std::size_t>(j));
      CHECK(s.stamp[v] == stamp + static_cast<std::uint32_t>(j));
      CHECK(s.state[v] == VState::Front);
      // The live queue entry of v: defer_step · r · j above its height.
      auto q = s.queue;
      int live = 0;
      for (; !q.empty(); q.pop())
        if (q.top().v == v.idx() && q.top().stamp == s.stamp[v]) {
          ++live;
          CHECK(q.top().h == doctest::Approx(s.height(v) + fx.opt.defer_step * s.disc_radius(v) * j));
        }
      CHECK(live == 1);
    }
    // Out of deferrals: no fan of m, m + 1, m + 2 or m - 1 triangles clears w2
    // and u2, so v is stuck (held by no critical point).
    const CreepPlan plan = plan_creep(s, v);
    CHECK(plan.verdict == CreepVerdict::Stuck);
    CHECK(s.state[v] == VState::Held);
    CHECK(s.holder_of(v) == kInvalidIndex);
    CHECK(s.stats.stuck == 1);
    CHECK(s.mesh.n_faces() == faces);
    CHECK(s.mesh.vertices_size() == nv);
    check_partial_mesh(s, fx.skin);
  }

  SUBCASE("no deferrals allowed: the first fan of m + 1, m + 2, m - 1 that clears is taken") {
    // Measure, on the sphere, how close each fan size brings its end points to
    // w2 and u2, and set the clearance between the m - 1 = 3 fan and the others.
    fx.opt.max_deferrals = 0;
    FrontState s(fx.skin, fx.ms, fx.opt);
    const Vertex v = bowl_rim(s, fx)[2];
    const Corner k = corner(s, v);
    const Vertex w2 = s.mesh.to_vertex(s.mesh.next(k.out)), u2 = s.mesh.from_vertex(s.mesh.prev(k.in));
    auto clearance = [&](int mm) {
      const Vec3 p1 = sphere_fan_point(s, v, k, k.angle / mm), pm = sphere_fan_point(s, v, k, k.angle * (mm - 1) / mm);
      return std::min((p1 - s.mesh.position(w2)).norm(), (pm - s.mesh.position(u2)).norm());
    };
    const int m = static_cast<int>(std::ceil(k.angle / (fx.opt.fan_angle_deg * kDegree)));
    REQUIRE(m == 4);
    const double others = std::max({clearance(m), clearance(m + 1), clearance(m + 2)});
    REQUIRE(clearance(m - 1) > others * 1.01);
    const double r = s.disc_radius(v);
    fx.opt.fan_clearance = (others + clearance(m - 1)) / 2 / r;
    const std::size_t nv = s.mesh.vertices_size();
    const CreepPlan plan = plan_creep(s, v);
    REQUIRE(plan.verdict == CreepVerdict::Build);
    CHECK(plan.triangles == m - 1);
    CHECK(s.stats.deferred == 0);
    build_fan(s, v, plan);
    CHECK(s.mesh.vertices_size() == nv + static_cast<std::size_t>(m - 2));
    std::vector<Vertex> fan{k.w};
    for (std::size_t x = nv; x < s.mesh.vertices_size(); ++x) fan.push_back(Vertex(static_cast<Index>(x)));
    fan.push_back(k.u);
    check_fan_faces(s, v, fan);
    for (const double a : apex_angles(s, v, fan)) CHECK(a == doctest::Approx(k.angle / (m - 1)).epsilon(1e-9));
    // The fan's end points where the oracle put them.
    CHECK((s.mesh.position(fan[1]) - sphere_fan_point(s, v, k, k.angle / (m - 1))).norm() < 1e-9);
    CHECK(euler(s) == 1);
    check_partial_mesh(s, fx.skin);
  }

  SUBCASE("clearance never met and no deferrals allowed: Stuck at once") {
    fx.opt.fan_clearance = 100;
    fx.opt.max_deferrals = 0;
    FrontState s(fx.skin, fx.ms, fx.opt);
    const Vertex v = bowl_rim(s, fx)[0];
    const CreepPlan plan = plan_creep(s, v);
    CHECK(plan.verdict == CreepVerdict::Stuck);
    CHECK(s.state[v] == VState::Held);
    CHECK(s.holder_of(v) == kInvalidIndex);
    CHECK(s.stats.deferred == 0);
    CHECK(s.stats.stuck == 1);
    CHECK(s.mesh.n_faces() == 6);
  }
}

TEST_CASE("plan_creep: a fan that would fold over a held neighbour joins its hold") {
  Fixture fx(one_sphere());
  fx.opt.fan_clearance = 100;  // every fan fails the Figure 7 test at both ends
  const Index cmax = fx.first_live(morse::CriticalKind::Maximum);
  REQUIRE(cmax != kInvalidIndex);
  FrontState s(fx.skin, fx.ms, fx.opt);
  const std::vector<Vertex> rim = bowl_rim(s, fx);
  const Vertex v = rim[1];
  const Corner k = corner(s, v);
  hold(s, k.w, cmax);
  REQUIRE(s.holder_of(k.w) == cmax);
  const CreepPlan plan = plan_creep(s, v);
  CHECK(plan.verdict == CreepVerdict::Hold);
  CHECK(s.state[v] == VState::Held);
  CHECK(s.holder_of(v) == cmax);
  CHECK(std::count(s.held[cmax].begin(), s.held[cmax].end(), v) == 1);
  CHECK(s.stats.held == 2);
  CHECK(s.stats.deferred == 0);
  CHECK(s.mesh.n_faces() == 6);
  // A free neighbour (the u side) is not a reason to hold: with w free again,
  // the same test defers instead.
  release_holds(s, cmax, /*requeue=*/false);
  CHECK(plan_creep(s, v).verdict == CreepVerdict::Defer);
}

TEST_CASE(
    "plan_creep: a fan point near another vertex is a Collision (deferred); without deferrals, the vertex is left for "
    "the seal (fallback) or the fan built anyway (no fallback)") {
  // On a fresh bowl, the fan's points at a rim vertex come within 1.75 r of
  // the bowl's centre (interior, so no contact can be made with it).
  Fixture fx(one_sphere());
  fx.opt.collision_radius = 1.9;
  // The plan at a rim vertex v of a fresh bowl under the fixture's options, and
  // its collision counted.
  auto rim_plan = [&fx](FrontState& s, Vertex& v) {
    v = bowl_rim(s, fx)[3];
    const CreepPlan plan = plan_creep(s, v);
    CHECK(s.stats.collisions == 1);
    return plan;
  };
  {
    FrontState s(fx.skin, fx.ms, fx.opt);
    Vertex v;
    CHECK(rim_plan(s, v).verdict == CreepVerdict::Collision);
    CHECK(s.stats.deferred == 1);
    CHECK(s.deferrals[v] == 1);
    CHECK(s.state[v] == VState::Front);
    CHECK(s.mesh.n_faces() == 6);
  }
  fx.opt.max_deferrals = 0;
  {
    // The bowl's centre is interior: the fan would cover meshed surface.
    FrontState s(fx.skin, fx.ms, fx.opt);
    Vertex v;
    CHECK(rim_plan(s, v).verdict == CreepVerdict::Collision);
    CHECK(s.stats.left_holes == 1);
    CHECK(s.state[v] == VState::Held);
    CHECK(s.holder_of(v) == kInvalidIndex);
    CHECK(s.mesh.n_faces() == 6);
  }
  {
    fx.opt.patch_fallback = false;
    FrontState s(fx.skin, fx.ms, fx.opt);
    Vertex v;
    const CreepPlan plan = rim_plan(s, v);
    CHECK(plan.verdict == CreepVerdict::Build);
    CHECK(s.stats.deferred == 0);
    build_fan(s, v, plan);
    CHECK(s.mesh.n_faces() == 6 + static_cast<std::size_t>(plan.triangles));
    check_partial_mesh(s, fx.skin);
  }
}

}  // TEST_SUITE
