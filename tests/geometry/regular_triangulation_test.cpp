// tests/geometry/regular_triangulation_test.cpp: tests of
// geometry/triangulation/regular_triangulation. Every triangulation is checked by one verifier
// (structure, orientation, adjacency, volume, local and, for small inputs,
// global emptiness of the orthospheres with power_test_sos); small inputs are
// also compared with a brute force over all 4-subsets, which is exact for
// degenerate inputs too because SoS makes the perturbed input generic.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "core/errors.h"
#include "geometry/kernel/predicates.h"
#include "geometry/triangulation/regular_triangulation.h"
#include "tests/geometry/test_meshes.h"

namespace sg = skinmesh::geometry;
using sg::RegularTriangulation;
using sg::WeightedPoint;
using skinmesh::Index;
using skinmesh::kInvalidIndex;
using skinmesh::Sign;
using skinmesh::Vec3;
using skinmesh::test::integer_sphere;

namespace {

using Quad = std::array<Index, 4>;

std::vector<Quad> all_tets(const RegularTriangulation& rt) {
  std::vector<Quad> out;
  for (Index t = 0; t < rt.num_tets(); ++t) out.push_back(rt.tet(t));
  return out;
}

Quad sorted(Quad q) {
  std::sort(q.begin(), q.end());
  return q;
}

// Verifier ----------------------------------------------------------------------
// `global`: test every tetrahedron against every point (O(T n)); otherwise only
// against the opposite vertices of its neighbours (local regularity, which
// implies global regularity for a triangulation of a convex domain) and every
// redundant point against the tetrahedron containing it.
void verify(const RegularTriangulation& rt, bool global) {
  const Index np = rt.num_points();
  const Index n = rt.num_input_points();
  REQUIRE(np == n + 4);
  REQUIRE(rt.num_tets() >= 1);
  std::vector<char> used(np, 0);
  int outer_faces = 0;
  double volume = 0.0;
  for (Index t = 0; t < rt.num_tets(); ++t) {
    const Quad& q = rt.tet(t);
    for (const Index v : q) {
      REQUIRE(v < np);
      used[v] = 1;
    }
    REQUIRE(sorted(q)[0] != sorted(q)[1]);
    REQUIRE(sorted(q)[1] != sorted(q)[2]);
    REQUIRE(sorted(q)[2] != sorted(q)[3]);
    // Positive orientation (exact).
    REQUIRE(sg::orient3d(rt.point(q[0]).z, rt.point(q[1]).z, rt.point(q[2]).z, rt.point(q[3]).z) == Sign::Positive);
    volume += sg::orient3d_fast(rt.point(q[0]).z, rt.point(q[1]).z, rt.point(q[2]).z, rt.point(q[3]).z) / 6.0;
    for (int i = 0; i < 4; ++i) {
      const Index u = rt.neighbor(t, i);
      if (u == kInvalidIndex) {
        ++outer_faces;
        // An outer face has three bounding vertices.
        for (int k = 0; k < 4; ++k)
          if (k != i) CHECK(rt.is_bounding(q[k]));
        continue;
      }
      REQUIRE(u < rt.num_tets());
      // Symmetry: u sees t across the face opposite the one vertex of u not in t.
      int j = -1;
      for (int k = 0; k < 4; ++k)
        if (rt.neighbor(u, k) == t) j = k;
      REQUIRE(j >= 0);
      const Index opposite = rt.tet(u)[j];
      CHECK(rt.local_index(t, opposite) == -1);
      for (int k = 0; k < 4; ++k)
        if (k != i) CHECK(rt.local_index(u, q[k]) >= 0);
      // Local regularity: the opposite vertex is not in conflict.
      CHECK(rt.conflict(t, opposite) == Sign::Negative);
    }
  }
  CHECK(outer_faces == 4);
  // Vertices and redundant points.
  std::vector<Index> redundant = rt.redundant_points();
  CHECK(std::is_sorted(redundant.begin(), redundant.end()));
  std::vector<char> is_red(np, 0);
  for (const Index v : redundant) {
    REQUIRE(v < n);
    is_red[v] = 1;
  }
  for (Index v = 0; v < np; ++v) {
    CHECK(rt.is_vertex(v) == !is_red[v]);
    CHECK(bool(used[v]) == rt.is_vertex(v));
    if (rt.is_vertex(v)) {
      const Index t = rt.vertex_tet(v);
      REQUIRE(t != kInvalidIndex);
      CHECK(rt.local_index(t, v) >= 0);
    } else {
      CHECK(rt.vertex_tet(v) == kInvalidIndex);
      const Index t = rt.locate(rt.point(v).z);
      REQUIRE(t != kInvalidIndex);
      CHECK(rt.conflict(t, v) == Sign::Negative);
    }
  }
  for (Index v = n; v < np; ++v) CHECK(rt.is_bounding(v));
  // Volumes add up to the bounding tetrahedron's.
  const double big = sg::orient3d_fast(rt.point(n).z, rt.point(n + 1).z, rt.point(n + 2).z, rt.point(n + 3).z) / 6.0;
  CHECK(volume == doctest::Approx(std::abs(big)).epsilon(1e-9));
  // Euler characteristic of a triangulated ball: V - E + F - T = 1.
  std::set<std::pair<Index, Index>> edges;
  for (const Quad& q : all_tets(rt))
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) edges.insert({std::min(q[a], q[b]), std::max(q[a], q[b])});
  const long long V = np - Index(redundant.size()), T = rt.num_tets(), F = (4 * T + outer_faces) / 2,
                  E = static_cast<long long>(edges.size());
  CHECK(V - E + F - T == 1);
  if (global) {
    for (Index t = 0; t < rt.num_tets(); ++t)
      for (Index v = 0; v < np; ++v)
        if (rt.local_index(t, v) < 0) REQUIRE(rt.conflict(t, v) == Sign::Negative);
  }
}

