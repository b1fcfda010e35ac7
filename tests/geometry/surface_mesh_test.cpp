// tests/geometry/surface_mesh_test.cpp: the half-edge SurfaceMesh
// (geometry/mesh/surface_mesh). Every test asserts what an operation changes (counts,
// valences, boundary loops, endpoints) and runs check_consistency() after each
// step, so a no-op or a broken link fails.
#include <doctest/doctest.h>
#include <Eigen/Geometry>  // cross()

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/errors.h"
#include "geometry/check/mesh_checks.h"
#include "geometry/mesh/surface_mesh.h"
#include "tests/geometry/test_meshes.h"

using skinmesh::Index;
using skinmesh::TopologyError;
using skinmesh::Vec3;
using namespace skinmesh::geometry;

using skinmesh::test::icosahedron;
using skinmesh::test::sphere;
using skinmesh::test::torus;

namespace {

// Fixtures ----------------------------------------------------------------------

// Octahedron with vertices +x, +y, +z, -x, -y, -z (indices 0..5).
IndexedMesh octahedron() {
  IndexedMesh m;
  m.positions = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(-1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, -1)};
  m.triangles = {{0, 1, 2}, {1, 3, 2}, {3, 4, 2}, {4, 0, 2}, {1, 0, 5}, {3, 1, 5}, {4, 3, 5}, {0, 4, 5}};
  return m;
}

// Helpers -------------------------------------------------------------------------

void consistent(const SurfaceMesh& m) { REQUIRE_NOTHROW(m.check_consistency()); }

long long euler(const SurfaceMesh& m) {
  return (long long)m.n_vertices() - (long long)m.n_edges() + (long long)m.n_faces();
}

// Boundary loops as vertex sequences (source of each half-edge), each rotated to
// start at its smallest vertex, sorted.
std::vector<std::vector<Index>> loops(const SurfaceMesh& m) {
  std::vector<std::vector<Index>> out;
  for (const auto& loop : m.boundary_loops()) {
    std::vector<Index> vs;
    for (Halfedge h : loop) vs.push_back(m.from_vertex(h).idx());
    std::rotate(vs.begin(), std::min_element(vs.begin(), vs.end()), vs.end());
    out.push_back(vs);
  }
  std::sort(out.begin(), out.end());
  return out;
}

using Loops = std::vector<std::vector<Index>>;

// Normal (b - a) x (c - a) of a face.
Vec3 normal(const SurfaceMesh& m, Face f) {
  std::vector<Vec3> p;
  for (Vertex v : m.vertices(f)) p.push_back(m.position(v));
  return (p[1] - p[0]).cross(p[2] - p[0]);
}

// Vertex indices of a face, rotated to start at the smallest.
std::array<Index, 3> corners(const SurfaceMesh& m, Face f) {
  std::array<Index, 3> c{};
  int i = 0;
  for (Vertex v : m.vertices(f)) c[i++] = v.idx();
  std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
  return c;
}

// Rotate a cyclic sequence to start at its smallest element.
std::vector<Index> canonical_cycle(std::vector<Index> c) {
  std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
  return c;
}

SurfaceMesh build(const IndexedMesh& im) { return SurfaceMesh::from_indexed_mesh(im); }

Vertex V(Index i) { return Vertex(i); }

/// A closed mesh cut by the plane z = 0: side[i] (0 below, 1 above) and
/// index local[i] of vertex i in part[side[i]], each part the triangles with
/// all three corners on its side, and `band` the triangles (of the whole
/// mesh's indices) that mix both sides.
struct SplitSphere {
  explicit SplitSphere(const IndexedMesh& whole) : side(whole.positions.size()), local(whole.positions.size()) {
    for (std::size_t i = 0; i < side.size(); ++i) side[i] = whole.positions[i].z() < 0 ? 0 : 1;
    for (std::size_t i = 0; i < side.size(); ++i) {
      local[i] = Index(part[side[i]].positions.size());
      part[side[i]].positions.push_back(whole.positions[i]);
    }
    for (const auto& t : whole.triangles) {
      const int s0 = side[t[0]];
      if (side[t[1]] == s0 && side[t[2]] == s0)
        part[s0].triangles.push_back({local[t[0]], local[t[1]], local[t[2]]});
      else
        band.push_back(t);
    }
  }
  std::vector<int> side;
  std::vector<Index> local;
  IndexedMesh part[2];
  std::vector<std::array<Index, 3>> band;
};

template <class P, class H>
concept IndexableBy = requires(P p, H h) {
  p[h];
};

}  // namespace

