// tests/front/hole_filling_test.cpp: the hole filling (not in the paper) —
// small_hole and close_small_hole on the last loop of a sweep, the
// max-min-angle programme fill_hole_dp against a brute-force enumeration of
// every triangulation of the hole, and enlarge_hole / reopen_hole, which
// delete the faces around a hole and leave a valid partial mesh whose rim is
// the front.
// Through the sweep's state and operations (front/operations.h), on small
// synthetic skins; after every step the partial mesh keeps its invariants
// (tests/front/front_fixture.h).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "core/errors.h"
#include "geometry/kernel/angles.h"
#include "morse/critical_points.h"
#include "morse/morse_smale_complex.h"
#include "skin/skin_surface.h"
#include "tests/front/front_fixture.h"
#include "tests/skin/skin_test_util.h"

using namespace skinmesh;
using namespace skinmesh::front::detail;
using namespace skinmesh::test;

namespace {

std::vector<geometry::WeightedPoint> one_sphere() { return {{Vec3(0.3, -0.2, 0.1), w_of(1.6, 1.4)}}; }

bool live_vertex(const FrontState& s, Vertex v) { return !s.mesh.is_deleted(v) && !s.mesh.is_isolated(v); }

/// The front is the boundary: a vertex is on it iff its state is not Interior.
void check_front_is_boundary(const FrontState& s) {
  std::size_t bad = 0;
  for (Vertex v : s.mesh.vertices())
    if (live_vertex(s, v) && s.mesh.is_boundary(v) != (s.state[v] != VState::Interior)) ++bad;
  CHECK(bad == 0);
}

/// Sweeps one sphere until some front vertex bounds a small hole (before the
/// departure that would close it); the maximum is silenced so that no hold
/// stops the front below it. Returns that vertex, or an invalid one.
Vertex sweep_to_small_hole(FrontState& s) {
  create_initial_front(s);
  for (int step = 0; step < 2000; ++step) {
    if (!departure_step(s)) break;
    for (Vertex v : s.mesh.vertices())
      if (live_vertex(s, v) && s.mesh.is_boundary(v) && small_hole(s, v)) return v;
  }
  return Vertex();
}

struct SphereToSmallHole {
  Fixture fx{one_sphere()};
  explicit SphereToSmallHole() {
    const Index cmax = fx.first_live(morse::CriticalKind::Maximum);
    REQUIRE(cmax != kInvalidIndex);
    fx.ms.live[cmax] = 0;
  }
};

/// The vertices of the front loop through v, in boundary order.
std::vector<Vertex> loop_of(const FrontState& s, Vertex v) {
  std::vector<Vertex> poly;
  for (const auto h : s.mesh.boundary_loop(s.mesh.halfedge(v))) poly.push_back(s.mesh.to_vertex(h));
  return poly;
}

using Tri = std::array<std::size_t, 3>;

/// Visits every triangulation of the polygon 0..k-1, one at a time (no
/// dynamic programming): `pending` holds the chords (i, j) whose sub-polygon
/// i..j is still to be triangulated; each choice of apex m of the first one
/// adds the triangle (i, m, j). At each triangulation, `leaf` gets the minimum
/// of `quality` over its triangles.
template <class Quality, class Leaf>
void each_triangulation(std::vector<std::array<std::size_t, 2>>& pending, double q, const Quality& quality,
                        const Leaf& leaf) {
  if (pending.empty()) {
    leaf(q);
    return;
  }
  const auto [i, j] = pending.back();
  pending.pop_back();
  if (j == i + 1) {
    each_triangulation(pending, q, quality, leaf);
  } else {
    for (std::size_t m = i + 1; m < j; ++m) {
      pending.push_back({i, m});
      pending.push_back({m, j});
      each_triangulation(pending, std::min(q, quality(i, m, j)), quality, leaf);
      pending.pop_back();
      pending.pop_back();
    }
  }
  pending.push_back({i, j});
}

/// The Catalan number C(n): the number of triangulations of an (n + 2)-gon.
double catalan(std::size_t n) {
  double c = 1;
  for (std::size_t i = 0; i < n; ++i) c = c * 2 * (2 * static_cast<double>(i) + 1) / (static_cast<double>(i) + 2);
  return c;
}

/// The admissibility of a hole triangle as fill_hole_dp documents it: it faces
/// outwards at its three corners, fits their hole wedges, and its chords (edges
/// that are not hole edges) are not edges of the mesh yet. Its minimum angle,
/// or -1 if inadmissible.
double triangle_quality(const FrontState& s, const std::vector<Vertex>& poly, const Tri& t) {
  const std::size_t k = poly.size();
  const Vertex a = poly[t[0]], b = poly[t[1]], c = poly[t[2]];
  for (const auto& [x, y] : {std::array<std::size_t, 2>{t[0], t[1]}, {t[1], t[2]}, {t[0], t[2]}}) {
    const bool hole_edge = y == x + 1 || (x == 0 && y == k - 1);
    if (!hole_edge && s.mesh.find_edge(poly[x], poly[y]).is_valid()) return -1;
  }
  const Vec3 &pa = s.mesh.position(a), &pb = s.mesh.position(b), &pc = s.mesh.position(c);
  const Vec3 nt = (pb - pa).cross(pc - pa);
  for (Vertex x : {a, b, c})
    if (nt.dot(s.normal[x]) <= 0) return -1;
  if (!fits_at(s, a, b, c) || !fits_at(s, b, c, a) || !fits_at(s, c, a, b)) return -1;
  return geometry::min_angle(pa, pb, pc);
}

/// Fills the hole `poly` by fill_hole_dp and checks it against the brute force:
/// filled iff some triangulation is admissible, with the best minimum angle
/// over them, by admissible triangles. Returns true if it was filled.
bool check_dp_against_brute_force(FrontState& s, const skin::SkinSurface& skin, const std::vector<Vertex>& poly) {
  const std::size_t k = poly.size();
  CAPTURE(k);
  // The quality of every triangle (i < m < j) once, then every triangulation.
  std::vector<double> table(k * k * k, -1);
  std::vector<Tri> admissible;
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t m = i + 1; m < k; ++m)
      for (std::size_t j = m + 1; j < k; ++j)
        if ((table[(i * k + m) * k + j] = triangle_quality(s, poly, {i, m, j})) >= 0) admissible.push_back({i, m, j});
  double best = -1, count = 0;
  std::vector<std::array<std::size_t, 2>> pending{{0, k - 1}};
  each_triangulation(
      pending, std::numeric_limits<double>::infinity(),
      [&](std::size_t i, std::size_t m, std::size_t j) { return table[(i * k + m) * k + j]; },
      [&](double q) {
        best = std::max(best, q);
        ++count;
      });
  CHECK(count == catalan(k - 2));