// Brute force: the 4-subsets of all n + 4 points whose (SoS) orthosphere is
// empty of every other point, as sorted quadruples.
std::set<Quad> brute_force(const RegularTriangulation& rt) {
  const auto pts = rt.points();
  const Index np = static_cast<Index>(pts.size());
  std::set<Quad> out;
  for (Index a = 0; a < np; ++a)
    for (Index b = a + 1; b < np; ++b)
      for (Index c = b + 1; c < np; ++c)
        for (Index d = c + 1; d < np; ++d) {
          Quad q = {a, b, c, d};
          const Sign o = sg::orient3d(pts[a].z, pts[b].z, pts[c].z, pts[d].z);
          if (o == Sign::Zero) continue;
          if (o == Sign::Negative) std::swap(q[0], q[1]);
          bool empty = true;
          for (Index e = 0; e < np && empty; ++e) {
            if (e == a || e == b || e == c || e == d) continue;
            empty = sg::power_test_sos(pts[q[0]], pts[q[1]], pts[q[2]], pts[q[3]], pts[e], q[0], q[1], q[2], q[3], e) ==
                    Sign::Negative;
          }
          if (empty) out.insert(sorted(q));
        }
  return out;
}

std::set<Quad> tet_set(const RegularTriangulation& rt) {
  std::set<Quad> out;
  for (const Quad& q : all_tets(rt)) out.insert(sorted(q));
  return out;
}

void compare_with_brute_force(const std::vector<WeightedPoint>& pts) {
  const RegularTriangulation rt(pts);
  verify(rt, true);
  const std::set<Quad> expected = brute_force(rt);
  CHECK(tet_set(rt) == expected);
  CHECK(rt.num_tets() == expected.size());
}

std::vector<WeightedPoint> random_points(std::mt19937_64& rng, int n, double box, double rmin, double rmax) {
  std::uniform_real_distribution<double> c(-box, box), r(rmin, rmax);
  std::vector<WeightedPoint> pts;
  for (int i = 0; i < n; ++i) {
    // One draw per statement: the same numbers with every compiler.
    const double rad = r(rng);
    const double x = c(rng), y = c(rng), z = c(rng);
    pts.push_back({Vec3(x, y, z), rad * rad});
  }
  return pts;
}

double round3(double x) { return std::round(x * 1000.0) / 1000.0; }

}  // namespace

