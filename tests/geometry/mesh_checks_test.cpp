// tests/geometry/mesh_checks_test.cpp: the mesh verifier (geometry/check/mesh_checks)
// on good meshes with known invariants (icosahedron, torus, spheres) and on
// meshes broken in one known way each; the grid broad phase against brute force.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "geometry/check/mesh_checks.h"
#include "geometry/kernel/triangle_intersection.h"
#include "tests/geometry/test_meshes.h"

using skinmesh::Index;
using skinmesh::Vec3;
using namespace skinmesh::geometry;

using skinmesh::test::brute_force_intersections;
using skinmesh::test::icosahedron;
using skinmesh::test::join;
using skinmesh::test::sphere;
using skinmesh::test::torus;

namespace {

// Fixtures ----------------------------------------------------------------------

// Closed cone with its apex at `apex`, opening along +z (dir = 1) or -z (dir = -1):
// apex, a ring of k vertices at height dir, the centre of the base.
IndexedMesh cone(const Vec3& apex, int dir, int k) {
  IndexedMesh c;
  c.positions.push_back(apex);
  for (int i = 0; i < k; ++i) {
    const double a = 2 * std::numbers::pi * i / k;
    c.positions.push_back(apex + Vec3(std::cos(a), std::sin(a), dir));
  }
  c.positions.push_back(apex + Vec3(0, 0, dir));
  const Index base = Index(k + 1);
  for (int i = 0; i < k; ++i) {
    const Index r0 = Index(1 + i), r1 = Index(1 + (i + 1) % k);
    if (dir > 0) {
      c.triangles.push_back({0, r1, r0});
      c.triangles.push_back({base, r0, r1});
    } else {
      c.triangles.push_back({0, r0, r1});
      c.triangles.push_back({base, r1, r0});
    }
  }
  return c;
}

// Unit tetrahedron (0, e_x, e_y, e_z) translated by t, outward oriented.
IndexedMesh tetrahedron(const Vec3& t) {
  IndexedMesh m;
  m.positions = {t, t + Vec3(1, 0, 0), t + Vec3(0, 1, 0), t + Vec3(0, 0, 1)};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

// Brackets balance outside strings and the text is one object.
bool looks_like_json_object(const std::string& s) {
  if (s.empty() || s.front() != '{' || s.back() != '}') return false;
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"')
      in_string = true;
    else if (c == '{' || c == '[')
      ++depth;
    else if (c == '}' || c == ']') {
      if (--depth < 0) return false;
      if (depth == 0 && i + 1 != s.size()) return false;
    }
  }
  return depth == 0 && !in_string;
}

}  // namespace