TEST_SUITE("geometry") {

TEST_CASE("SurfaceMesh: handles and properties are typed") {
  static_assert(!std::is_convertible_v<Vertex, Face>);
  static_assert(!std::is_convertible_v<Index, Vertex>);  // explicit construction only
  static_assert(!std::equality_comparable_with<Vertex, Face>);
  static_assert(IndexableBy<VertexProperty<int>, Vertex>);
  static_assert(!IndexableBy<VertexProperty<int>, Face>);
  static_assert(!IndexableBy<FaceProperty<int>, Edge>);
  static_assert(IndexableBy<EdgeProperty<bool>, Edge>);
  CHECK_FALSE(Vertex().is_valid());
  CHECK(Vertex(3).is_valid());
  CHECK(Vertex(3) == Vertex(3));
  CHECK(Vertex(2) < Vertex(3));
  std::ostringstream os;
  os << Vertex(12) << ' ' << Halfedge(3) << ' ' << Edge(7) << ' ' << Face(0) << ' ' << Face();
  CHECK(os.str() == "v12 h3 e7 f0 f-");

  SurfaceMesh m;
  const Halfedge h(5);
  CHECK(m.opposite(h) == Halfedge(4));
  CHECK(m.edge(h) == Edge(2));
  CHECK(m.halfedge(Edge(2), 1) == h);
}

TEST_CASE("SurfaceMesh: a fan, then an ear that closes the gap") {
  // Centre 0 and a ring 1..6 counter-clockwise in the xy-plane (normal +z).
  SurfaceMesh m;
  const Vertex c = m.add_vertex(Vec3(0, 0, 0));
  std::vector<Vertex> ring;
  for (int i = 0; i < 6; ++i)
    ring.push_back(m.add_vertex(Vec3(std::cos(i * std::numbers::pi / 3), std::sin(i * std::numbers::pi / 3), 0)));
  CHECK(m.is_isolated(c));
  CHECK(m.boundary_loops().empty());

  // Fan (c, r0, r1), ..., (c, r4, r5): after k triangles the loop is c, r_k, ..., r_0.
  for (int k = 1; k <= 5; ++k) {
    const Face f = m.add_triangle(c, ring[k - 1], ring[k]);
    consistent(m);
    CHECK(m.n_faces() == std::size_t(k));
    CHECK(m.n_edges() == std::size_t(2 * k + 1));
    std::vector<Index> expect = {c.idx()};
    for (int i = k; i >= 0; --i) expect.push_back(ring[i].idx());
    CHECK(loops(m) == Loops{expect});
    CHECK(m.is_boundary(c));
    CHECK(m.valence(c) == std::size_t(k + 1));
    CHECK(normal(m, f).z() > 0);
    // halfedge(v) of a boundary vertex is an outgoing boundary half-edge.
    CHECK(m.is_boundary(m.halfedge(c)));
    CHECK(m.from_vertex(m.halfedge(c)) == c);
  }
  // The ear (c, r5, r0): two existing boundary edges and one new.
  CHECK(m.find_halfedge(c, ring[5]).is_valid());
  CHECK(m.find_halfedge(ring[0], c).is_valid());
  CHECK_FALSE(m.find_halfedge(ring[5], ring[0]).is_valid());
  m.add_triangle(c, ring[5], ring[0]);
  consistent(m);
  CHECK(m.n_faces() == 6);
  CHECK(m.n_edges() == 12);
  CHECK_FALSE(m.is_boundary(c));
  CHECK(m.valence(c) == 6);
  CHECK(loops(m) == Loops{{1, 6, 5, 4, 3, 2}});
  CHECK(euler(m) == 1);
  // The one-ring of c counter-clockwise is r0, ..., r5 (up to rotation).
  std::vector<Index> ringv;
  for (Vertex w : m.vertices(c)) ringv.push_back(w.idx());
  CHECK(canonical_cycle(ringv) == std::vector<Index>{1, 2, 3, 4, 5, 6});
  std::size_t nf = 0;
  for ([[maybe_unused]] Face f : m.faces(c)) ++nf;
  CHECK(nf == 6);
}

TEST_CASE("SurfaceMesh: a triangle merges two loops through a pinch, the next one resolves it") {
  // Two separate triangles A = (0, 1, 2) and B = (3, 4, 5).
  SurfaceMesh m;
  for (int i = 0; i < 6; ++i) m.add_vertex(Vec3(i, i % 2, 0));
  m.add_triangle(V(0), V(1), V(2));
  m.add_triangle(V(3), V(4), V(5));
  consistent(m);
  CHECK(loops(m) == Loops{{0, 2, 1}, {3, 5, 4}});

  // (1, 0, 3) uses A's boundary half-edge 1->0 and touches B only at vertex 3.
  m.add_triangle(V(1), V(0), V(3));
  consistent(m);
  CHECK(m.n_faces() == 3);
  CHECK(m.n_edges() == 8);
  CHECK(loops(m) == Loops{{0, 2, 1, 3, 5, 4, 3}});  // one loop through 3 twice
  CHECK(m.boundary_gaps(V(3)) == 2);
  CHECK_FALSE(m.is_manifold(V(3)));
  CHECK(m.valence(V(3)) == 4);
  CHECK(m.is_manifold(V(0)));

  // (4, 3, 0) fills the gap at 3 between B's edge 4->3 and the new edge 3->0.
  CHECK(m.next(m.find_halfedge(V(4), V(3))) == m.find_halfedge(V(3), V(0)));
  m.add_triangle(V(4), V(3), V(0));
  consistent(m);
  CHECK(m.n_faces() == 4);
  CHECK(m.n_edges() == 9);
  CHECK(loops(m) == Loops{{0, 2, 1, 3, 5, 4}});
  CHECK(m.boundary_gaps(V(3)) == 1);
  CHECK(m.is_manifold(V(3)));
  CHECK(euler(m) == 1);
}

TEST_CASE("SurfaceMesh: a triangle between two vertices of one loop splits it") {
  // Closed hexagonal fan: centre 0, ring 1..6; its loop runs 1, 6, 5, 4, 3, 2.
  SurfaceMesh m;
  m.add_vertex(Vec3(0, 0, 0));
  for (int i = 0; i < 6; ++i)
    m.add_vertex(Vec3(std::cos(i * std::numbers::pi / 3), std::sin(i * std::numbers::pi / 3), 0));
  for (Index i = 0; i < 6; ++i) m.add_triangle(V(0), V(1 + i), V(1 + (i + 1) % 6));
  CHECK(loops(m) == Loops{{1, 6, 5, 4, 3, 2}});
  // (2, 1, 4): the boundary edge 2->1 and the loop vertex 4 (combinatorial test:
  // positions are irrelevant to add_triangle).
  m.add_triangle(V(2), V(1), V(4));
  consistent(m);
  CHECK(m.n_faces() == 7);
  CHECK(m.n_edges() == 14);
  CHECK(loops(m) == Loops{{1, 6, 5, 4}, {2, 4, 3}});
  CHECK(m.boundary_gaps(V(4)) == 2);
  // Closing the small loop 2 -> 4 -> 3 makes 4 manifold again.
  m.add_triangle(V(2), V(4), V(3));
  consistent(m);
  CHECK(loops(m) == Loops{{1, 6, 5, 4}});
  CHECK(m.boundary_gaps(V(4)) == 1);
  CHECK(m.boundary_gaps(V(2)) == 0);
}

TEST_CASE("SurfaceMesh: three fans at a vertex are re-linked into their geometric order") {
  // Vertex 0 at the origin; three single triangles at 0..40, 120..160, 240..280
  // degrees; then the three gaps are filled in every order. Depending on the
  // order the fans were added, the fans' order in the structure differs from
  // the geometric one and add_triangle must move a fan (patch re-linking).
  auto at = [](double deg) {
    const double a = deg * std::numbers::pi / 180.0;
    return Vec3(std::cos(a), std::sin(a), 0);
  };
  const double angles[6] = {0, 40, 120, 160, 240, 280};
  const std::array<std::array<Index, 3>, 3> fans = {{{0, 1, 2}, {0, 3, 4}, {0, 5, 6}}};
  const std::array<std::array<Index, 3>, 3> fills = {{{0, 2, 3}, {0, 4, 5}, {0, 6, 1}}};
  int relinked = 0, runs = 0;
  for (const auto& fan_order : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 1}}) {
    std::array<int, 3> perm = {0, 1, 2};
    do {
      SurfaceMesh m;
      m.add_vertex(Vec3(0, 0, 0));
      for (double a : angles) m.add_vertex(at(a));
      for (int i : fan_order) m.add_triangle(V(fans[i][0]), V(fans[i][1]), V(fans[i][2]));
      consistent(m);
      CHECK(m.boundary_gaps(V(0)) == 3);
      for (int k = 0; k < 3; ++k) {
        const auto& t = fills[perm[k]];
        const Halfedge p = m.find_halfedge(V(t[2]), V(0)), n = m.find_halfedge(V(0), V(t[1]));
        REQUIRE(m.is_boundary(p));
        REQUIRE(m.is_boundary(n));
        if (m.next(p) != n) ++relinked;
        m.add_triangle(V(t[0]), V(t[1]), V(t[2]));
        consistent(m);
        CHECK(m.boundary_gaps(V(0)) == std::size_t(2 - k));
      }
      CHECK_FALSE(m.is_boundary(V(0)));
      CHECK(m.valence(V(0)) == 6);
      std::vector<Index> ring;
      for (Vertex w : m.vertices(V(0))) ring.push_back(w.idx());
      CHECK(canonical_cycle(ring) == std::vector<Index>{1, 2, 3, 4, 5, 6});  // counter-clockwise
      CHECK(loops(m) == Loops{{1, 6, 5, 4, 3, 2}});
      ++runs;
    } while (std::next_permutation(perm.begin(), perm.end()));
  }
  CHECK(runs == 12);
  CHECK(relinked > 0);  // the re-linking path was exercised
}

