// tests/geometry/mesh_checks_broad_phase_test.cpp: the two shortcuts of the
// self-intersection test of geometry/check/mesh_checks against brute force — the
// column broad phase (box_overlap_pairs() against all pairs of boxes) and the
// simple-fan test (simple_fan_vertices(): no two triangles around a simple fan
// meet beyond what they share, by the exact all-pairs test), then check_mesh()
// on perturbed and folded meshes against the exact test on all pairs.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "geometry/check/mesh_checks.h"
#include "geometry/check/mesh_checks_internal.h"
#include "geometry/kernel/triangle_intersection.h"
#include "tests/geometry/test_meshes.h"

using skinmesh::Index;
using skinmesh::Vec3;
using namespace skinmesh::geometry;
using namespace skinmesh::geometry::mesh_checks_detail;
using skinmesh::test::brute_force_intersections;

namespace {

using Box = std::array<double, 6>;

// All pairs (i < j) of closed boxes that overlap, by brute force.
std::vector<std::array<Index, 2>> brute_force_pairs(const std::vector<Box>& b) {
  std::vector<std::array<Index, 2>> out;
  for (std::size_t i = 0; i < b.size(); ++i)
    for (std::size_t j = i + 1; j < b.size(); ++j) {
      bool overlap = true;
      for (int k = 0; k < 3; ++k) overlap = overlap && b[i][k] <= b[j][3 + k] && b[j][k] <= b[i][3 + k];
      if (overlap) out.push_back({Index(i), Index(j)});
    }
  return out;
}

// The box of a triangle.
Box box_of(const Vec3& a, const Vec3& b, const Vec3& c) {
  Box r;
  for (int k = 0; k < 3; ++k) {
    r[k] = std::min({a[k], b[k], c[k]});
    r[3 + k] = std::max({a[k], b[k], c[k]});
  }
  return r;
}

// The classes check_mesh() computes, for the meshes of these tests (indices in
// range, finite coordinates): repeated index or zero area, else good.
TriangleClasses classes_of(const IndexedMesh& m) {
  TriangleClasses c;
  c.vertex_finite.assign(m.positions.size(), true);
  c.referenced.assign(m.positions.size(), true);
  for (const auto& t : m.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      c.kind.push_back(TriangleKind::kRepeated);
    else if (is_degenerate_triangle(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]))
      c.kind.push_back(TriangleKind::kZeroArea);
    else
      c.kind.push_back(TriangleKind::kGood);
  }
  return c;
}

// Every vertex the fan test accepts: no two good triangles around it meet
// beyond what they share (the exact test on every pair of its star).
void check_simple_fans_are_embedded(const IndexedMesh& m, std::size_t& accepted) {
  const TriangleClasses classes = classes_of(m);
  const std::vector<std::uint8_t> ok = simple_fan_vertices(m, classes, build_incidence(m, classes));
  REQUIRE(ok.size() == m.positions.size());
  std::vector<std::vector<Index>> star(m.positions.size());
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    if (classes.kind[t] == TriangleKind::kGood)
      for (Index v : m.triangles[t]) star[v].push_back(Index(t));
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    if (!ok[v]) continue;
    ++accepted;
    const auto& s = star[v];
    for (std::size_t i = 0; i < s.size(); ++i)
      for (std::size_t j = i + 1; j < s.size(); ++j) {
        INFO("vertex " << v << ", triangles " << s[i] << " and " << s[j]);
        CHECK_FALSE(mesh_triangles_intersect(m.triangles[s[i]], m.triangles[s[j]], m.positions));
      }
  }
}

// `base` with every vertex moved by a uniform offset in [-amp, amp]^3; with
// `grid` > 0 the coordinates are then rounded to multiples of 1 / grid, which
// makes coplanar and collinear configurations frequent.
IndexedMesh perturbed(IndexedMesh base, std::mt19937& rng, double amp, double grid) {
  std::uniform_real_distribution<double> d(-amp, amp);
  for (Vec3& p : base.positions) {
    p += Vec3(d(rng), d(rng), d(rng));
    if (grid > 0)
      for (int k = 0; k < 3; ++k) p[k] = std::round(p[k] * grid) / grid;
  }
  return base;
}

}  // namespace