  const std::size_t f0 = s.mesh.faces_size(), nf = s.mesh.n_faces(), seals = s.stats.seals, loops = front_loops(s);
  const long chi = euler(s);
  const bool filled = fill_hole_dp(s, poly);
  CHECK(filled == (best > 0));
  if (!filled) {
    CHECK(s.mesh.faces_size() == f0);
    CHECK(s.stats.seals == seals);
    return false;
  }
  CHECK(s.mesh.n_faces() == nf + k - 2);
  CHECK(s.stats.seals == seals + 1);
  CHECK(front_loops(s) == loops - 1);
  CHECK(euler(s) == chi + 1);  // a disc glued in
  double dp = std::numeric_limits<double>::infinity();
  for (std::size_t f = f0; f < s.mesh.faces_size(); ++f) {
    std::vector<std::size_t> idx;
    std::vector<Vec3> p;
    for (Vertex x : s.mesh.vertices(geometry::Face(static_cast<Index>(f)))) {
      idx.push_back(static_cast<std::size_t>(std::find(poly.begin(), poly.end(), x) - poly.begin()));
      p.push_back(s.mesh.position(x));
    }
    REQUIRE(idx.size() == 3);
    dp = std::min(dp, geometry::min_angle(p[0], p[1], p[2]));
    // Each triangle is one the brute force admits (its corners in hole order).
    std::rotate(idx.begin(), std::min_element(idx.begin(), idx.end()), idx.end());
    CHECK(std::find(admissible.begin(), admissible.end(), Tri{idx[0], idx[1], idx[2]}) != admissible.end());
  }
  CHECK(dp == doctest::Approx(best).epsilon(1e-12));
  for (Vertex x : poly) {
    CHECK(s.state[x] == VState::Interior);
    CHECK_FALSE(s.mesh.is_boundary(x));
  }
  check_partial_mesh(s, skin);
  return true;
}

}  // namespace

