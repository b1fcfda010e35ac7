// tests/front/operations_test.cpp: each operation of the sweep on its own, on
// small synthetic skins, through the sweep's private interface
// (front/sweep_internal.h): creation() gives a bowl of six triangles and one
// front loop; wing() closes a front angle below 90°; bridge() changes the
// number of front loops by one (two loops merge below a saddle, one splits
// above it) and the Euler characteristic by -1; seal() closes a hole; a
// contact of the safety net joins two front parts. After every step the
// partial mesh must keep its invariants: faces outward, vertices on the skin,
// no fold in any tangent plane.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "front/operations.h"
#include "core/errors.h"
#include "morse/critical_points.h"
#include "morse/morse_smale_complex.h"
#include "skin/skin_surface.h"
#include "tests/skin/skin_test_util.h"

using namespace skinmesh;
using front::detail::FrontState;
using namespace front::detail;
using front::detail::VState;
using geometry::Vertex;

namespace {

double w_of(double r, double probe) { return 2 * (r + probe) * (r + probe); }

/// A skin with its Morse–Smale complex, kept alive for a Sweep.
struct Fixture {
  skin::SkinSurface skin;
  morse::MorseSmaleComplex ms;
  front::SweepOptions opt;
  explicit Fixture(std::vector<geometry::WeightedPoint> pts, Vec3 e = morse::default_height_direction())
      : skin(std::move(pts)), ms(morse::build_morse_smale_complex(skin, e)) {}
  Index first_live(morse::CriticalKind kind) const {
    for (std::size_t i = 0; i < ms.critical.size(); ++i)
      if (ms.live[i] && ms.critical[i].kind == kind) return static_cast<Index>(i);
    return kInvalidIndex;
  }
};

/// Number of boundary loops (front polygons) of the partial mesh.
std::size_t front_loops(const FrontState& s) { return s.mesh.boundary_loops().size(); }

/// V - E + F of the partial mesh (isolated and deleted vertices excluded).
long euler(const FrontState& s) {
  const auto& m = s.mesh;
  long v = 0;
  for (Vertex x : m.vertices())
    if (!m.is_deleted(x) && !m.is_isolated(x)) ++v;
  return v - static_cast<long>(m.n_edges()) + static_cast<long>(m.n_faces());
}

/// The invariants of a partial mesh of the skin: every vertex on the skin,
/// every face outward at its three corners, no fold at any vertex.
void check_partial_mesh(const FrontState& s, const skin::SkinSurface& skin) {
  const auto& m = s.mesh;
  std::size_t far = 0, inward = 0, folded = 0;
  for (Vertex v : m.vertices()) {
    if (m.is_deleted(v) || m.is_isolated(v)) continue;
    const skin::SkinSample smp = skin.sample(m.position(v), kInvalidIndex);
    if (std::abs(smp.f) / smp.gradient.norm() > 1e-9) ++far;
    if (std::abs(fold_excess(s, v)) > 1 * kDegree) ++folded;
  }
  for (geometry::Face f : m.faces()) {
    if (m.is_deleted(f)) continue;
    std::array<Vertex, 3> c{};
    int i = 0;
    for (Vertex v : m.vertices(f)) c[i++] = v;
    const Vec3 nt = (m.position(c[1]) - m.position(c[0])).cross(m.position(c[2]) - m.position(c[0]));
    for (Vertex v : c)
      if (nt.dot(s.normal[v]) <= 0) ++inward;
  }
  CHECK(far == 0);
  CHECK(inward == 0);
  CHECK(folded == 0);
}

}  // namespace

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