TEST_SUITE("geometry") {

TEST_CASE("mesh_checks broad phase: the column sweep reports exactly the overlapping box pairs") {
  const unsigned seed = 20261122;
  INFO("seed = " << seed);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);

  SUBCASE("triangle soups of mixed sizes, some sharing vertices") {
    for (int round = 0; round < 6; ++round) {
      std::vector<Vec3> pool;
      for (int i = 0; i < 200; ++i) pool.emplace_back(unit(rng), unit(rng), unit(rng));
      std::vector<Box> boxes;
      const double size = round < 3 ? 0.03 : 0.2;
      std::uniform_real_distribution<double> off(-size, size);
      std::uniform_int_distribution<int> pick(0, 199);
      for (int i = 0; i < 700; ++i) {
        const Vec3 a = pool[std::size_t(pick(rng))];
        const Vec3 b = i % 2 ? pool[std::size_t(pick(rng))] : a + Vec3(off(rng), off(rng), off(rng));
        const Vec3 c = a + Vec3(off(rng), off(rng), off(rng));
        boxes.push_back(box_of(a, b, c));
      }
      // A few huge ones and a few flat or point-like boxes (zero extent on an axis).
      boxes.push_back(box_of(Vec3(-1, -1, 0.5), Vec3(2, 0.5, 0.5), Vec3(0.5, 2, 0.7)));
      boxes.push_back(box_of(Vec3(0.5, -3, -3), Vec3(0.5, 3, 3), Vec3(0.5, 3, -3)));
      boxes.push_back(Box{0.25, 0.25, 0.25, 0.25, 0.25, 0.25});
      boxes.push_back(Box{0.25, 0.25, 0.25, 0.25, 0.25, 0.25});
      const auto expect = brute_force_pairs(boxes);
      INFO("round " << round << ", pairs " << expect.size());
      CHECK(box_overlap_pairs(boxes) == expect);
      // Small blocks of columns on several threads: the same pairs.
      for (const int threads : {1, 2, 3}) {
        INFO("threads " << threads);
        CHECK(box_overlap_pairs(boxes, threads, 64) == expect);
      }
      // Bands of a few boxes (each band then as wide as the widest box, the
      // huge ones above: one band), and without those boxes many bands.
      for (const std::size_t band : {1, 7, 50}) {
        INFO("boxes per band " << band);
        CHECK(box_overlap_pairs(boxes, 2, 64, band) == expect);
        const std::vector<Box> small(boxes.begin(), boxes.begin() + 700);
        CHECK(box_overlap_pairs(small, 2, 64, band) == brute_force_pairs(small));
      }
    }
  }

  SUBCASE("boxes that only touch, on a lattice (closed boxes: touching counts)") {
    std::vector<Box> boxes;
    for (int x = 0; x < 8; ++x)
      for (int y = 0; y < 8; ++y)
        for (int z = 0; z < 3; ++z)
          boxes.push_back(Box{x * 0.5, y * 0.5, z * 0.5, x * 0.5 + 0.5, y * 0.5 + 0.5, z * 0.5 + 0.5});
    const auto expect = brute_force_pairs(boxes);
    CHECK(expect.size() > 1000);
    CHECK(box_overlap_pairs(boxes) == expect);
    for (const std::size_t band : {1, 5, 40}) CHECK(box_overlap_pairs(boxes, 2, 16, band) == expect);
  }

  SUBCASE("all boxes in one column, equal lower z, and -0.0 against 0.0") {
    std::vector<Box> boxes;
    for (int i = 0; i < 100; ++i) {
      const double z = (i % 5 == 0) ? -0.0 : (i % 5 == 1 ? 0.0 : unit(rng));
      boxes.push_back(Box{0, 0, z, 1e-3, 1e-3, z + unit(rng) * 0.1});
    }
    CHECK(box_overlap_pairs(boxes) == brute_force_pairs(boxes));
  }

  SUBCASE("coordinates near the double range (no finite grid)") {
    std::vector<Box> boxes;
    for (int i = 0; i < 80; ++i) {
      const double x = (unit(rng) - 0.5) * 1.7e308, y = (unit(rng) - 0.5) * 1e300;
      boxes.push_back(Box{x, y, unit(rng), x + 1e307, y + 1e299, 1.0 + unit(rng)});
    }
    CHECK(box_overlap_pairs(boxes) == brute_force_pairs(boxes));
  }

  SUBCASE("bounds a double ulp apart (one single-precision value): touching and not") {
    // The broad phase stores boxes rounded out to floats: these pairs look
    // alike there, and only the exact confirmation tells them apart.
    std::vector<Box> boxes;
    for (int i = 0; i < 60; ++i) {
      const double x = 1.0 + std::ldexp(double(i % 7), -40);  // within one float ulp of 1
      const double gap = (i % 3 == 0) ? 0.0 : std::ldexp(1.0, -52) * double(i % 3);
      boxes.push_back(Box{x - 0.5, 0, 0, x, 1, 1});
      boxes.push_back(Box{x + gap, 0, 0, x + gap + 0.5, 1, 1});
    }
    CHECK(box_overlap_pairs(boxes) == brute_force_pairs(boxes));
  }

  SUBCASE("fewer than two boxes") {
    CHECK(box_overlap_pairs({}).empty());
    CHECK(box_overlap_pairs({Box{0, 0, 0, 1, 1, 1}}).empty());
  }
}