TEST_SUITE("geometry") {

TEST_CASE("check_mesh: icosahedron") {
  const MeshCheckReport r = check_mesh(icosahedron());
  CHECK(r.ok());
  CHECK(r.problems.empty());
  CHECK(r.num_vertices == 12);
  CHECK(r.num_triangles == 20);
  CHECK(r.num_edges == 30);
  CHECK(r.num_unreferenced_vertices == 0);
  CHECK(r.closed);
  CHECK(r.edge_manifold);
  CHECK(r.vertex_manifold);
  CHECK(r.oriented);
  REQUIRE(r.components.size() == 1);
  const MeshComponent& c = r.components[0];
  CHECK(c.vertices == 12);
  CHECK(c.edges == 30);
  CHECK(c.faces == 20);
  CHECK(c.euler == 2);
  REQUIRE(c.genus.has_value());
  CHECK(*c.genus == 0);
  // Volume of the regular icosahedron with edge a = 2: (5/12)(3 + sqrt 5) a^3.
  CHECK(c.volume == doctest::Approx(5.0 / 12.0 * (3.0 + std::sqrt(5.0)) * 8.0).epsilon(1e-12));
  CHECK(c.area == doctest::Approx(20 * std::sqrt(3.0)).epsilon(1e-12));
  CHECK(r.num_vertex_components == 1);
  CHECK(r.self_intersections_checked);
  CHECK(r.num_self_intersections == 0);
  CHECK(r.num_pairs_tested >= 30);  // at least the edge-adjacent pairs went through the exact test
  CHECK(r.min_angle_deg == doctest::Approx(60.0).epsilon(1e-12));
  CHECK(r.max_angle_deg == doctest::Approx(60.0).epsilon(1e-12));
  CHECK(r.worst_triangle < 20);
  const std::size_t in_5_or_6 = r.angle_histogram[5] + r.angle_histogram[6];
  CHECK(in_5_or_6 == 60);  // 60° sits on the 50-60 / 60-70 bin border: rounding decides
  CHECK(r.num_small_angle_triangles == 0);
  const std::string json = r.to_json();
  CHECK(looks_like_json_object(json));
  CHECK(json.find("\"closed\":true") != std::string::npos);
  CHECK(json.find("\"genus\":0") != std::string::npos);
  CHECK(json.find("\"ok\":true") != std::string::npos);
}

TEST_CASE("check_mesh: a finer sphere, a torus and two spheres") {
  SUBCASE("sphere") {
    const MeshCheckReport r = check_mesh(sphere(3));
    CHECK(r.ok());
    REQUIRE(r.components.size() == 1);
    CHECK(r.components[0].euler == 2);
    CHECK(r.components[0].genus == 0);
    const double ball = 4.0 / 3.0 * std::numbers::pi;
    CHECK(r.components[0].volume < ball);  // inscribed polyhedron
    CHECK(r.components[0].volume > 0.97 * ball);
    CHECK(r.min_angle_deg > 40.0);
    CHECK(r.max_angle_deg < 80.0);
  }
  SUBCASE("torus") {
    const MeshCheckReport r = check_mesh(torus(24, 12));
    CHECK(r.ok());
    REQUIRE(r.components.size() == 1);
    CHECK(r.components[0].euler == 0);
    REQUIRE(r.components[0].genus.has_value());
    CHECK(*r.components[0].genus == 1);
    const double solid = 2 * std::numbers::pi * std::numbers::pi * 2.0 * 0.7 * 0.7;
    CHECK(r.components[0].volume > 0.9 * solid);
    CHECK(r.components[0].volume < solid);
    CHECK(r.num_self_intersections == 0);
  }
  SUBCASE("two disjoint spheres") {
    IndexedMesh b = sphere(1);
    for (Vec3& p : b.positions) p += Vec3(3, 0, 0);
    const MeshCheckReport r = check_mesh(join(sphere(1), b));
    CHECK(r.ok());
    REQUIRE(r.components.size() == 2);
    for (const MeshComponent& c : r.components) {
      CHECK(c.euler == 2);
      CHECK(c.genus == 0);
      CHECK(c.faces == 80);
      CHECK(c.volume > 0);
    }
    CHECK(r.num_vertex_components == 2);
  }
}

TEST_CASE("check_mesh: one flipped triangle breaks the orientation") {
  IndexedMesh m = icosahedron();
  std::swap(m.triangles[7][1], m.triangles[7][2]);
  const MeshCheckReport r = check_mesh(m);
  CHECK_FALSE(r.ok());
  CHECK_FALSE(r.oriented);
  CHECK(r.num_misoriented_edges == 3);
  CHECK(r.misoriented_edge_examples.size() == 3);
  CHECK(r.closed);
  CHECK(r.edge_manifold);
  CHECK(r.vertex_manifold);
  REQUIRE(r.components.size() == 1);
  CHECK_FALSE(r.components[0].oriented);
  CHECK_FALSE(r.components[0].genus.has_value());
  CHECK(r.components[0].euler == 2);
  CHECK(r.problems.size() == 1);
  CHECK(r.to_json().find("\"genus\":null") != std::string::npos);
}

TEST_CASE("check_mesh: a missing triangle opens the surface") {
  IndexedMesh m = icosahedron();
  m.triangles.erase(m.triangles.begin() + 4);  // (0, 10, 11)
  const MeshCheckReport r = check_mesh(m);
  CHECK_FALSE(r.ok());
  CHECK_FALSE(r.closed);
  CHECK(r.num_boundary_edges == 3);
  std::vector<std::array<Index, 2>> expect = {{0, 10}, {0, 11}, {10, 11}};
  CHECK(r.boundary_edge_examples == expect);
  CHECK(r.oriented);
  CHECK(r.vertex_manifold);
  REQUIRE(r.components.size() == 1);
  CHECK(r.components[0].euler == 1);
  CHECK_FALSE(r.components[0].closed);
  CHECK_FALSE(r.components[0].genus.has_value());
}

TEST_CASE("check_mesh: a duplicated triangle makes non-manifold edges") {
  IndexedMesh m = icosahedron();
  m.triangles.push_back(m.triangles[2]);
  const MeshCheckReport r = check_mesh(m);
  CHECK_FALSE(r.ok());
  CHECK_FALSE(r.edge_manifold);
  CHECK(r.num_nonmanifold_edges == 3);
  CHECK(r.num_duplicate_triangles == 1);
  CHECK(r.num_nonmanifold_vertices == 3);  // the corners of the doubled triangle
  CHECK(r.num_self_intersections == 0);    // the duplicate pair is not double-counted
  REQUIRE(r.components.size() == 1);
  CHECK_FALSE(r.components[0].manifold);
}

TEST_CASE("check_mesh: two cones touching at their tips") {
  IndexedMesh up = cone(Vec3(0, 0, 0), +1, 8), down = cone(Vec3(0, 0, 0), -1, 8);
  IndexedMesh m = join(up, down);
  // Weld the second apex onto the first.
  const Index second_apex = Index(up.positions.size());
  for (auto& t : m.triangles)
    for (Index& v : t)
      if (v == second_apex) v = 0;
  const MeshCheckReport r = check_mesh(m);
  CHECK_FALSE(r.ok());
  CHECK(r.closed);
  CHECK(r.edge_manifold);
  CHECK(r.oriented);
  CHECK_FALSE(r.vertex_manifold);
  CHECK(r.num_nonmanifold_vertices == 1);
  CHECK(r.nonmanifold_vertex_examples == std::vector<Index>{0});
  CHECK(r.num_unreferenced_vertices == 1);  // the second apex, now unused
  REQUIRE(r.components.size() == 2);
  for (const MeshComponent& c : r.components) {
    CHECK(c.euler == 2);
    CHECK(c.manifold);
    CHECK(c.genus == 0);
    // A cone over a regular octagon of circumradius 1, height 1: (1/3) (8/2) sin(45°).
    CHECK(c.volume == doctest::Approx(4.0 / 3.0 * std::sin(std::numbers::pi / 4)).epsilon(1e-12));
  }
  CHECK(r.num_vertex_components == 1);
  CHECK(r.num_self_intersections == 0);  // they meet only at the shared vertex
}

TEST_CASE("check_mesh: two interpenetrating tetrahedra") {
  const IndexedMesh m = join(tetrahedron(Vec3(0, 0, 0)), tetrahedron(Vec3(0.25, 0.25, 0.25)));
  MeshCheckOptions opt;
  opt.max_examples = 100;
  const MeshCheckReport r = check_mesh(m, opt);
  CHECK(r.closed);
  CHECK(r.oriented);
  CHECK(r.vertex_manifold);
  CHECK(r.components.size() == 2);
  CHECK_FALSE(r.ok());
  CHECK(r.num_self_intersections > 0);
  for (const auto& p : r.self_intersection_examples) {
    CHECK(p[0] < 4);  // one face of each tetrahedron
    CHECK(p[1] >= 4);
  }
  CHECK(r.self_intersection_examples == brute_force_intersections(m));
  // Apart, they do not intersect.
  const MeshCheckReport apart = check_mesh(join(tetrahedron(Vec3(0, 0, 0)), tetrahedron(Vec3(1.01, 0, 0))));
  CHECK(apart.ok());
  // Touching at a point (a vertex of one on a face of the other) counts.
  const MeshCheckReport touch = check_mesh(join(tetrahedron(Vec3(0, 0, 0)), tetrahedron(Vec3(0.25, 0.25, -1))));
  CHECK(touch.num_self_intersections >= 1);
}

TEST_CASE("check_mesh: adjacent triangles that overlap in their plane") {
  MeshCheckOptions opt;
  SUBCASE("sharing an edge, apexes on the same side") {
    IndexedMesh m;
    m.positions = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0), Vec3(3, 1, 0)};
    m.triangles = {{0, 1, 2}, {1, 0, 3}};  // consistently oriented, but folded onto each other
    const MeshCheckReport r = check_mesh(m, opt);
    CHECK(r.oriented);
    CHECK(r.num_self_intersections == 1);
    CHECK(r.self_intersection_examples == std::vector<std::array<Index, 2>>{{0, 1}});
  }
  SUBCASE("sharing an edge, apexes on opposite sides (a flat quad)") {
    IndexedMesh m;
    m.positions = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0), Vec3(3, -1, 0)};
    m.triangles = {{0, 1, 2}, {1, 0, 3}};
    CHECK(check_mesh(m, opt).num_self_intersections == 0);
  }
  SUBCASE("sharing a vertex") {
    IndexedMesh m;
    m.positions = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0), Vec3(3, 3, 0), Vec3(-1, 3, 0)};
    m.triangles = {{0, 1, 2}, {0, 3, 4}};
    const MeshCheckReport r = check_mesh(m, opt);
    CHECK(r.num_self_intersections == 1);
    CHECK_FALSE(r.vertex_manifold);  // two fans at vertex 0
  }
  SUBCASE("sharing a vertex, apart") {
    IndexedMesh m;
    m.positions = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0), Vec3(-3, -3, 0), Vec3(-1, -3, 0)};
    m.triangles = {{0, 1, 2}, {0, 3, 4}};
    CHECK(check_mesh(m, opt).num_self_intersections == 0);
  }
}