TEST_CASE("wing closes a front angle below 90°") {
  // Sweep with wings switched off until some free front vertex has a front
  // angle below 90°, then wing it with the paper's threshold.
  Fixture fx({{Vec3(0, 0, 0), w_of(1.6, 1.4)}, {Vec3(2.4, 0.3, 0.2), w_of(1.7, 1.4)}});
  fx.opt.wing_angle_deg = 0;
  fx.opt.forced_wing_angle_deg = 0;
  FrontState s(fx.skin, fx.ms, fx.opt);
  create_initial_front(s);
  Vertex target;
  for (int step = 0; step < 400 && !target.is_valid(); ++step) {
    REQUIRE(departure_step(s));
    for (Vertex v : s.mesh.vertices())
      if (!s.mesh.is_deleted(v) && s.mesh.is_boundary(v) && s.state[v] == VState::Front &&
          corner(s, v).angle < 85 * kDegree) {
        fx.opt.wing_angle_deg = 90;  // the sweep reads its options by reference
        if (wing_refusal(s, v, false) == nullptr) target = v;
        fx.opt.wing_angle_deg = 0;
        if (target.is_valid()) break;
      }
  }
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

TEST_CASE("bridge: two loops merge below the neck's saddle, one splits above it; chi drops by one") {
  Fixture fx({{Vec3(0, 0, 0), w_of(1.6, 1.4)}, {Vec3(4.5, 0.8, 0.3), w_of(1.6, 1.4)}});
  REQUIRE(fx.ms.live_count().saddles == 2);
  REQUIRE(fx.ms.live_count().minima == 2);
  FrontState s(fx.skin, fx.ms, fx.opt);
  create_initial_front(s);
  CHECK(front_loops(s) == 2);
  std::vector<long> loop_changes;
  for (;;) {
    const std::size_t bridges = s.stats.bridges, loops = front_loops(s);
    const long chi = euler(s);
    if (!departure_step(s)) break;
    if (s.stats.bridges == bridges) continue;
    REQUIRE(s.stats.bridges == bridges + 1);
    loop_changes.push_back(static_cast<long>(front_loops(s)) - static_cast<long>(loops));
    CHECK(euler(s) == chi - 1);  // a 1-handle: a ladder adds 2(k-1) vertices, 4k-1 edges, 2k faces
    check_partial_mesh(s, fx.skin);
  }
  // Index-1 critical points: the lower saddle joins the two bowls' fronts, the
  // upper one splits the front around the neck into two caps.
  CHECK(loop_changes == std::vector<long>{-1, +1});
  CHECK(s.stats.released == 0);
}

TEST_CASE("seal closes each hole left at the maxima; the mesh is closed with chi = 2") {
  Fixture fx({{Vec3(0, 0, 0), w_of(1.6, 1.4)}, {Vec3(4.5, 0.8, 0.3), w_of(1.6, 1.4)}});
  FrontState s(fx.skin, fx.ms, fx.opt);
  create_initial_front(s);
  while (departure_step(s) || release_saddles(s)) {
  }
  check_partial_mesh(s, fx.skin);
  std::size_t loops = front_loops(s);
  REQUIRE(loops >= 1);
  while (loops > 0) {
    const long chi = euler(s);
    const std::size_t seals = s.stats.seals;
    seal_loop(s, s.mesh.boundary_loops().front().front(), fx.opt.max_hole_enlargements);
    CHECK(front_loops(s) == loops - 1);
    CHECK(euler(s) == chi + 1);  // a disc glued in
    CHECK(s.stats.seals == seals + 1);
    loops = front_loops(s);
  }
  check_partial_mesh(s, fx.skin);
  CHECK(euler(s) == 2);
  for (Vertex v : s.mesh.vertices())
    if (!s.mesh.is_deleted(v)) CHECK(s.state[v] == VState::Interior);
}

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

TEST_CASE("debugging aids: the trace names the operations, max_steps stops and dumps, paranoid passes") {
  Fixture fx({{Vec3(0, 0, 0), w_of(1.6, 1.4)}, {Vec3(4.5, 0.8, 0.3), w_of(1.6, 1.4)}});
  std::vector<std::string> lines;
  fx.opt.trace = [&lines](const std::string& line) { lines.push_back(line); };
  fx.opt.paranoid = true;
  const front::SweepResult res = front::sweep_mesh(fx.skin, fx.ms, fx.opt);
  auto traced = [&](const std::string& word) {
    return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.rfind(word, 0) == 0; });
  };
  CHECK(traced("hold v"));
  CHECK(traced("bridge saddle"));
  CHECK(traced("seal loop of"));
  CHECK(res.stats.bridges == 2);
  CHECK(res.mesh.boundary_loops().empty());

  const std::string dump = (std::filesystem::temp_directory_path() / "skinmesh_max_steps_dump.ply").string();
  front::SweepOptions stop;
  stop.max_steps = 5;
  stop.dump_path = dump;
  std::filesystem::remove(dump);
  CHECK_THROWS_AS(front::sweep_mesh(fx.skin, fx.ms, stop), TopologyError);
  CHECK(std::filesystem::exists(dump));
  std::filesystem::remove(dump);
}

TEST_CASE("a tangent-disc factor outside the window of C and Q is refused") {
  Fixture fx({{Vec3(0, 0, 0), w_of(1.6, 1.4)}});
  fx.opt.disc_factor = 0.25;  // above 0.2077
  CHECK_THROWS_AS(front::sweep_mesh(fx.skin, fx.ms, fx.opt), std::invalid_argument);
  fx.opt.disc_factor = 0.1;  // below 0.1074
  CHECK_THROWS_AS(front::sweep_mesh(fx.skin, fx.ms, fx.opt), std::invalid_argument);
}

}  // TEST_SUITE