TEST_CASE("SurfaceMesh: add_triangle refuses non-manifold and misoriented input, unchanged") {
  SurfaceMesh m;
  for (int i = 0; i < 8; ++i) m.add_vertex(Vec3(i, (i * 7) % 5, 0));
  m.add_triangle(V(0), V(1), V(2));
  m.add_triangle(V(1), V(0), V(3));
  const auto before = loops(m);
  auto unchanged = [&] {
    consistent(m);
    CHECK(m.n_faces() == 2);
    CHECK(m.n_edges() == 5);
    CHECK(m.n_vertices() == 8);
    CHECK(loops(m) == before);
  };
  auto message = [&](Index a, Index b, Index c) {
    try {
      m.add_triangle(V(a), V(b), V(c));
    } catch (const TopologyError& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  CHECK(message(0, 1, 4).find("non-manifold edge") != std::string::npos);
  unchanged();
  CHECK(message(2, 0, 5).find("wrong orientation") != std::string::npos);  // 2->0 is used by (0,1,2)
  unchanged();
  CHECK(message(4, 4, 5).find("repeated vertex") != std::string::npos);
  unchanged();
  CHECK_THROWS_AS(m.add_triangle(V(4), V(5), V(99)), std::invalid_argument);
  unchanged();

  SUBCASE("a vertex with a closed one-ring") {
    SurfaceMesh d = build(octahedron());
    d.add_vertex(Vec3(5, 5, 5));
    d.add_vertex(Vec3(6, 5, 5));
    try {
      d.add_triangle(V(0), V(6), V(7));
      FAIL("no exception");
    } catch (const TopologyError& e) {
      CHECK(std::string(e.what()).find("interior") != std::string::npos);
    }
    consistent(d);
    CHECK(d.n_faces() == 8);
  }
  SUBCASE("a triangle that would close one fan while another fan remains") {
    // A fan of five triangles around 0 (ring 1..6) and a separate triangle (0, 7, 8):
    // closing the fan with (0, 6, 1) would leave (0, 7, 8) hanging at a closed vertex.
    SurfaceMesh d;
    d.add_vertex(Vec3(0, 0, 0));
    for (int i = 0; i < 8; ++i) d.add_vertex(Vec3(std::cos(i), std::sin(i), 0));
    for (Index i = 1; i <= 5; ++i) d.add_triangle(V(0), V(i), V(i + 1));
    d.add_triangle(V(0), V(7), V(8));
    CHECK(d.boundary_gaps(V(0)) == 2);
    try {
      d.add_triangle(V(0), V(6), V(1));
      FAIL("no exception");
    } catch (const TopologyError& e) {
      CHECK(std::string(e.what()).find("close a fan") != std::string::npos);
    }
    consistent(d);
    CHECK(d.n_faces() == 6);
    CHECK(d.boundary_gaps(V(0)) == 2);
  }
}

TEST_CASE("SurfaceMesh: closing an octahedron and an icosahedron face by face") {
  SUBCASE("octahedron, in an order that pinches the apex") {
    const IndexedMesh o = octahedron();
    SurfaceMesh m;
    for (const Vec3& p : o.positions) m.add_vertex(p);
    // Faces 0 and 2 share only vertex 2 (+z): a pinch until 1 and 3 arrive.
    const int order[8] = {0, 2, 5, 7, 1, 6, 3, 4};
    for (int k = 0; k < 8; ++k) {
      const auto& t = o.triangles[std::size_t(order[k])];
      m.add_triangle(V(t[0]), V(t[1]), V(t[2]));
      consistent(m);
      if (k == 1) CHECK(m.boundary_gaps(V(2)) == 2);
    }
    CHECK(m.n_vertices() == 6);
    CHECK(m.n_edges() == 12);
    CHECK(m.n_faces() == 8);
    CHECK(m.boundary_loops().empty());
    for (Vertex v : m.vertices()) {
      CHECK_FALSE(m.is_boundary(v));
      CHECK(m.valence(v) == 4);
    }
  }
  SUBCASE("icosahedron in file order") {
    const IndexedMesh ico = icosahedron();
    SurfaceMesh m;
    for (const Vec3& p : ico.positions) m.add_vertex(p);
    for (const auto& t : ico.triangles) {
      const Face f = m.add_triangle(V(t[0]), V(t[1]), V(t[2]));
      consistent(m);
      const Vec3 centroid = (m.position(V(t[0])) + m.position(V(t[1])) + m.position(V(t[2]))) / 3;
      CHECK(normal(m, f).dot(centroid) > 0);  // the fixture is outward oriented
    }
    CHECK(m.n_vertices() == 12);
    CHECK(m.n_edges() == 30);
    CHECK(m.n_faces() == 20);
    CHECK(euler(m) == 2);
    CHECK(m.boundary_loops().empty());
    for (Vertex v : m.vertices()) {
      CHECK_FALSE(m.is_boundary(v));
      CHECK(m.valence(v) == 5);
    }
  }
}

TEST_CASE("SurfaceMesh: from_indexed_mesh accepts any triangle order and round-trips") {
  const unsigned seed = 1234567;
  INFO("seed = " << seed);
  std::mt19937 rng(seed);
  for (const IndexedMesh& base : {icosahedron(), torus(7, 5), sphere(2)}) {
    for (int run = 0; run < 40; ++run) {
      IndexedMesh im = base;
      std::shuffle(im.triangles.begin(), im.triangles.end(), rng);
      SurfaceMesh m = build(im);
      consistent(m);
      CHECK(m.n_faces() == im.triangles.size());
      CHECK(m.boundary_loops().empty());
      CHECK(euler(m) == (base.triangles.size() == 70 ? 0 : 2));
      const IndexedMesh back = m.to_indexed_mesh();
      CHECK(back.positions == im.positions);
      REQUIRE(back.triangles.size() == im.triangles.size());
      for (std::size_t j = 0; j < im.triangles.size(); ++j) {
        auto a = im.triangles[j], b = back.triangles[j];
        std::rotate(a.begin(), std::min_element(a.begin(), a.end()), a.end());
        std::rotate(b.begin(), std::min_element(b.begin(), b.end()), b.end());
        CHECK(a == b);  // same face, same orientation
      }
    }
  }
}

TEST_CASE("SurfaceMesh: append keeps each mesh's connectivity, and the band between them glues") {
  // A sphere cut by the plane z = 0 into its lower and upper vertices: the
  // triangles of each side are built as their own mesh, appended, and the
  // triangles that mix both sides are added on the appended boundaries.
  const IndexedMesh whole = sphere(2);
  const SplitSphere split(whole);
  const std::vector<int>& side = split.side;
  const std::vector<Index>& local = split.local;
  const IndexedMesh* part = split.part;
  std::vector<std::array<Index, 3>> band = split.band;
  REQUIRE(!band.empty());
  SurfaceMesh m;
  auto tag = m.add_vertex_property<int>("v:tag", -1);
  Index base[2];
  for (int k = 0; k < 2; ++k) {
    const SurfaceMesh p = build(part[k]);
    base[k] = Index(m.vertices_size());
    const std::size_t faces_before = m.n_faces(), loops_before = m.boundary_loops().size();
    m.append(p);
    consistent(m);
    CHECK(m.n_faces() == faces_before + p.n_faces());
    CHECK(m.boundary_loops().size() == loops_before + p.boundary_loops().size());
    for (std::size_t i = 0; i < p.vertices_size(); ++i) CHECK(tag[Vertex(base[k] + Index(i))] == -1);
  }
  std::mt19937 rng(2611);
  std::shuffle(band.begin(), band.end(), rng);
  auto glued = [&](Index i) { return Vertex(base[side[i]] + local[i]); };
  for (const auto& t : band) m.add_triangle(glued(t[0]), glued(t[1]), glued(t[2]));
  consistent(m);
  CHECK(m.boundary_loops().empty());
  CHECK(euler(m) == 2);
  for (std::size_t i = 0; i < whole.positions.size(); ++i) CHECK(m.position(glued(Index(i))) == whole.positions[i]);

  SurfaceMesh with_garbage = build(icosahedron());
  with_garbage.delete_face(Face(0));
  CHECK_THROWS_AS(m.append(with_garbage), std::invalid_argument);
  CHECK_THROWS_AS(m.append(m), std::invalid_argument);
}

TEST_CASE("SurfaceMesh: append_consuming makes append's mesh with the shared properties, and empties the part") {
  // Levels 1 (arrays of a few kB, malloc'd) and 4 (mapped arrays, given back
  // a page at a time as they are copied).
  for (int level : {1, 4}) {
    INFO("level " << level);
    const SplitSphere split(sphere(level));
    const std::vector<int>& side = split.side;
    const std::vector<Index>& local = split.local;
    SurfaceMesh lower = build(split.part[0]), upper = build(split.part[1]);
    auto tag = lower.add_vertex_property<int>("v:tag", -1);
    auto weight = lower.add_vertex_property<double>("v:weight", 0.25);
    auto upper_tag = upper.add_vertex_property<int>("v:tag", -2);
    upper.add_vertex_property<float>("v:weight", 9.0f);  // another type: not copied
    upper.add_vertex_property<char>("v:only_upper", 'x');
    for (Vertex v : lower.vertices()) tag[v] = int(v.idx());
    for (Vertex v : upper.vertices()) upper_tag[v] = 1000 + int(v.idx());

    SurfaceMesh expected = lower;
    expected.append(upper);
    const std::size_t nv0 = lower.vertices_size(), nv1 = upper.vertices_size(), nh = upper.halfedges_size();
    lower.append_consuming(upper);
    consistent(lower);
    REQUIRE(lower.vertices_size() == expected.vertices_size());
    REQUIRE(lower.halfedges_size() == expected.halfedges_size());
    REQUIRE(lower.faces_size() == expected.faces_size());
    bool same = true;
    for (Vertex v : expected.vertices())
      same = same && lower.position(v) == expected.position(v) && lower.halfedge(v) == expected.halfedge(v);
    for (std::size_t i = 0; i < expected.halfedges_size(); ++i) {
      const Halfedge h(static_cast<Index>(i));
      same = same && lower.to_vertex(h) == expected.to_vertex(h) && lower.face(h) == expected.face(h) &&
             lower.next(h) == expected.next(h) && lower.prev(h) == expected.prev(h);
    }
    for (Face f : expected.faces()) same = same && lower.halfedge(f) == expected.halfedge(f);
    CHECK(same);
    CHECK(nh > 0);
    // The shared property is copied, the one of another type is not.
    bool tags = true, weights = true;
    for (std::size_t i = 0; i < nv0 + nv1; ++i) {
      const Vertex v(static_cast<Index>(i));
      tags = tags && tag[v] == (i < nv0 ? int(i) : 1000 + int(i - nv0));
      weights = weights && (i < nv0 || weight[v] == 0.25);
    }
    CHECK(tags);
    CHECK(weights);
    // The part is empty and keeps its properties.
    CHECK(upper.vertices_size() == 0);
    CHECK(upper.halfedges_size() == 0);
    CHECK(upper.faces_size() == 0);
    CHECK(upper.get_vertex_property<char>("v:only_upper"));
    // The band glues the appended boundaries into the whole sphere.
    auto glued = [&](Index i) { return Vertex((side[i] ? Index(nv0) : 0) + local[i]); };
    for (const auto& t : split.band) lower.add_triangle(glued(t[0]), glued(t[1]), glued(t[2]));
    consistent(lower);
    CHECK(lower.boundary_loops().empty());
    CHECK(euler(lower) == 2);
  }
  SurfaceMesh m = build(icosahedron());
  SurfaceMesh with_garbage = build(icosahedron());
  with_garbage.delete_face(Face(0));
  CHECK_THROWS_AS(m.append_consuming(with_garbage), std::invalid_argument);
  CHECK(with_garbage.n_faces() == 19);  // refused before anything changed
  CHECK_THROWS_AS(m.append_consuming(m), std::invalid_argument);
  CHECK(m.n_faces() == 20);
}

TEST_CASE("SurfaceMesh: from_indexed_mesh refuses non-manifold input") {
  SUBCASE("duplicated triangle") {
    IndexedMesh im = icosahedron();
    im.triangles.push_back(im.triangles[3]);
    CHECK_THROWS_AS(build(im), TopologyError);
  }
  SUBCASE("flipped triangle") {
    IndexedMesh im = icosahedron();
    std::swap(im.triangles[4][0], im.triangles[4][1]);
    CHECK_THROWS_AS(build(im), TopologyError);
  }
  SUBCASE("two triangles sharing only a vertex (bow tie)") {
    IndexedMesh im;
    im.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 0, 0), Vec3(-1, -1, 0)};
    im.triangles = {{0, 1, 2}, {0, 3, 4}};
    try {
      build(im);
      FAIL("no exception");
    } catch (const TopologyError& e) {
      CHECK(std::string(e.what()).find("vertex 0 is non-manifold") != std::string::npos);
    }
  }
  SUBCASE("two closed octahedra sharing a vertex") {
    IndexedMesh a = octahedron(), b = octahedron();
    IndexedMesh im = a;
    // b shifted by +2 in x so that its -x vertex (3) sits on a's +x vertex (0).
    std::vector<Index> map(6);
    for (Index i = 0; i < 6; ++i) {
      if (i == 3) {
        map[i] = 0;
        continue;
      }
      map[i] = Index(im.positions.size());
      im.positions.push_back(b.positions[i] + Vec3(2, 0, 0));
    }
    for (auto t : b.triangles) im.triangles.push_back({map[t[0]], map[t[1]], map[t[2]]});
    CHECK_THROWS_AS(build(im), TopologyError);
  }
  SUBCASE("index out of range") {
    IndexedMesh im = octahedron();
    im.triangles.push_back({0, 1, 6});
    CHECK_THROWS_AS(build(im), TopologyError);
  }
}

