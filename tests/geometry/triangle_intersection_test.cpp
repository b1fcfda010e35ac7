// tests/geometry/triangle_intersection_test.cpp: exact segment/triangle and
// triangle/triangle tests (geometry/kernel/triangle_intersection) on hand cases, on
// near-coplanar inputs where a floating-point test decides wrongly, and against
// the mesh-triangle variants.
#include <doctest/doctest.h>

#include <random>

#include "geometry/kernel/predicates.h"
#include "geometry/kernel/triangle_intersection.h"

using skinmesh::Index;
using skinmesh::Vec3;
using namespace skinmesh::geometry;

namespace {

// Both argument orders and both vertex orders give the same answer.
bool tt(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1, const Vec3& b2) {
  const bool r = triangles_intersect(a0, a1, a2, b0, b1, b2);
  CHECK(triangles_intersect(b0, b1, b2, a0, a1, a2) == r);
  CHECK(triangles_intersect(a2, a1, a0, b1, b0, b2) == r);
  CHECK(triangles_intersect(a1, a2, a0, b2, b0, b1) == r);
  return r;
}

}  // namespace

TEST_SUITE("geometry") {

TEST_CASE("triangle_intersection: degenerate triangles are detected exactly") {
  CHECK(is_degenerate_triangle(Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(3, 3, 3)));
  CHECK(is_degenerate_triangle(Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(4, 5, 6)));
  CHECK_FALSE(is_degenerate_triangle(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)));
  // Collinear in two projections, not in the third.
  CHECK_FALSE(is_degenerate_triangle(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 1e-300)));
  // 0.1 + 0.2 != 0.3 in doubles: these three points are not collinear.
  CHECK_FALSE(is_degenerate_triangle(Vec3(0, 0, 0), Vec3(0.1, 0.1, 0.1), Vec3(0.3, 0.1 + 0.2, 0.3)));
}

TEST_CASE("triangle_intersection: hand cases in general position") {
  const Vec3 a0(0, 0, 0), a1(1, 0, 0), a2(0, 1, 0);
  SUBCASE("disjoint, parallel planes") { CHECK_FALSE(tt(a0, a1, a2, Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1))); }
  SUBCASE("disjoint, crossing planes but apart") {
    CHECK_FALSE(tt(a0, a1, a2, Vec3(2, 2, -1), Vec3(2, 2, 1), Vec3(3, 2, 0)));
  }
  SUBCASE("piercing") { CHECK(tt(a0, a1, a2, Vec3(0.2, 0.2, -1), Vec3(0.2, 0.2, 1), Vec3(2, 2, 0.5))); }
  SUBCASE("a vertex touches the interior") {
    CHECK(tt(a0, a1, a2, Vec3(0.25, 0.25, 0), Vec3(0.25, 0.25, 1), Vec3(1, 1, 1)));
  }
  SUBCASE("vertex touches vertex") { CHECK(tt(a0, a1, a2, Vec3(1, 0, 0), Vec3(2, 0, 1), Vec3(2, 1, 1))); }
  SUBCASE("a vertex just above the plane does not touch") {
    CHECK_FALSE(tt(a0, a1, a2, Vec3(0.25, 0.25, 1e-300), Vec3(0.25, 0.25, 1), Vec3(1, 1, 1)));
  }
  SUBCASE("sharing an edge, not coplanar") {
    CHECK(tt(a0, a1, a2, a1, a0, Vec3(0.5, -1, 1)));
    CHECK_FALSE(triangles_intersect_beyond_edge(a0, a1, a2, Vec3(0.5, -1, 1)));
    CHECK_FALSE(triangles_intersect_beyond_edge(a0, a1, a2, Vec3(0.5, 1, 1)));
  }
  SUBCASE("edge crossing an edge") { CHECK(tt(a0, a1, a2, Vec3(0.5, -1, 0), Vec3(0.5, 1, 0), Vec3(0.5, 0, 1))); }
}