TEST_CASE("check_mesh: the grid finds exactly the pairs brute force finds") {
  const unsigned seed = 987654321;
  INFO("seed = " << seed);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> small(-0.05, 0.05);
  IndexedMesh m;
  // A pool of points, with triangles of different sizes drawn from it so that
  // some share one or two vertices; a few large triangles cross many cells.
  for (int i = 0; i < 300; ++i) m.positions.emplace_back(unit(rng), unit(rng), unit(rng));
  std::uniform_int_distribution<Index> pick(0, 299);
  for (int i = 0; i < 500; ++i) {
    const Index a = pick(rng);
    const Vec3 c = m.positions[a];
    const Index b = Index(m.positions.size());
    m.positions.push_back(c + Vec3(small(rng), small(rng), small(rng)));
    Index d = pick(rng);
    if (i % 3 == 0) {  // a small triangle with a fresh third vertex
      d = Index(m.positions.size());
      m.positions.push_back(c + Vec3(small(rng), small(rng), small(rng)));
    }
    if (d == a) continue;
    m.triangles.push_back({a, b, d});
  }
  // Edge-sharing pairs: reuse existing edges.
  const std::size_t n0 = m.triangles.size();
  for (std::size_t i = 0; i < n0; i += 7) {
    const auto t = m.triangles[i];
    m.triangles.push_back({t[1], t[0], pick(rng)});
  }
  MeshCheckOptions opt;
  opt.max_examples = 1000000;
  const MeshCheckReport r = check_mesh(m, opt);
  const auto expect = brute_force_intersections(m);
  INFO("intersecting pairs: " << expect.size());
  CHECK(expect.size() > 100);
  CHECK(r.num_self_intersections == expect.size());
  CHECK(r.self_intersection_examples == expect);
}