TEST_SUITE("front operations") {

TEST_CASE("small_hole tells the last loop of a sweep from a fresh bowl; close_small_hole closes it") {
  SphereToSmallHole t;
  FrontState s(t.fx.skin, t.fx.ms, t.fx.opt);
  {
    // A fresh bowl's rim is a loop of six close by, but around a disc: not a hole.
    FrontState bowl(t.fx.skin, t.fx.ms, t.fx.opt);
    create_initial_front(bowl);
    for (Vertex v : bowl.mesh.vertices())
      if (live_vertex(bowl, v) && bowl.mesh.is_boundary(v)) CHECK_FALSE(small_hole(bowl, v));
  }
  const Vertex v = sweep_to_small_hole(s);
  REQUIRE(v.is_valid());
  const std::vector<Vertex> poly = loop_of(s, v);
  REQUIRE(poly.size() <= static_cast<std::size_t>(t.fx.opt.small_hole_vertices));
  // What small_hole promises: a short loop, near v, whose hole angles add up
  // to less than k 180°.
  double sum = 0;
  for (Vertex x : poly) {
    CHECK((s.mesh.position(x) - s.mesh.position(v)).norm() <= t.fx.opt.small_hole_reach * s.disc_radius(v));
    sum += corner(s, x).angle;
  }
  CHECK(sum < static_cast<double>(poly.size()) * kPi);
  // With one vertex fewer allowed, the same loop is not small.
  t.fx.opt.small_hole_vertices = static_cast<int>(poly.size()) - 1;
  CHECK_FALSE(small_hole(s, v));
  t.fx.opt.small_hole_vertices = 7;

  check_partial_mesh(s, t.fx.skin);
  check_front_is_boundary(s);
  const std::size_t loops = front_loops(s), seals = s.stats.seals, nf = s.mesh.n_faces();
  const long chi = euler(s);
  close_small_hole(s, v);
  CHECK(front_loops(s) == loops - 1);
  CHECK(euler(s) == chi + 1);  // a disc glued in
  CHECK(s.stats.seals == seals + 1);
  CHECK(s.mesh.n_faces() == nf + poly.size() - 2);
  for (Vertex x : poly) CHECK(s.state[x] == VState::Interior);
  check_partial_mesh(s, t.fx.skin);
  check_front_is_boundary(s);
  // It was the last loop: the sphere is closed.
  CHECK(front_loops(s) == 0);
  CHECK(euler(s) == 2);
}

TEST_CASE("fill_hole_dp: the best minimum angle over every admissible triangulation, by brute force") {
  std::size_t compared = 0, filled = 0;
  SUBCASE("the rim of a fresh bowl: no triangulation faces outwards") {
    Fixture fx(one_sphere());
    FrontState s(fx.skin, fx.ms, fx.opt);
    create_initial_front(s);
    const auto loops = s.mesh.boundary_loops();
    REQUIRE(loops.size() == 1);
    std::vector<Vertex> poly;
    for (const auto h : loops[0]) poly.push_back(s.mesh.to_vertex(h));
    CHECK_FALSE(check_dp_against_brute_force(s, fx.skin, poly));
    ++compared;
  }
  SUBCASE("the small hole at the top of a sphere") {
    SphereToSmallHole t;
    FrontState s(t.fx.skin, t.fx.ms, t.fx.opt);
    const Vertex v = sweep_to_small_hole(s);
    REQUIRE(v.is_valid());
    filled += check_dp_against_brute_force(s, t.fx.skin, loop_of(s, v));
    ++compared;
    CHECK(filled == 1);
  }
  SUBCASE("the holes left for the seal") {
    for (int input = 0; input < 3; ++input) {
      CAPTURE(input);
      Fixture fx(input == 0   ? one_sphere()
                 : input == 1 ? test::three_ball_ring()
                              : std::vector<geometry::WeightedPoint>{{Vec3(0, 0, 0), w_of(1.6, 1.4)},
                                                                     {Vec3(4.5, 0.8, 0.3), w_of(1.6, 1.4)}});
      FrontState s(fx.skin, fx.ms, fx.opt);
      create_initial_front(s);
      while (departure_step(s) || release_saddles(s)) {
      }
      for (const auto& loop : s.mesh.boundary_loops()) {
        if (loop.size() > 16) continue;
        std::vector<Vertex> poly;
        for (const auto h : loop) poly.push_back(s.mesh.to_vertex(h));
        filled += check_dp_against_brute_force(s, fx.skin, poly);
        ++compared;
      }
    }
    CHECK(compared >= 5);
    CHECK(filled >= 3);
  }
}

TEST_CASE("enlarge_hole: the faces around a hole go, the rim is the front, and the seal closes it") {
  SphereToSmallHole t;
  FrontState s(t.fx.skin, t.fx.ms, t.fx.opt);
  const Vertex v = sweep_to_small_hole(s);
  REQUIRE(v.is_valid());
  const std::vector<Vertex> poly = loop_of(s, v);
  std::vector<geometry::Face> around;
  for (Vertex x : poly)
    for (geometry::Face f : s.mesh.faces(x))
      if (std::find(around.begin(), around.end(), f) == around.end()) around.push_back(f);
  const std::size_t nf = s.mesh.n_faces(), loops = front_loops(s);
  const long chi = euler(s);
  const geometry::Halfedge h = enlarge_hole(s, poly);
  REQUIRE(h.is_valid());
  CHECK(s.mesh.is_boundary(h));
  CHECK_NOTHROW(s.mesh.check_consistency());
  CHECK(s.mesh.n_faces() == nf - around.size());
  for (geometry::Face f : around) CHECK(s.mesh.is_deleted(f));
  for (Vertex x : poly) CHECK_FALSE(live_vertex(s, x));
  CHECK(front_loops(s) == loops);
  CHECK(euler(s) == chi);  // an annulus of faces removed
  for (const auto e : s.mesh.boundary_loop(h)) {
    const Vertex x = s.mesh.to_vertex(e);
    CHECK(s.state[x] == VState::Front);
    CHECK(s.mesh.boundary_gaps(x) == 1);
  }
  check_partial_mesh(s, t.fx.skin);
  check_front_is_boundary(s);
  seal_loop(s, h, 0);
  CHECK(front_loops(s) == 0);
  CHECK(euler(s) == 2);
  check_partial_mesh(s, t.fx.skin);
}

TEST_CASE("reopen_hole: the region around a hole goes back to the front, and the sweep closes it again") {
  SphereToSmallHole t;
  FrontState s(t.fx.skin, t.fx.ms, t.fx.opt);
  const Vertex v = sweep_to_small_hole(s);
  REQUIRE(v.is_valid());
  const std::vector<Vertex> poly = loop_of(s, v);
  const std::size_t nf = s.mesh.n_faces(), loops = front_loops(s);
  const long chi = euler(s);

  // A vertex re-opened too often refuses, and nothing changes.
  t.fx.opt.max_reopenings = 0;
  CHECK_FALSE(reopen_hole(s, poly));
  CHECK(s.mesh.n_faces() == nf);
  CHECK(s.stats.reopened_holes == 0);
  t.fx.opt.max_reopenings = 3;

  std::vector<Vertex> ring;  // the corners of the faces around the hole
  for (Vertex x : poly)
    for (Vertex y : s.mesh.vertices(x))
      if (std::find(poly.begin(), poly.end(), y) == poly.end() && std::find(ring.begin(), ring.end(), y) == ring.end())
        ring.push_back(y);
  REQUIRE(reopen_hole(s, poly));
  CHECK(s.stats.reopened_holes == 1);
  CHECK(s.mesh.n_faces() < nf);
  CHECK_NOTHROW(s.mesh.check_consistency());
  CHECK(front_loops(s) == loops);
  CHECK(euler(s) == chi);
  for (Vertex x : poly) CHECK_FALSE(live_vertex(s, x));
  std::size_t rim = 0;
  for (Vertex x : s.mesh.vertices()) {
    if (!live_vertex(s, x) || !s.mesh.is_boundary(x)) continue;
    ++rim;
    CHECK(s.state[x] == VState::Front);
    CHECK(s.mesh.boundary_gaps(x) == 1);  // no pinch
    CHECK(s.reopenings[x] == 1);
  }
  CHECK(rim >= ring.size());
  for (Vertex y : ring) CHECK((!live_vertex(s, y) || s.mesh.is_boundary(y)));
  check_partial_mesh(s, t.fx.skin);
  check_front_is_boundary(s);

  // A region with a corner on that rim is where the sweep would tangle again:
  // refused while a corner has been on max_reopenings rims, though the hole's
  // own vertex never was. And the faces a re-opening deletes never exceed
  // the faces left standing.
  {
    Vertex inner;  // a vertex off the rim with a rim vertex among its faces' corners
    for (Vertex y : s.mesh.vertices()) {
      if (!live_vertex(s, y) || s.reopenings[y] != 0) continue;
      for (Vertex x : s.mesh.vertices(y))
        if (s.reopenings[x] > 0) inner = y;
      if (inner.is_valid()) break;
    }
    REQUIRE(inner.is_valid());
    const std::size_t nf1 = s.mesh.n_faces();
    t.fx.opt.max_reopenings = 1;
    CHECK_FALSE(reopen_hole(s, {inner}));
    t.fx.opt.max_reopenings = 3;
    const std::size_t deleted = s.stats.reopened_faces;
    CHECK(deleted > 0);
    s.stats.reopened_faces = nf1;  // as if as many faces had been deleted as stand
    CHECK_FALSE(reopen_hole(s, {inner}));
    s.stats.reopened_faces = deleted;
    CHECK(s.mesh.n_faces() == nf1);
    CHECK(s.stats.reopened_holes == 1);
  }

  // The rim is queued: the sweep re-meshes the region and closes it.
  for (int step = 0; step < 500 && departure_step(s); ++step) {
  }
  CHECK(s.queue.empty());
  seal_all(s);
  CHECK(front_loops(s) == 0);
  CHECK(euler(s) == 2);
  check_partial_mesh(s, t.fx.skin);
}

}  // TEST_SUITE