TEST_CASE("SurfaceMesh: flip") {
  SUBCASE("in a quad: the edge changes its endpoints, counts do not change") {
    // a = 0, b = 1 on the x axis, c = 2 above, d = 3 below: faces (a,b,c), (b,a,d).
    SurfaceMesh m;
    m.add_vertex(Vec3(0, 0, 0));
    m.add_vertex(Vec3(2, 0, 0));
    m.add_vertex(Vec3(1, 1, 0));
    m.add_vertex(Vec3(1, -1, 0));
    m.add_triangle(V(0), V(1), V(2));
    m.add_triangle(V(1), V(0), V(3));
    const Edge e = m.find_edge(V(0), V(1));
    REQUIRE(e.is_valid());
    CHECK(m.is_flip_ok(e));
    CHECK_FALSE(m.is_flip_ok(m.find_edge(V(0), V(2))));  // boundary
    CHECK_THROWS_AS(m.flip(m.find_edge(V(0), V(2))), TopologyError);
    m.flip(e);
    consistent(m);
    CHECK(m.to_vertex(m.halfedge(e, 0)) == V(2));
    CHECK(m.to_vertex(m.halfedge(e, 1)) == V(3));
    CHECK_FALSE(m.find_edge(V(0), V(1)).is_valid());
    CHECK(m.find_edge(V(2), V(3)) == e);
    CHECK(m.n_vertices() == 4);
    CHECK(m.n_edges() == 5);
    CHECK(m.n_faces() == 2);
    CHECK(m.valence(V(0)) == 2);
    CHECK(m.valence(V(1)) == 2);
    CHECK(m.valence(V(2)) == 3);
    CHECK(m.valence(V(3)) == 3);
    std::set<std::array<Index, 3>> fs;
    for (Face f : m.faces()) {
      fs.insert(corners(m, f));
      CHECK(normal(m, f).z() > 0);
    }
    CHECK(fs == std::set<std::array<Index, 3>>{{0, 3, 2}, {1, 2, 3}});
    CHECK(loops(m) == Loops{{0, 2, 1, 3}});
  }
  SUBCASE("in a closed mesh") {
    SurfaceMesh m = build(icosahedron());
    const Edge e = m.find_edge(V(0), V(1));  // faces (0,1,7) and (0,5,1)
    REQUIRE(m.is_flip_ok(e));
    m.flip(e);
    consistent(m);
    CHECK(m.find_edge(V(5), V(7)) == e);
    CHECK(m.valence(V(0)) == 4);
    CHECK(m.valence(V(1)) == 4);
    CHECK(m.valence(V(5)) == 6);
    CHECK(m.valence(V(7)) == 6);
    CHECK(m.n_edges() == 30);
    CHECK(euler(m) == 2);
    // Flipping back restores the edge (0, 1).
    m.flip(e);
    consistent(m);
    CHECK(m.find_edge(V(0), V(1)) == e);
    CHECK(m.valence(V(0)) == 5);
  }
  SUBCASE("refused when the new edge exists (tetrahedron)") {
    IndexedMesh t;
    t.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    t.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    SurfaceMesh m = build(t);
    for (Edge e : m.edges()) CHECK_FALSE(m.is_flip_ok(e));
    CHECK_THROWS_AS(m.flip(Edge(0)), TopologyError);
    consistent(m);
  }
}