TEST_CASE("check_mesh: degenerate, out-of-range and non-finite input") {
  IndexedMesh m = icosahedron();
  const Index n = Index(m.positions.size());
  m.positions.push_back(Vec3(0, 0, 0));                                         // n: unreferenced
  m.positions.push_back(Vec3(0.1, 0.2, 0.3));                                   // n+1
  m.positions.push_back(Vec3(0.2, 0.4, 0.6));                                   // n+2: 2 x (n+1)
  m.positions.push_back(Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0));  // n+3
  m.triangles.push_back({1, 1, 2});                                             // repeated index
  m.triangles.push_back({n, n + 1, n + 2});                                     // collinear: 0, p, 2p
  m.triangles.push_back({0, 1, 99});                                            // out of range
  m.triangles.push_back({n + 3, n + 1, n});                                     // a NaN vertex
  const MeshCheckReport r = check_mesh(m);
  CHECK_FALSE(r.ok());
  CHECK(r.num_repeated_index_triangles == 1);
  CHECK(r.num_zero_area_triangles == 1);
  CHECK(r.num_degenerate_triangles == 2);
  CHECK(r.degenerate_triangle_examples == std::vector<Index>{20, 21});
  CHECK(r.num_out_of_range_triangles == 1);
  CHECK(r.num_nonfinite_vertices == 1);
  CHECK(r.num_unreferenced_vertices == 0);
  CHECK(r.min_angle_deg == 0.0);  // the collinear triangle: 0, 0, 180 degrees
  CHECK(r.max_angle_deg == doctest::Approx(180.0));
  CHECK(r.worst_triangle == 21);
  CHECK(r.angle_histogram[17] >= 1);
  CHECK(r.num_self_intersections == 0);  // the degenerate ones are not tested
  CHECK(looks_like_json_object(r.to_json()));
}