TEST_CASE("triangle_intersection: coplanar cases") {
  const Vec3 a0(0, 0, 0), a1(4, 0, 0), a2(0, 4, 0);
  SUBCASE("overlapping") { CHECK(tt(a0, a1, a2, Vec3(1, 1, 0), Vec3(5, 1, 0), Vec3(1, 5, 0))); }
  SUBCASE("one inside the other") { CHECK(tt(a0, a1, a2, Vec3(1, 1, 0), Vec3(2, 1, 0), Vec3(1, 2, 0))); }
  SUBCASE("touching at a point") { CHECK(tt(a0, a1, a2, Vec3(2, 2, 0), Vec3(5, 2, 0), Vec3(2, 5, 0))); }
  SUBCASE("apart") { CHECK_FALSE(tt(a0, a1, a2, Vec3(3, 3, 0), Vec3(5, 3, 0), Vec3(3, 5, 0))); }
  SUBCASE("in a tilted plane (no axis-aligned projection is trivial)") {
    // Plane x + y + z = 0 with integer points: exact.
    const Vec3 b0(0, 0, 0), b1(4, 0, -4), b2(0, 4, -4);
    CHECK(tt(b0, b1, b2, Vec3(1, 1, -2), Vec3(5, 1, -6), Vec3(1, 5, -6)));
    CHECK_FALSE(tt(b0, b1, b2, Vec3(3, 3, -6), Vec3(5, 3, -8), Vec3(3, 5, -8)));
    CHECK(tt(b0, b1, b2, Vec3(2, 2, -4), Vec3(5, 2, -7), Vec3(2, 5, -7)));
  }
  SUBCASE("sharing an edge: overlap iff the apexes are on the same side") {
    CHECK(triangles_intersect_beyond_edge(a0, a1, a2, Vec3(3, 1, 0)));
    CHECK_FALSE(triangles_intersect_beyond_edge(a0, a1, a2, Vec3(3, -1, 0)));
    CHECK(triangles_intersect_beyond_edge(a1, a0, a2, Vec3(3, 1, 0)));
  }
  SUBCASE("sharing a vertex") {
    // Same side of the vertex: overlap.
    CHECK(triangles_intersect_beyond_vertex(a0, a1, a2, Vec3(1, 3, 0), Vec3(3, 1, 0)));
    // Opposite quadrant: only the shared vertex.
    CHECK_FALSE(triangles_intersect_beyond_vertex(a0, a1, a2, Vec3(-1, -3, 0), Vec3(-3, -1, 0)));
    // Touching along the x axis beyond the vertex: an edge of one lies on an edge of the other.
    CHECK(triangles_intersect_beyond_vertex(a0, a1, a2, Vec3(2, 0, 0), Vec3(1, -1, 0)));
    // Sharing only the vertex, not coplanar.
    CHECK_FALSE(triangles_intersect_beyond_vertex(a0, a1, a2, Vec3(-1, 0, 1), Vec3(0, -1, 1)));
    // Not coplanar, but the other triangle passes through this one's interior.
    CHECK(triangles_intersect_beyond_vertex(a0, a1, a2, Vec3(1, 1, -1), Vec3(1, 1, 1)));
  }
}

TEST_CASE("triangle_intersection: segment against triangle") {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  CHECK(segment_intersects_triangle(Vec3(0.2, 0.2, -1), Vec3(0.2, 0.2, 1), a, b, c));
  CHECK_FALSE(segment_intersects_triangle(Vec3(0.2, 0.2, 0.5), Vec3(0.2, 0.2, 1), a, b, c));
  CHECK(segment_intersects_triangle(Vec3(0.2, 0.2, 0), Vec3(0.2, 0.2, 1), a, b, c));   // endpoint on it
  CHECK(segment_intersects_triangle(Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1), a, b, c));  // through edge bc
  CHECK_FALSE(segment_intersects_triangle(Vec3(0.6, 0.6, -1), Vec3(0.6, 0.6, 1), a, b, c));
  CHECK(segment_intersects_triangle(Vec3(-1, -1, 0), Vec3(2, 2, 0), a, b, c));  // coplanar, crossing
  CHECK_FALSE(segment_intersects_triangle(Vec3(-1, 2, 0), Vec3(2, 2, 0), a, b, c));
  CHECK(segment_intersects_triangle(Vec3(0.1, 0.1, 0), Vec3(0.1, 0.1, 0), a, b, c));  // a point
  CHECK_THROWS_AS(segment_intersects_triangle(Vec3(0, 0, 0), Vec3(1, 1, 0), a, b, Vec3(2, 0, 0)),
                  std::invalid_argument);
}