TEST_CASE("SurfaceMesh: collapse") {
  SUBCASE("interior edge of an icosahedron: V-1, E-3, F-2, Euler characteristic kept") {
    SurfaceMesh m = build(icosahedron());
    const Halfedge h = m.find_halfedge(V(0), V(1));
    REQUIRE(m.is_collapse_ok(h));
    m.collapse(h);
    consistent(m);
    CHECK(m.n_vertices() == 11);
    CHECK(m.n_edges() == 27);
    CHECK(m.n_faces() == 18);
    CHECK(euler(m) == 2);
    CHECK(m.is_deleted(V(0)));
    CHECK_FALSE(m.is_deleted(V(1)));
    CHECK(m.valence(V(1)) == 6);  // 5 + 5 - 4
    CHECK(m.position(V(1)) == icosahedron().positions[1]);
    // Former neighbours of 0 are now neighbours of 1; the apexes 5 and 7 lost one edge.
    for (Index w : {10u, 11u}) CHECK(m.find_edge(V(1), V(w)).is_valid());
    CHECK(m.valence(V(5)) == 4);
    CHECK(m.valence(V(7)) == 4);
    for (Face f : m.faces())
      for (Vertex v : m.vertices(f)) CHECK(v != V(0));
    m.garbage_collection();
    consistent(m);
    CHECK(m.vertices_size() == 11);
    CHECK(m.faces_size() == 18);
    // The result is still a closed oriented surface: rebuild it from its arrays.
    const SurfaceMesh again = build(m.to_indexed_mesh());
    CHECK(again.boundary_loops().empty());
    CHECK(euler(again) == 2);
  }
  SUBCASE("boundary edge of a disc: V-1, E-2, F-1") {
    SurfaceMesh m;
    m.add_vertex(Vec3(0, 0, 0));
    for (int i = 0; i < 6; ++i)
      m.add_vertex(Vec3(std::cos(i * std::numbers::pi / 3), std::sin(i * std::numbers::pi / 3), 0));
    for (Index i = 0; i < 6; ++i) m.add_triangle(V(0), V(1 + i), V(1 + (i + 1) % 6));
    const Halfedge h = m.find_halfedge(V(2), V(1));  // boundary: the face is on 1->2
    REQUIRE(m.is_boundary(h));
    REQUIRE(m.is_collapse_ok(h));
    m.collapse(h);
    consistent(m);
    CHECK(m.n_vertices() == 6);
    CHECK(m.n_edges() == 10);
    CHECK(m.n_faces() == 5);
    CHECK(euler(m) == 1);
    CHECK(loops(m) == Loops{{1, 6, 5, 4, 3}});
    CHECK(m.valence(V(0)) == 5);
  }
  SUBCASE("interior edge with a boundary endpoint: the kept vertex becomes boundary") {
    SurfaceMesh m;
    m.add_vertex(Vec3(0, 0, 0));
    for (int i = 0; i < 6; ++i)
      m.add_vertex(Vec3(std::cos(i * std::numbers::pi / 3), std::sin(i * std::numbers::pi / 3), 0));
    for (Index i = 0; i < 6; ++i) m.add_triangle(V(0), V(1 + i), V(1 + (i + 1) % 6));
    const Halfedge h = m.find_halfedge(V(1), V(0));  // removes ring vertex 1
    REQUIRE(m.is_collapse_ok(h));
    m.collapse(h);
    consistent(m);
    CHECK(m.n_vertices() == 6);
    CHECK(m.n_faces() == 4);
    CHECK(euler(m) == 1);
    CHECK(m.is_boundary(V(0)));
    CHECK(loops(m) == Loops{{0, 6, 5, 4, 3, 2}});
  }
  SUBCASE("refusals leave the mesh unchanged") {
    // Tetrahedron: the apexes have valence 3.
    IndexedMesh t;
    t.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    t.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    SurfaceMesh m = build(t);
    for (Halfedge h : m.halfedges()) CHECK_FALSE(m.is_collapse_ok(h));
    CHECK_THROWS_AS(m.collapse(Halfedge(0)), TopologyError);
    consistent(m);
    CHECK(m.n_faces() == 4);
    // Triangular bipyramid: a and b share the neighbour c besides the apexes N, S.
    IndexedMesh bp;
    bp.positions = {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(-0.5, 0.8, 0), Vec3(-0.5, -0.8, 0)};
    bp.triangles = {{0, 2, 3}, {0, 3, 4}, {0, 4, 2}, {1, 3, 2}, {1, 4, 3}, {1, 2, 4}};
    SurfaceMesh b = build(bp);
    CHECK_FALSE(b.is_collapse_ok(b.find_halfedge(V(2), V(3))));  // link condition
    CHECK(b.is_collapse_ok(b.find_halfedge(V(0), V(2))));
    // Interior edge between two boundary vertices.
    SurfaceMesh s;
    for (int i = 0; i < 4; ++i) s.add_vertex(Vec3(i % 2, i / 2, 0));
    s.add_triangle(V(0), V(1), V(2));
    s.add_triangle(V(2), V(1), V(3));
    CHECK_FALSE(s.is_collapse_ok(s.find_halfedge(V(1), V(2))));
    CHECK_FALSE(s.is_collapse_ok(s.find_halfedge(V(2), V(1))));
  }
}