TEST_CASE("check_mesh: angle statistics") {
  IndexedMesh m;
  m.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(10, 0, 0), Vec3(10, 1, 0)};
  m.triangles = {{0, 1, 2}, {1, 3, 4}};  // 45-45-90 and a thin one
  MeshCheckOptions opt;
  opt.small_angle_threshold_deg = 30.0;
  const MeshCheckReport r = check_mesh(m, opt);
  const double thin = std::atan2(1.0, 9.0) * 180.0 / std::numbers::pi;  // angle at vertex 1
  CHECK(r.min_angle_deg == doctest::Approx(thin));
  CHECK(r.max_angle_deg == doctest::Approx(90.0));  // the right angles at vertices 0 and 3
  CHECK(r.worst_triangle == 1);
  CHECK(r.num_small_angle_triangles == 1);
  CHECK(r.small_angle_threshold_deg == 30.0);
  std::size_t total = 0;
  for (std::size_t x : r.angle_histogram) total += x;
  CHECK(total == 6);
  CHECK(r.angle_histogram[4] == 2);                         // the two 45° angles
  CHECK(r.angle_histogram[0] == 1);                         // the thin angle, about 6.3°
  CHECK(r.angle_histogram[8] + r.angle_histogram[9] == 3);  // 83.7° and the two right angles
}

TEST_CASE("check_mesh: self-intersection check can be skipped") {
  MeshCheckOptions opt;
  opt.check_self_intersections = false;
  const MeshCheckReport r = check_mesh(join(tetrahedron(Vec3(0, 0, 0)), tetrahedron(Vec3(0.25, 0.25, 0.25))), opt);
  CHECK_FALSE(r.self_intersections_checked);
  CHECK(r.num_self_intersections == 0);
  CHECK(r.num_pairs_tested == 0);
  CHECK(r.to_json().find("\"self_intersections_checked\":false") != std::string::npos);
}

TEST_CASE("check_mesh: empty mesh and lone vertices") {
  const MeshCheckReport empty = check_mesh(IndexedMesh{});
  CHECK(empty.num_triangles == 0);
  CHECK(empty.components.empty());
  CHECK(empty.worst_triangle == skinmesh::kInvalidIndex);
  CHECK(empty.ok());
  CHECK(empty.to_json().find("\"worst_triangle\":null") != std::string::npos);
  IndexedMesh lone;
  lone.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
  const MeshCheckReport r = check_mesh(lone);
  CHECK(r.num_unreferenced_vertices == 2);
  CHECK(r.num_vertex_components == 0);
}

TEST_CASE("check_mesh: candidate pairs and duplicates equal brute force on a coarse random soup") {
  // Points on a coarse integer grid, so that boxes touch exactly, triangles are
  // often coplanar and vertex sets repeat (as permutations and reflections).
  const unsigned seed = 20261122;
  INFO("seed = " << seed);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> coord(0, 4);
  IndexedMesh m;
  for (int i = 0; i < 60; ++i) m.positions.emplace_back(coord(rng), coord(rng), coord(rng));
  std::uniform_int_distribution<Index> pick(0, 59);
  for (int i = 0; i < 400; ++i) {
    std::array<Index, 3> t{pick(rng), pick(rng), pick(rng)};
    if (i % 9 == 0 && !m.triangles.empty()) {  // a duplicate of an earlier triangle, permuted
      t = m.triangles[std::uniform_int_distribution<std::size_t>(0, m.triangles.size() - 1)(rng)];
      std::shuffle(t.begin(), t.end(), rng);
    }
    m.triangles.push_back(t);
  }
  MeshCheckOptions opt;
  opt.max_examples = 1000000;
  const MeshCheckReport r = check_mesh(m, opt);
  const auto& P = m.positions;
  const auto& T = m.triangles;
  auto good = [&](const std::array<Index, 3>& t) {
    return t[0] != t[1] && t[1] != t[2] && t[2] != t[0] && !is_degenerate_triangle(P[t[0]], P[t[1]], P[t[2]]);
  };
  auto box_overlap = [&](const std::array<Index, 3>& a, const std::array<Index, 3>& b) {
    for (int k = 0; k < 3; ++k) {
      const double alo = std::min({P[a[0]][k], P[a[1]][k], P[a[2]][k]}),
                   ahi = std::max({P[a[0]][k], P[a[1]][k], P[a[2]][k]});
      const double blo = std::min({P[b[0]][k], P[b[1]][k], P[b[2]][k]}),
                   bhi = std::max({P[b[0]][k], P[b[1]][k], P[b[2]][k]});
      if (alo > bhi || blo > ahi) return false;
    }
    return true;
  };
  auto sorted = [](std::array<Index, 3> t) {
    std::sort(t.begin(), t.end());
    return t;
  };
  std::size_t pairs = 0, duplicates = 0;
  for (std::size_t i = 0; i < T.size(); ++i) {
    const bool distinct = T[i][0] != T[i][1] && T[i][1] != T[i][2] && T[i][2] != T[i][0];
    bool earlier = false;
    for (std::size_t j = 0; j < i && distinct; ++j) earlier = earlier || sorted(T[j]) == sorted(T[i]);
    duplicates += earlier;
    if (!good(T[i])) continue;
    for (std::size_t j = i + 1; j < T.size(); ++j)
      if (good(T[j]) && sorted(T[i]) != sorted(T[j]) && box_overlap(T[i], T[j])) ++pairs;
  }
  CHECK(duplicates > 20);
  CHECK(r.num_duplicate_triangles == duplicates);
  CHECK(r.num_pairs_tested == pairs);
  CHECK(r.self_intersection_examples == brute_force_intersections(m));
}