TEST_CASE("mesh_checks simple fans: accepted fans are embedded, exactly") {
  const unsigned seed = 424242;
  INFO("seed = " << seed);
  std::mt19937 rng(seed);
  std::size_t accepted = 0;

  SUBCASE("a clean sphere and torus: every vertex is a simple fan") {
    for (const IndexedMesh& m : {skinmesh::test::sphere(2), skinmesh::test::torus(12, 8)}) {
      const std::vector<std::uint8_t> ok = simple_fan_vertices(m, classes_of(m), build_incidence(m, classes_of(m)));
      CHECK(std::count(ok.begin(), ok.end(), 1) == std::ptrdiff_t(m.positions.size()));
      check_simple_fans_are_embedded(m, accepted);
    }
  }

  SUBCASE("perturbed, folded and rounded spheres") {
    std::size_t rejected = 0;
    for (int round = 0; round < 12; ++round) {
      const double amp = round < 4 ? 0.02 : (round < 8 ? 0.08 : 0.2);
      const double grid = round % 2 ? 16.0 : 0.0;
      const IndexedMesh m = perturbed(skinmesh::test::sphere(2), rng, amp, grid);
      const std::vector<std::uint8_t> ok = simple_fan_vertices(m, classes_of(m), build_incidence(m, classes_of(m)));
      rejected += std::size_t(std::count(ok.begin(), ok.end(), 0));
      check_simple_fans_are_embedded(m, accepted);
    }
    CHECK(rejected > 0);
  }

  SUBCASE("flat fans: coplanar neighbours, a folded-over triangle, a fan winding twice") {
    // A hexagonal fan in the plane z = 0 around the origin.
    IndexedMesh m;
    m.positions.push_back(Vec3(0, 0, 0));
    for (int i = 0; i < 6; ++i)
      m.positions.push_back(Vec3(std::cos(i * 1.0471975511965976), std::sin(i * 1.0471975511965976), 0));
    for (Index i = 0; i < 6; ++i) m.triangles.push_back({0, Index(1 + i), Index(1 + (i + 1) % 6)});
    CHECK(simple_fan_vertices(m, classes_of(m), build_incidence(m, classes_of(m)))[0] == 1);
    check_simple_fans_are_embedded(m, accepted);
    // Fold: one rim vertex moved across its neighbour's ray, so two triangles overlap.
    IndexedMesh folded = m;
    folded.positions[2] = Vec3(0.9, -0.3, 0);
    CHECK(simple_fan_vertices(folded, classes_of(folded), build_incidence(folded, classes_of(folded)))[0] == 0);
    CHECK(!brute_force_intersections(folded).empty());
    // Twelve triangles winding twice around the centre.
    IndexedMesh twice;
    twice.positions.push_back(Vec3(0, 0, 0));
    for (int i = 0; i < 12; ++i)
      twice.positions.push_back(Vec3(std::cos(i * 1.0471975511965976), std::sin(i * 1.0471975511965976), 0.01 * i));
    for (Index i = 0; i < 12; ++i) twice.triangles.push_back({0, Index(1 + i), Index(1 + (i + 1) % 12)});
    CHECK(simple_fan_vertices(twice, classes_of(twice), build_incidence(twice, classes_of(twice)))[0] == 0);
  }
  CHECK(accepted > 0);
}

TEST_CASE("check_mesh: self-intersections of perturbed meshes equal the all-pairs exact test") {
  const unsigned seed = 77001;
  INFO("seed = " << seed);
  std::mt19937 rng(seed);
  for (int round = 0; round < 10; ++round) {
    const double amp = 0.02 + 0.03 * round;
    IndexedMesh m = perturbed(round % 2 ? skinmesh::test::sphere(2) : skinmesh::test::torus(14, 9), rng, amp,
                              round % 3 == 0 ? 32.0 : 0.0);
    // A second, shifted copy overlapping the first, and a duplicated triangle.
    if (round % 4 == 1) {
      IndexedMesh copy = m;
      for (Vec3& p : copy.positions) p += Vec3(0.05, 0.02, 0.0);
      const Index off = Index(m.positions.size());
      m.positions.insert(m.positions.end(), copy.positions.begin(), copy.positions.end());
      for (auto t : copy.triangles) m.triangles.push_back({t[0] + off, t[1] + off, t[2] + off});
      m.triangles.push_back(m.triangles[3]);
    }
    MeshCheckOptions opt;
    opt.max_examples = 1000000;
    const MeshCheckReport r = check_mesh(m, opt);
    const auto expect = brute_force_intersections(m);
    INFO("round " << round << ", intersecting pairs " << expect.size());
    CHECK(r.num_self_intersections == expect.size());
    CHECK(r.self_intersection_examples == expect);
  }
}

}  // TEST_SUITE