TEST_SUITE("geometry") {

TEST_CASE("hilbert_key: consecutive keys are face-adjacent cells") {
  std::vector<std::pair<std::uint64_t, std::array<int, 3>>> cells;
  for (int x = 0; x < 8; ++x)
    for (int y = 0; y < 8; ++y)
      for (int z = 0; z < 8; ++z) cells.push_back({sg::detail::hilbert_key(x, y, z), {x, y, z}});
  std::sort(cells.begin(), cells.end());
  // The corner sub-cube of side 8 is the first 512 cells of the curve.
  for (std::size_t i = 0; i < cells.size(); ++i) CHECK(cells[i].first == i);
  for (std::size_t i = 1; i < cells.size(); ++i) {
    const auto& a = cells[i - 1].second;
    const auto& b = cells[i].second;
    CHECK(std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]) == 1);
  }
}

TEST_CASE("regular triangulation: bad input throws InputError") {
  std::vector<WeightedPoint> none;
  CHECK_THROWS_AS(RegularTriangulation{none}, skinmesh::InputError);
  std::vector<WeightedPoint> nan = {{Vec3(0, 0, 0), 1.0}, {Vec3(1, std::numeric_limits<double>::quiet_NaN(), 0), 1.0}};
  CHECK_THROWS_AS(RegularTriangulation{nan}, skinmesh::InputError);
  // Outside the admissible range of the exact predicates (issue #7: 1e300 once
  // ended in an orient3d assertion).
  const std::vector<WeightedPoint> far = {{Vec3(0, 0, 0), 1.0}, {Vec3(1e300, 0, 0), 1.0}};
  CHECK_THROWS_AS(RegularTriangulation{far}, skinmesh::InputError);
  const std::vector<WeightedPoint> heavy = {{Vec3(0, 0, 0), 1e300}};
  CHECK_THROWS_AS(RegularTriangulation{heavy}, skinmesh::InputError);
  std::vector<WeightedPoint> inf = {{Vec3(0, 0, 0), std::numeric_limits<double>::infinity()}};
  CHECK_THROWS_AS(RegularTriangulation{inf}, skinmesh::InputError);
}

TEST_CASE("regular triangulation: 1, 2 and 3 points") {
  SUBCASE("one point") {
    const std::vector<WeightedPoint> pts = {{Vec3(1.5, -2, 3), 2.25}};
    const RegularTriangulation rt(pts);
    verify(rt, true);
    CHECK(rt.num_tets() == 4);
    CHECK(rt.is_vertex(0));
    CHECK(rt.redundant_points().empty());
    // Bounding tetrahedron: centred at the point, D = 50 * (0 + 1.5) Å.
    CHECK((rt.bounding_centre() - pts[0].z).norm() == 0.0);
    CHECK(rt.bounding_radius() == doctest::Approx(75.0));
    for (Index v = 1; v < 5; ++v) CHECK((rt.point(v).z - pts[0].z).norm() == doctest::Approx(75.0));
    compare_with_brute_force(pts);
  }
  SUBCASE("two points") { compare_with_brute_force({{Vec3(0, 0, 0), 1.0}, {Vec3(1.2, 0, 0), 0.8}}); }
  SUBCASE("three points") {
    compare_with_brute_force({{Vec3(0, 0, 0), 1.0}, {Vec3(1.2, 0, 0), 0.8}, {Vec3(0.4, 1.1, 0), 1.44}});
  }
  SUBCASE("one point of zero weight: L' = 1 Å") {
    const RegularTriangulation rt(std::vector<WeightedPoint>{{Vec3(0, 0, 0), 0.0}});
    CHECK(rt.bounding_radius() == doctest::Approx(50.0));
    verify(rt, true);
  }
}

TEST_CASE("regular triangulation: random weighted points equal the brute force") {
  for (const unsigned seed : {1u, 2u, 3u, 4u, 5u}) {
    INFO("seed " << seed);
    std::mt19937_64 rng(seed);
    compare_with_brute_force(random_points(rng, 14, 3.0, 0.5, 2.0));
  }
}