TEST_CASE("SurfaceMesh: split_face and split_edge") {
  SUBCASE("split_face: 1 -> 3 faces, the new vertex has valence 3") {
    SurfaceMesh m;
    m.add_vertex(Vec3(0, 0, 0));
    m.add_vertex(Vec3(1, 0, 0));
    m.add_vertex(Vec3(0, 1, 0));
    const Face f = m.add_triangle(V(0), V(1), V(2));
    const Vertex v = m.split_face(f, Vec3(0.25, 0.25, 0));
    consistent(m);
    CHECK(m.n_vertices() == 4);
    CHECK(m.n_edges() == 6);
    CHECK(m.n_faces() == 3);
    CHECK(m.valence(v) == 3);
    CHECK_FALSE(m.is_boundary(v));
    for (Index i = 0; i < 3; ++i) CHECK(m.valence(V(i)) == 3);
    for (Face g : m.faces()) CHECK(normal(m, g).z() > 0);
    CHECK(loops(m) == Loops{{0, 2, 1}});
    CHECK(m.position(v) == Vec3(0.25, 0.25, 0));
  }
  SUBCASE("split_edge, interior: 2 -> 4 faces, valence 4") {
    SurfaceMesh m;
    m.add_vertex(Vec3(0, 0, 0));
    m.add_vertex(Vec3(2, 0, 0));
    m.add_vertex(Vec3(1, 1, 0));
    m.add_vertex(Vec3(1, -1, 0));
    m.add_triangle(V(0), V(1), V(2));
    m.add_triangle(V(1), V(0), V(3));
    const Edge e = m.find_edge(V(0), V(1));
    const Vertex a = m.from_vertex(m.halfedge(e, 0));
    const Vertex v = m.split_edge(e, Vec3(1, 0, 0));
    consistent(m);
    CHECK(m.n_vertices() == 5);
    CHECK(m.n_edges() == 8);
    CHECK(m.n_faces() == 4);
    CHECK(m.valence(v) == 4);
    CHECK_FALSE(m.is_boundary(v));
    CHECK(m.from_vertex(m.halfedge(e, 0)) == a);
    CHECK(m.to_vertex(m.halfedge(e, 0)) == v);
    CHECK_FALSE(m.find_edge(V(0), V(1)).is_valid());
    for (Index w : {0u, 1u, 2u, 3u}) CHECK(m.find_edge(v, V(w)).is_valid());
    for (Face g : m.faces()) CHECK(normal(m, g).z() > 0);
    CHECK(loops(m) == Loops{{0, 2, 1, 3}});
  }
  SUBCASE("split_edge, boundary: 1 -> 2 faces, the loop gets the new vertex") {
    // Two configurations: the face on halfedge(e, 0) (a single triangle), or on
    // halfedge(e, 1) (the face on halfedge(e, 0) was deleted).
    for (int config = 0; config < 2; ++config) {
      SurfaceMesh m;
      m.add_vertex(Vec3(0, 0, 0));
      m.add_vertex(Vec3(1, 0, 0));
      m.add_vertex(Vec3(0, 1, 0));
      const Face f = m.add_triangle(V(0), V(1), V(2));
      if (config == 1) {
        m.add_vertex(Vec3(0.5, -1, 0));
        m.add_triangle(V(1), V(0), V(3));
        m.delete_face(f);
      }
      const Edge e = m.find_edge(V(0), V(1));
      REQUIRE(m.is_boundary(m.halfedge(e, 0)) == (config == 1));
      CHECK(m.n_vertices() == 3);
      const Vertex v = m.split_edge(e, Vec3(0.5, 0, 0));
      consistent(m);
      CHECK(m.n_vertices() == 4);
      CHECK(m.n_edges() == 5);
      CHECK(m.n_faces() == 2);
      CHECK(m.valence(v) == 3);
      CHECK(m.is_boundary(v));
      CHECK(m.is_boundary(m.halfedge(v)));
      const auto ls = loops(m);
      REQUIRE(ls.size() == 1);
      CHECK(ls[0].size() == 4);
      CHECK(std::count(ls[0].begin(), ls[0].end(), v.idx()) == 1);
      for (Face g : m.faces()) CHECK(normal(m, g).z() > 0);
    }
  }
}

TEST_CASE("SurfaceMesh: delete_face, delete_vertex and garbage_collection remap properties") {
  const IndexedMesh ico = icosahedron();
  SurfaceMesh m = build(ico);
  auto vid = m.add_vertex_property<int>("v:id", -1);
  for (Vertex v : m.vertices()) vid[v] = int(v.idx());
  // The original triangles and edges, by vertex ids, to recognise the faces
  // and edges that survive the compaction.
  auto canonical = [](std::array<Index, 3> t) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return t;
  };
  std::set<std::array<Index, 3>> triangles;
  std::set<std::pair<Index, Index>> edges;
  for (const auto& t : ico.triangles) {
    triangles.insert(canonical(t));
    for (int i = 0; i < 3; ++i) edges.insert(std::minmax(t[i], t[(i + 1) % 3]));
  }

  m.delete_face(Face(0));  // (0, 11, 5): a triangular hole
  consistent(m);
  CHECK(m.n_faces() == 19);
  CHECK(m.n_edges() == 30);
  CHECK(m.n_vertices() == 12);
  CHECK(loops(m) == Loops{{0, 11, 5}});
  CHECK(m.is_deleted(Face(0)));
  CHECK(m.has_garbage());

  m.delete_face(Face(1));  // (0, 5, 1) shares the edge (0, 5): it goes away
  consistent(m);
  CHECK(m.n_faces() == 18);
  CHECK(m.n_edges() == 29);
  CHECK_FALSE(m.find_edge(V(0), V(5)).is_valid());
  CHECK(loops(m) == Loops{{0, 11, 5, 1}});

  m.delete_vertex(V(3));  // its five faces, then the vertex
  consistent(m);
  CHECK(m.is_deleted(V(3)));
  CHECK(m.n_vertices() == 11);
  CHECK(m.n_faces() == 13);
  CHECK(m.boundary_loops().size() == 2);

  const std::size_t nv = m.n_vertices(), ne = m.n_edges(), nf = m.n_faces();
  m.garbage_collection();
  consistent(m);
  CHECK_FALSE(m.has_garbage());
  CHECK(m.vertices_size() == nv);
  CHECK(m.edges_size() == ne);
  CHECK(m.faces_size() == nf);
  CHECK(m.halfedges_size() == 2 * ne);
  // The handles taken before still read the compacted data.
  std::set<int> ids;
  for (Vertex v : m.vertices()) {
    REQUIRE(vid[v] >= 0);
    ids.insert(vid[v]);
    CHECK(m.position(v) == ico.positions[std::size_t(vid[v])]);
  }
  CHECK(ids.size() == 11);
  CHECK(ids.count(3) == 0);
  // Every face and edge left is an original one, oriented as it was, and none
  // of the deleted faces (0 and 1) or of vertex 3's is among them.
  std::set<std::array<Index, 3>> kept;
  for (Face f : m.faces()) {
    std::array<Index, 3> now{};
    int i = 0;
    for (Vertex v : m.vertices(f)) now[i++] = Index(vid[v]);
    CHECK(triangles.count(canonical(now)) == 1);
    CHECK(std::find(now.begin(), now.end(), Index(3)) == now.end());
    kept.insert(canonical(now));
  }
  CHECK(kept.size() == nf);
  CHECK(kept.count(canonical(ico.triangles[0])) == 0);
  CHECK(kept.count(canonical(ico.triangles[1])) == 0);
  for (Edge e : m.edges()) CHECK(edges.count(std::minmax(Index(vid[m.vertex(e, 0)]), Index(vid[m.vertex(e, 1)]))) == 1);
  CHECK(loops(m).size() == 2);
}

TEST_CASE("SurfaceMesh: deleting the last face removes its edges and vertices") {
  SurfaceMesh m;
  for (int i = 0; i < 3; ++i) m.add_vertex(Vec3(i, i * i, 0));
  const Face f = m.add_triangle(V(0), V(1), V(2));
  m.delete_face(f);
  consistent(m);
  CHECK(m.n_faces() == 0);
  CHECK(m.n_edges() == 0);
  CHECK(m.n_vertices() == 0);
  m.garbage_collection();
  CHECK(m.vertices_size() == 0);
  CHECK(m.halfedges_size() == 0);
}

TEST_CASE("SurfaceMesh: property API") {
  SurfaceMesh m = build(octahedron());
  auto w = m.add_vertex_property<double>("v:weight", 2.5);
  CHECK(w.is_valid());
  CHECK(w.name() == "v:weight");
  CHECK(w[V(3)] == 2.5);
  CHECK_THROWS_AS(m.add_vertex_property<int>("v:weight"), std::invalid_argument);
  CHECK(m.get_vertex_property<double>("v:weight").is_valid());
  CHECK_FALSE(m.get_vertex_property<int>("v:weight").is_valid());  // wrong type
  w[V(3)] = 7.0;
  CHECK(m.vertex_property<double>("v:weight")[V(3)] == 7.0);  // get-or-add finds it
  // New elements get the default value.
  const Vertex v = m.add_vertex(Vec3(9, 9, 9));
  CHECK(w[v] == 2.5);
  // Boolean properties (std::vector<bool> underneath) work like the others.
  auto locked = m.vertex_property<bool>("v:locked", false);
  locked[V(1)] = true;
  CHECK(locked[V(1)]);
  CHECK_FALSE(locked[V(2)]);
  m.remove_vertex_property(w);
  CHECK_FALSE(w.is_valid());
  CHECK_FALSE(m.has_vertex_property("v:weight"));
  auto pts = m.get_vertex_property<Vec3>("v:point");
  CHECK(pts[V(0)] == Vec3(1, 0, 0));
  CHECK_THROWS_AS(m.remove_vertex_property(pts), std::invalid_argument);
  CHECK(m.has_vertex_property("v:point"));
  // A typed key names the property and its type once.
  constexpr VertexPropertyKey<double> kWeight{"v:weight"};
  auto k = m.vertex_property(kWeight, 1.5);
  CHECK(k[V(2)] == 1.5);
  CHECK(m.has_vertex_property(kWeight));
  CHECK(m.get_vertex_property(kWeight)[V(2)] == 1.5);
  CHECK_THROWS_AS(m.add_vertex_property(kWeight), std::invalid_argument);
  CHECK_FALSE(m.has_vertex_property(VertexPropertyKey<int>{"v:weight"}));  // same name, another type
}