TEST_CASE("triangle_intersection: near-coplanar inputs where floating point decides wrongly") {
  // Triangle A lies in the plane x + y + z = C with large integer coordinates:
  // orient3d's products need ~60 bits, so the plain double evaluation rounds.
  // A point P of that plane (exactly) inside A touches A; the naive test, which
  // trusts orient3d_fast, may put P strictly on one side and then call two
  // triangles disjoint although they touch. Seeded search for such a P.
  const double C = 3221225473.0;  // 3 * 2^30 + 1
  const Vec3 a0(3, 5, C - 8), a1(1999999973, 17, C - 1999999990), a2(13, 1999999931, C - 1999999944);
  const unsigned seed = 20240607;
  INFO("seed = " << seed);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::int64_t> coord(100, (std::int64_t(1) << 29));
  int fooled = 0, tried = 0;
  for (; tried < 2000 && fooled < 20; ++tried) {
    const double x = double(coord(rng)), y = double(coord(rng));
    const Vec3 p(x, y, C - x - y);  // exact: integers below 2^53
    REQUIRE(orient3d_exact(a0, a1, a2, p) == skinmesh::Sign::Zero);
    const double fast = orient3d_fast(a0, a1, a2, p);
    if (fast == 0.0) continue;
    // The other two vertices of B on the side the naive evaluation reports for P.
    const double s = fast > 0 ? 1.0 : -1.0;
    const Vec3 up = s * Vec3(1048576.0, 1048576.0, 1048576.0);  // off the plane by s * 3 * 2^20
    REQUIRE(orient3d(a0, a1, a2, p + up) == (s > 0 ? skinmesh::Sign::Positive : skinmesh::Sign::Negative));
    const Vec3 b1 = p + up, b2 = p + up + Vec3(4096.0, 0, 0);
    // Naive: all three of B on one side -> disjoint. Exact: they touch at P.
    CHECK(triangles_intersect(a0, a1, a2, p, b1, b2));
    // Moved by one unit off the plane to the far side, they are disjoint.
    const Vec3 q = p + Vec3(0, 0, s);
    CHECK(orient3d(a0, a1, a2, q) == orient3d(a0, a1, a2, b1));
    CHECK_FALSE(triangles_intersect(a0, a1, a2, q, b1, b2));
    ++fooled;
  }
  INFO("tried " << tried);
  CHECK(fooled == 20);  // the double evaluation really is wrong on these inputs
}

TEST_CASE("triangle_intersection: mesh triangles by index") {
  const std::vector<Vec3> P = {Vec3(0, 0, 0),  Vec3(4, 0, 0), Vec3(0, 4, 0),  Vec3(3, 1, 0),
                               Vec3(3, -1, 0), Vec3(1, 3, 1), Vec3(-1, -1, 0)};
  using T = std::array<Index, 3>;
  CHECK(mesh_triangles_intersect(T{0, 1, 2}, T{1, 0, 3}, P));        // shared edge, same side
  CHECK_FALSE(mesh_triangles_intersect(T{0, 1, 2}, T{1, 0, 4}, P));  // shared edge, opposite
  CHECK_FALSE(mesh_triangles_intersect(T{0, 1, 2}, T{2, 6, 5}, P));  // shared vertex only
  CHECK(mesh_triangles_intersect(T{0, 1, 2}, T{2, 3, 4}, P));        // shared vertex, overlap
  CHECK(mesh_triangles_intersect(T{0, 1, 2}, T{2, 0, 1}, P));        // same triangle
  // Distinct indices at equal positions are different vertices: touching counts.
  const std::vector<Vec3> Q = {Vec3(0, 0, 0), Vec3(1, 0, 0),  Vec3(0, 1, 0),
                               Vec3(0, 0, 0), Vec3(-1, 0, 1), Vec3(0, -1, 1)};
  CHECK(mesh_triangles_intersect(T{0, 1, 2}, T{3, 4, 5}, Q));
  CHECK_FALSE(mesh_triangles_intersect(T{0, 1, 2}, T{0, 4, 5}, Q));
}

TEST_CASE("triangle_intersection: beyond-vertex test equals the two segment tests on random grid inputs") {
  // Integer coordinates in a small range: many coplanar and touching cases.
  std::mt19937_64 rng(20261122);
  std::uniform_int_distribution<int> c(-2, 2);
  auto point = [&] { return Vec3(c(rng), c(rng), c(rng)); };
  int tested = 0, hits = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec3 s = point(), a1 = point(), a2 = point(), b1 = point(), b2 = point();
    if (is_degenerate_triangle(s, a1, a2) || is_degenerate_triangle(s, b1, b2)) continue;
    const bool want = segment_intersects_triangle(a1, a2, s, b1, b2) || segment_intersects_triangle(b1, b2, s, a1, a2);
    CHECK(triangles_intersect_beyond_vertex(s, a1, a2, b1, b2) == want);
    CHECK(triangles_intersect_beyond_vertex(s, b1, b2, a1, a2) == want);
    ++tested;
    hits += want;
  }
  CHECK(tested > 5000);
  CHECK(hits > 500);
  CHECK(tested - hits > 500);
}

}  // TEST_SUITE