TEST_CASE("edges and edge-connected components of random triangle soups agree with brute force") {
  // Few vertices and many triangles: shared, boundary, non-manifold and
  // misoriented edges all occur, and components merge and split. Brute force:
  // every edge's uses from a map, the components by repeated joining.
  std::mt19937 rng(2026);
  std::uniform_int_distribution<int> pick(0, 9);
  std::uniform_real_distribution<double> coord(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    IndexedMesh m;
    for (int v = 0; v < 10; ++v) m.positions.emplace_back(coord(rng), coord(rng), coord(rng));
    const int nt = 1 + trial % 17;
    while (static_cast<int>(m.triangles.size()) < nt) {
      const std::array<Index, 3> t{Index(pick(rng)), Index(pick(rng)), Index(pick(rng))};
      if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) m.triangles.push_back(t);
    }
    MeshCheckOptions o;
    o.check_self_intersections = false;
    const MeshCheckReport r = check_mesh(m, o);

    std::map<std::pair<Index, Index>, std::vector<std::pair<std::size_t, int>>> uses;  // (triangle, direction)
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      for (int i = 0; i < 3; ++i) {
        const Index a = m.triangles[t][i], b = m.triangles[t][(i + 1) % 3];
        uses[{std::min(a, b), std::max(a, b)}].push_back({t, a < b ? 1 : -1});
      }
    std::vector<std::size_t> comp(m.triangles.size());
    for (std::size_t t = 0; t < comp.size(); ++t) comp[t] = t;
    for (bool changed = true; changed;) {  // every triangle takes the lowest label of an edge neighbour
      changed = false;
      for (const auto& [edge, u] : uses)
        for (const auto& [t, d] : u)
          for (const auto& [w, e] : u)
            if (comp[w] < comp[t]) comp[t] = comp[w], changed = true;
    }
    std::map<std::size_t, std::size_t> id;  // lowest triangle -> component number
    for (std::size_t t = 0; t < comp.size(); ++t)
      if (!id.count(comp[t])) id[comp[t]] = id.size();
    std::vector<MeshComponent> expect(id.size());
    for (MeshComponent& c : expect) c.closed = c.oriented = true;
    for (std::size_t t = 0; t < comp.size(); ++t) ++expect[id[comp[t]]].faces;
    std::size_t boundary = 0, nonmanifold = 0, misoriented = 0;
    for (const auto& [edge, u] : uses) {
      MeshComponent& c = expect[id[comp[u[0].first]]];
      ++c.edges;
      if (u.size() == 1) ++boundary, c.closed = false;
      if (u.size() > 2) ++nonmanifold;
      if (u.size() == 2 && u[0].second == u[1].second) ++misoriented, c.oriented = false;
    }
    CAPTURE(trial);
    CHECK(r.num_edges == uses.size());
    CHECK(r.num_boundary_edges == boundary);
    CHECK(r.num_nonmanifold_edges == nonmanifold);
    CHECK(r.num_misoriented_edges == misoriented);
    REQUIRE(r.components.size() == expect.size());
    for (std::size_t c = 0; c < expect.size(); ++c) {
      CHECK(r.components[c].faces == expect[c].faces);
      CHECK(r.components[c].edges == expect[c].edges);
      CHECK(r.components[c].closed == expect[c].closed);
      CHECK(r.components[c].oriented == expect[c].oriented);
    }
  }
}

}  // TEST_SUITE