TEST_CASE("SurfaceMesh: copies are deep, moves transfer") {
  SurfaceMesh a = build(octahedron());
  auto tag = a.add_vertex_property<int>("v:tag", 1);
  SurfaceMesh b = a;
  auto btag = b.get_vertex_property<int>("v:tag");
  REQUIRE(btag.is_valid());
  btag[V(0)] = 5;
  b.position(V(0)) = Vec3(7, 7, 7);
  b.delete_face(Face(0));
  CHECK(tag[V(0)] == 1);
  CHECK(a.position(V(0)) == Vec3(1, 0, 0));
  CHECK(a.n_faces() == 8);
  CHECK(b.n_faces() == 7);
  consistent(a);
  consistent(b);

  SurfaceMesh c = std::move(b);
  consistent(c);
  CHECK(c.n_faces() == 7);
  CHECK(c.get_vertex_property<int>("v:tag")[V(0)] == 5);
  CHECK(b.n_vertices() == 0);  // NOLINT(bugprone-use-after-move): documented state
  b.add_vertex(Vec3(0, 0, 0));
  consistent(b);
  CHECK(b.n_vertices() == 1);
}

TEST_CASE("SurfaceMesh: deleting random faces and adding them back in random order closes the mesh") {
  // The intermediate meshes have holes, pinched vertices and fans in arbitrary
  // order around a vertex: every case add_triangle has to handle.
  const unsigned seed = 4242;
  INFO("seed = " << seed);
  std::mt19937 rng(seed);
  const IndexedMesh base = sphere(2);
  for (int run = 0; run < 30; ++run) {
    SurfaceMesh m = build(base);
    std::vector<Face> all(m.faces().begin(), m.faces().end());
    std::shuffle(all.begin(), all.end(), rng);
    const std::size_t k = std::size_t(20 + 10 * run);
    std::vector<std::array<Index, 3>> removed;
    for (std::size_t i = 0; i < k; ++i) {
      std::array<Index, 3> t{};
      int c = 0;
      for (Vertex v : m.vertices(all[i])) t[c++] = v.idx();
      removed.push_back(t);
      m.delete_face(all[i]);
    }
    consistent(m);
    CHECK(m.n_faces() == base.triangles.size() - k);
    CHECK_FALSE(m.boundary_loops().empty());
    m.garbage_collection();
    // Deleted vertices come back as new vertices at the same place.
    std::map<Index, Vertex> revive;
    std::vector<Vec3> pos = base.positions;
    auto vertex_of = [&](Index old) -> Vertex {
      for (Vertex v : m.vertices())
        if (m.position(v) == pos[old]) return v;
      auto it = revive.find(old);
      if (it == revive.end()) it = revive.emplace(old, m.add_vertex(pos[old])).first;
      return it->second;
    };
    std::shuffle(removed.begin(), removed.end(), rng);
    for (const auto& t : removed) {
      m.add_triangle(vertex_of(t[0]), vertex_of(t[1]), vertex_of(t[2]));
      consistent(m);
    }
    CHECK(m.n_faces() == base.triangles.size());
    CHECK(m.n_vertices() == base.positions.size());
    CHECK(m.boundary_loops().empty());
    CHECK(euler(m) == 2);
    for (Vertex v : m.vertices()) CHECK(m.is_manifold(v));
  }
}

TEST_CASE("SurfaceMesh: random refinement operations keep a valid oriented surface") {
  // On a closed sphere and on a sphere with holes (boundary edges and vertices).
  for (const bool open : {false, true}) {
    CAPTURE(open);
    const unsigned seed = open ? 778 : 777;
    INFO("seed = " << seed);
    std::mt19937 rng(seed);
    SurfaceMesh m = build(sphere(2));
    if (open) {
      // Seven holes: faces with no common vertex, so that every vertex stays manifold.
      std::set<Index> used;
      int holes = 0;
      for (Index f = 0; f < m.faces_size() && holes < 7; f += 37) {
        std::vector<Vertex> vs(m.vertices(Face(f)).begin(), m.vertices(Face(f)).end());
        if (std::any_of(vs.begin(), vs.end(), [&](Vertex v) { return used.count(v.idx()) > 0; })) continue;
        for (Vertex v : vs) used.insert(v.idx());
        m.delete_face(Face(f));
        ++holes;
      }
      REQUIRE(holes == 7);
      m.garbage_collection();
      for (Vertex v : m.vertices()) REQUIRE(m.is_manifold(v));
    }
    const long long chi = euler(m);
    CHECK(chi == (open ? 2 - 7 : 2));
    int flips = 0, collapses = 0, face_splits = 0, edge_splits = 0;
    int boundary_collapses = 0, boundary_splits = 0, boundary_vertex_collapses = 0;
    for (int step = 0; step < 1500; ++step) {
      const std::size_t nv = m.n_vertices(), ne = m.n_edges(), nf = m.n_faces();
      const int op = int(rng() % 4);
      if (op == 0) {
        const Edge e(Index(rng() % m.edges_size()));
        if (!m.is_valid(e) || !m.is_flip_ok(e)) continue;
        const Vertex a = m.vertex(e, 0), b = m.vertex(e, 1);
        m.flip(e);
        CHECK_FALSE(m.find_edge(a, b).is_valid());
        CHECK(m.n_edges() == ne);
        ++flips;
      } else if (op == 1) {
        const Halfedge h(Index(rng() % m.halfedges_size()));
        if (!m.is_valid(h) || !m.is_collapse_ok(h)) continue;
        const Vertex gone = m.from_vertex(h);
        const bool boundary_edge = m.is_boundary(m.edge(h));
        boundary_collapses += boundary_edge ? 1 : 0;
        boundary_vertex_collapses += !boundary_edge && m.is_boundary(gone) ? 1 : 0;
        m.collapse(h);
        CHECK(m.is_deleted(gone));
        CHECK(m.n_vertices() == nv - 1);
        CHECK(m.n_edges() == ne - (boundary_edge ? 2 : 3));
        CHECK(m.n_faces() == nf - (boundary_edge ? 1 : 2));
        ++collapses;
      } else if (op == 2) {
        const Face f(Index(rng() % m.faces_size()));
        if (!m.is_valid(f)) continue;
        Vec3 c = Vec3::Zero();
        for (Vertex v : m.vertices(f)) c += m.position(v) / 3.0;
        const Vertex v = m.split_face(f, c);
        CHECK(m.valence(v) == 3);
        CHECK(m.n_faces() == nf + 2);
        ++face_splits;
      } else {
        const Edge e(Index(rng() % m.edges_size()));
        if (!m.is_valid(e)) continue;
        const bool boundary_edge = m.is_boundary(e);
        const Vertex v = m.split_edge(e, 0.5 * (m.position(m.vertex(e, 0)) + m.position(m.vertex(e, 1))));
        CHECK(m.valence(v) == (boundary_edge ? 3u : 4u));
        CHECK(m.is_boundary(v) == boundary_edge);
        CHECK(m.n_faces() == nf + (boundary_edge ? 1 : 2));
        ++edge_splits;
        boundary_splits += boundary_edge ? 1 : 0;
      }
      consistent(m);
      CHECK(euler(m) == chi);
      if (step % 300 == 299) {
        m.garbage_collection();
        consistent(m);
      }
    }
    INFO("flips " << flips << ", collapses " << collapses << ", face splits " << face_splits << ", edge splits "
                  << edge_splits);
    CHECK(flips > 50);
    CHECK(collapses > 50);
    CHECK(face_splits > 50);
    CHECK(edge_splits > 50);
    if (open) {
      INFO("boundary collapses " << boundary_collapses << ", interior edges from a boundary vertex "
                                 << boundary_vertex_collapses << ", boundary splits " << boundary_splits);
      CHECK(boundary_collapses > 0);
      CHECK(boundary_vertex_collapses > 0);
      CHECK(boundary_splits > 0);
    }
    for (Vertex v : m.vertices()) CHECK(m.is_manifold(v));
    // The verifier agrees (topology only: random flips may fold the geometry).
    MeshCheckOptions opt;
    opt.check_self_intersections = false;
    const MeshCheckReport r = check_mesh(m.to_indexed_mesh(), opt);
    CHECK(r.closed == !open);
    CHECK(r.edge_manifold);
    CHECK(r.vertex_manifold);
    CHECK(r.oriented);
    REQUIRE(r.components.size() == 1);
    CHECK(r.components[0].euler == chi);
  }
}