TEST_CASE("regular triangulation: degenerate small sets equal the brute force") {
  SUBCASE("cube corners and centre, equal weights (cospherical)") {
    std::vector<WeightedPoint> pts;
    for (int i = 0; i < 8; ++i) pts.push_back({Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1), 1.0});
    pts.push_back({Vec3(0.5, 0.5, 0.5), 1.0});
    compare_with_brute_force(pts);
  }
  SUBCASE("2 x 2 x 3 lattice, equal weights") {
    std::vector<WeightedPoint> pts;
    for (int x = 0; x < 2; ++x)
      for (int y = 0; y < 2; ++y)
        for (int z = 0; z < 3; ++z) pts.push_back({Vec3(x, y, z), 0.25});
    compare_with_brute_force(pts);
  }
  SUBCASE("benzene: coplanar ring, 3-decimal coordinates") {
    std::vector<WeightedPoint> pts;
    for (int k = 0; k < 6; ++k) {
      const double a = k * M_PI / 3;
      pts.push_back({Vec3(round3(1.39 * std::cos(a)), round3(1.39 * std::sin(a)), 0.0), 1.7 * 1.7});
      pts.push_back({Vec3(round3(2.47 * std::cos(a)), round3(2.47 * std::sin(a)), 0.0), 1.2 * 1.2});
    }
    compare_with_brute_force(pts);
  }
  SUBCASE("3 x 3 planar grid, equal weights (coplanar and cocircular)") {
    std::vector<WeightedPoint> pts;
    for (int x = 0; x < 3; ++x)
      for (int y = 0; y < 3; ++y) pts.push_back({Vec3(x, y, 0), 0.0});
    compare_with_brute_force(pts);
  }
  SUBCASE("integer points on a sphere (exactly cospherical)") {
    std::vector<WeightedPoint> pts;
    for (const Vec3& p : integer_sphere(9)) pts.push_back({p, 0.0});  // (±3,0,0), (±2,±2,±1), ...
    pts.resize(std::min<std::size_t>(pts.size(), 16));
    compare_with_brute_force(pts);
  }
  SUBCASE("collinear points") {
    std::vector<WeightedPoint> pts;
    for (int k = 0; k < 6; ++k) pts.push_back({Vec3(k, 2 * k, -k), 0.5});
    compare_with_brute_force(pts);
  }
  SUBCASE("duplicate centres with equal and different weights") {
    std::vector<WeightedPoint> pts = {{Vec3(0, 0, 0), 1.0}, {Vec3(0, 0, 0), 1.0}, {Vec3(1, 0, 0), 1.0},
                                      {Vec3(1, 0, 0), 2.0}, {Vec3(0, 1, 0), 3.0}, {Vec3(0, 1, 0), 1.0},
                                      {Vec3(0, 0, 1), 1.0}, {Vec3(0, 0, 1), 1.0}, {Vec3(0, 0, 1), 1.0}};
    compare_with_brute_force(pts);
    const RegularTriangulation rt(pts);
    // Larger weight wins; equal weights: the larger index wins.
    CHECK(rt.redundant_points() == std::vector<Index>{0, 2, 5, 6, 7});
  }
}

TEST_CASE("regular triangulation: 5 x 5 x 5 lattice with equal weights") {
  std::vector<WeightedPoint> pts;
  for (int x = 0; x < 5; ++x)
    for (int y = 0; y < 5; ++y)
      for (int z = 0; z < 5; ++z) pts.push_back({Vec3(1.5 * x, 1.5 * y, 1.5 * z), 1.0});
  sg::reset_predicate_stats();
  const RegularTriangulation rt(pts);
  verify(rt, true);
  CHECK(rt.redundant_points().empty());
  CHECK(sg::predicate_stats().power_test.sos > 0);  // the input is degenerate
  // Every unit cube of the lattice is split into tetrahedra: at least 5 per cube.
  Index interior = 0;
  for (const Quad& q : all_tets(rt)) {
    bool inner = true;
    for (const Index v : q) inner = inner && !rt.is_bounding(v);
    interior += inner;
  }
  CHECK(interior >= 5 * 64);
}

TEST_CASE("regular triangulation: lattice with interstitial points") {
  // 3 x 3 x 3 lattice (spacing 1, weight 0) plus a point at the centre of each
  // of the 8 cells. The cell's corners have orthosphere (centre, 3/4): a centre
  // point with weight -1 has power 1 > 3/4 there and is redundant, one with
  // weight -1/2 has power 1/2 < 3/4 and is a vertex.
  std::vector<WeightedPoint> pts;
  for (int x = 0; x < 3; ++x)
    for (int y = 0; y < 3; ++y)
      for (int z = 0; z < 3; ++z) pts.push_back({Vec3(x, y, z), 0.0});
  std::vector<Index> expected;
  for (int c = 0; c < 8; ++c) {
    const bool hidden = c % 2 == 0;
    if (hidden) expected.push_back(static_cast<Index>(pts.size()));
    pts.push_back({Vec3(0.5 + (c & 1), 0.5 + ((c >> 1) & 1), 0.5 + ((c >> 2) & 1)), hidden ? -1.0 : -0.5});
  }
  const RegularTriangulation rt(pts);
  verify(rt, true);
  CHECK(rt.redundant_points() == expected);
}