TEST_CASE("SurfaceMesh: release_faces keeps the vertices, their positions and properties") {
  // The pipeline's output reads the faces, releases them and then reads the
  // vertex properties: they must be those of to_indexed_mesh()'s vertices.
  SurfaceMesh m = build(sphere(2));
  const IndexedMesh before = m.to_indexed_mesh();
  auto tag = m.add_vertex_property<int>("v:tag", 0);
  for (Vertex v : m.vertices()) tag[v] = int(v.idx()) * 3;
  m.delete_vertex(Vertex(5));  // a deleted vertex stays left out
  const std::size_t nv = m.n_vertices();
  m.release_faces();
  CHECK(m.n_faces() == 0);
  CHECK(m.halfedges_size() == 0);
  CHECK(m.n_vertices() == nv);
  std::size_t i = 0;
  for (Vertex v : m.vertices()) {
    CHECK(v.idx() != 5);
    CHECK(tag[v] == int(v.idx()) * 3);
    CHECK(m.position(v) == before.positions[v.idx()]);
    ++i;
  }
  CHECK(i == nv);
}

}  // TEST_SUITE

TEST_CASE("SurfaceMesh binary files: the mesh read back is the mesh written, element for element") {
  // A mesh with deleted elements (a collapse, not compacted) and vertex
  // properties of several types: every link, flag and value must come back,
  // and the same operation on both meshes must give the same mesh.
  SurfaceMesh m = build(skinmesh::test::sphere(1));
  auto cell = m.add_vertex_property<Index>("v:cell", skinmesh::kInvalidIndex);
  auto weight = m.add_vertex_property<double>("v:weight", -1.5);
  auto normal = m.add_vertex_property<Vec3>("v:normal", Vec3(0, 0, 1));
  auto mark = m.add_vertex_property<std::uint8_t>("v:mark", 7);
  for (Vertex v : m.vertices()) {
    cell[v] = 3 * v.idx() + 1;
    weight[v] = 0.1 * v.idx() + 1e-17;
    normal[v] = m.position(v).normalized();
    mark[v] = static_cast<std::uint8_t>(v.idx() % 5);
  }
  Halfedge h(0);
  while (!m.is_collapse_ok(h)) h = Halfedge(h.idx() + 1);
  m.collapse(h);
  REQUIRE(m.has_garbage());

  std::stringstream file;
  m.write_binary(file);
  SurfaceMesh r = SurfaceMesh::read_binary(file, "mesh.bin");
  r.check_consistency();
  REQUIRE(r.vertices_size() == m.vertices_size());
  REQUIRE(r.halfedges_size() == m.halfedges_size());
  REQUIRE(r.faces_size() == m.faces_size());
  CHECK(r.n_vertices() == m.n_vertices());
  CHECK(r.n_edges() == m.n_edges());
  CHECK(r.n_faces() == m.n_faces());
  auto rcell = r.get_vertex_property<Index>("v:cell");
  auto rweight = r.get_vertex_property<double>("v:weight");
  auto rnormal = r.get_vertex_property<Vec3>("v:normal");
  auto rmark = r.get_vertex_property<std::uint8_t>("v:mark");
  REQUIRE((rcell && rweight && rnormal && rmark));
  for (Vertex v : m.vertices()) {
    CHECK(r.position(v) == m.position(v));
    CHECK(r.halfedge(v) == m.halfedge(v));
    CHECK(rcell[v] == cell[v]);
    CHECK(rweight[v] == weight[v]);
    CHECK(rnormal[v] == normal[v]);
    CHECK(rmark[v] == mark[v]);
  }
  for (Index i = 0; i < m.vertices_size(); ++i) CHECK(r.is_deleted(Vertex(i)) == m.is_deleted(Vertex(i)));
  for (Index i = 0; i < m.halfedges_size(); ++i) {
    const Halfedge g(i);
    CHECK(r.to_vertex(g) == m.to_vertex(g));
    if (m.is_deleted(Edge(i / 2))) continue;
    CHECK(r.next(g) == m.next(g));
    CHECK(r.prev(g) == m.prev(g));
    CHECK(r.face(g) == m.face(g));
  }
  for (Index i = 0; i < m.faces_size(); ++i) CHECK(r.is_deleted(Face(i)) == m.is_deleted(Face(i)));

  // The defaults come back too: a vertex added to both gets the same values.
  const Vertex a = m.add_vertex(Vec3(5, 5, 5)), b = r.add_vertex(Vec3(5, 5, 5));
  REQUIRE(a == b);
  CHECK(rcell[b] == cell[a]);
  CHECK(rweight[b] == -1.5);
  CHECK(rnormal[b] == Vec3(0, 0, 1));
  CHECK(rmark[b] == 7);
  // The same compaction on both: the same indexed mesh.
  m.garbage_collection();
  r.garbage_collection();
  const IndexedMesh im = m.to_indexed_mesh(), ir = r.to_indexed_mesh();
  CHECK(im.positions == ir.positions);
  CHECK(im.triangles == ir.triangles);
}

TEST_CASE("SurfaceMesh binary files: a damaged or foreign stream is refused with the file named") {
  SurfaceMesh m = build(skinmesh::test::icosahedron());
  std::stringstream file;
  m.write_binary(file);
  const std::string bytes = file.str();
  auto read = [](const std::string& s) {
    std::stringstream is(s);
    return SurfaceMesh::read_binary(is, "part.bin");
  };
  CHECK(read(bytes).n_faces() == 20);
  for (std::size_t cut : {std::size_t{0}, std::size_t{5}, std::size_t{12}, bytes.size() / 2, bytes.size() - 1}) {
    CAPTURE(cut);
    CHECK_THROWS_AS(read(bytes.substr(0, cut)), skinmesh::InputError);
  }
  std::string foreign = bytes;
  foreign[0] = 'X';
  CHECK_THROWS_WITH_AS(read(foreign), doctest::Contains("part.bin"), skinmesh::InputError);
  std::string swapped = bytes;
  std::swap(swapped[8], swapped[11]);  // the byte-order marker
  CHECK_THROWS_WITH_AS(read(swapped), doctest::Contains("byte order"), skinmesh::InputError);
}