TEST_CASE("regular triangulation: hidden vertices (duplicates inserted in random order)") {
  // 30 centres, each repeated 6 times with random weights: exactly the
  // largest weight of each centre survives, whatever the insertion order;
  // some vertices are hidden by later insertions.
  const unsigned seed = 2718u;
  INFO("seed " << seed);
  std::mt19937_64 rng(seed);
  auto base = random_points(rng, 30, 5.0, 1.0, 1.5);
  std::uniform_real_distribution<double> w(0.5, 2.5);
  std::vector<WeightedPoint> pts;
  std::vector<Index> expected;
  for (const auto& b : base) {
    Index best = 0;
    double best_w = -1;
    for (int k = 0; k < 6; ++k) {
      const double wk = k == 5 ? best_w : w(rng);  // the last one ties: larger index wins
      const Index id = static_cast<Index>(pts.size());
      pts.push_back({b.z, wk});
      if (wk >= best_w) {
        best_w = wk;
        best = id;
      }
    }
    for (Index id = static_cast<Index>(pts.size()) - 6; id < pts.size(); ++id)
      if (id != best) expected.push_back(id);
  }
  for (const std::uint64_t s : {1ull, 2ull, 3ull}) {
    const RegularTriangulation rt(pts, s);
    verify(rt, false);
    CHECK(rt.redundant_points() == expected);
    CHECK(rt.build_stats().hidden_vertices > 0);
  }
}

TEST_CASE("regular triangulation: the result does not depend on the seed") {
  const unsigned seed = 31u;
  INFO("seed " << seed);
  std::mt19937_64 rng(seed);
  std::vector<WeightedPoint> pts;
  // Degenerate: lattice points with a few distinct weights, 3-decimal rounding.
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y)
      for (int z = 0; z < 4; ++z) pts.push_back({Vec3(1.2 * x, 1.2 * y, 1.2 * z), (x + y) % 2 ? 1.0 : 0.81});
  for (auto& p : random_points(rng, 100, 3.0, 0.8, 1.8))
    pts.push_back({Vec3(round3(p.z.x()), round3(p.z.y()), round3(p.z.z())), p.w});
  const RegularTriangulation a(pts, 1), b(pts, 987654321);
  verify(a, true);
  verify(b, false);
  CHECK(tet_set(a) == tet_set(b));
  CHECK(a.redundant_points() == b.redundant_points());
  const RegularTriangulation a2(pts, 1);
  CHECK(all_tets(a) == all_tets(a2));
}

TEST_CASE("regular triangulation: points on a sphere and coplanar sets") {
  SUBCASE("all integer points on the sphere of radius 15 (exactly cospherical)") {
    std::vector<WeightedPoint> pts;
    for (const Vec3& p : integer_sphere(225)) pts.push_back({p, 0.0});
    REQUIRE(pts.size() > 100);
    const RegularTriangulation rt(pts);
    verify(rt, true);
    CHECK(rt.redundant_points().empty());
  }
  SUBCASE("planar 12 x 12 grid with equal weights") {
    std::vector<WeightedPoint> pts;
    for (int x = 0; x < 12; ++x)
      for (int y = 0; y < 12; ++y) pts.push_back({Vec3(1.4 * x, 1.4 * y, 0.0), 2.89});
    const RegularTriangulation rt(pts);
    verify(rt, true);
    CHECK(rt.redundant_points().empty());
  }
  SUBCASE("two stacked benzene-like rings (parallel planes)") {
    std::vector<WeightedPoint> pts;
    for (int layer = 0; layer < 2; ++layer)
      for (int k = 0; k < 6; ++k) {
        const double a = k * M_PI / 3;
        pts.push_back({Vec3(round3(1.39 * std::cos(a)), round3(1.39 * std::sin(a)), 3.4 * layer), 2.89});
      }
    compare_with_brute_force(pts);
  }
}

TEST_CASE("regular triangulation: negative weights, redundant inputs") {
  const unsigned seed = 77u;
  INFO("seed " << seed);
  std::mt19937_64 rng(seed);
  auto pts = random_points(rng, 300, 6.0, 1.2, 1.9);
  // Points with negative weights near existing centres: most are redundant.
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  for (int i = 0; i < 100; ++i) {
    const double dx = jitter(rng), dy = jitter(rng), dz = jitter(rng);
    const Vec3 z = pts[i].z + Vec3(dx, dy, dz);
    pts.push_back({z, -1.0});
  }
  const RegularTriangulation rt(pts);
  verify(rt, true);
  const auto red = rt.redundant_points();
  MESSAGE(red.size() << " redundant of " << pts.size());
  CHECK(red.size() >= 50);
}

TEST_CASE("regular triangulation: larger random and PDB-like inputs") {
  const unsigned seed = 123u;
  INFO("seed " << seed);
  std::mt19937_64 rng(seed);
  SUBCASE("5000 random weighted points") {
    const RegularTriangulation rt(random_points(rng, 5000, 20.0, 1.0, 2.0));
    verify(rt, false);
    CHECK(rt.build_stats().walk_fallbacks == 0);
  }
  SUBCASE("3000 PDB-like atoms: 3-decimal coordinates, few distinct radii") {
    const double radii[] = {1.2, 1.5, 1.6, 1.7, 1.8};
    std::uniform_real_distribution<double> c(-15.0, 15.0);
    std::uniform_int_distribution<int> r(0, 4);
    std::vector<WeightedPoint> pts;
    while (pts.size() < 3000) {
      const double x = c(rng), y = c(rng), zz = c(rng);
      const Vec3 z(round3(x), round3(y), round3(zz));
      if (z.norm() > 15.0) continue;  // a globular molecule
      const double rad = radii[r(rng)];
      pts.push_back({z, rad * rad});
    }
    const RegularTriangulation rt(pts);
    verify(rt, false);
    // About 6.5 tetrahedra per point for large inputs (papers/skin/skin_math.md §9).
    CHECK(rt.num_tets() > 5 * 3000);
    CHECK(rt.num_tets() < 8 * 3000);
  }
}

TEST_CASE("regular triangulation: locate") {
  const unsigned seed = 9u;
  INFO("seed " << seed);
  std::mt19937_64 rng(seed);
  const RegularTriangulation rt(random_points(rng, 500, 10.0, 1.0, 2.0));
  std::uniform_real_distribution<double> c(-12.0, 12.0);
  for (int k = 0; k < 200; ++k) {
    const double x = c(rng), y = c(rng), z = c(rng);
    const Vec3 p(x, y, z);
    const Index t = rt.locate(p, k % 2 ? Index(k) : kInvalidIndex);
    REQUIRE(t != kInvalidIndex);
    const Quad& q = rt.tet(t);
    for (const auto& f : RegularTriangulation::kFaceVertices)
      CHECK(sg::orient3d(rt.point(q[f[0]]).z, rt.point(q[f[1]]).z, rt.point(q[f[2]]).z, p) != Sign::Negative);
  }
  // Vertices themselves (on the closed hull of several tetrahedra).
  for (Index v = 0; v < 50; ++v) {
    const Index t = rt.locate(rt.point(v).z);
    REQUIRE(t != kInvalidIndex);
    const Quad& q = rt.tet(t);
    for (const auto& f : RegularTriangulation::kFaceVertices)
      CHECK(sg::orient3d(rt.point(q[f[0]]).z, rt.point(q[f[1]]).z, rt.point(q[f[2]]).z, rt.point(v).z) !=
            Sign::Negative);
  }
  // Outside the bounding tetrahedron.
  CHECK(rt.locate(rt.bounding_centre() + Vec3(1, 1, 1) * 10 * rt.bounding_radius()) == kInvalidIndex);
}

TEST_CASE("regular triangulation: face table matches the orientation convention") {
  const std::vector<WeightedPoint> pts = {{Vec3(0, 0, 0), 0.0}};
  const RegularTriangulation rt(pts);
  for (const Quad& q : all_tets(rt))
    for (int i = 0; i < 4; ++i) {
      const auto& f = RegularTriangulation::kFaceVertices[i];
      CHECK(sg::orient3d(rt.point(q[f[0]]).z, rt.point(q[f[1]]).z, rt.point(q[f[2]]).z, rt.point(q[i]).z) ==
            Sign::Positive);
    }
}

}  // TEST_SUITE
