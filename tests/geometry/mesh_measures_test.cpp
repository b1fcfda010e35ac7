// tests/geometry/mesh_measures_test.cpp: component_measures() against shapes
// whose area and volume are known — a unit cube (exact), a fine polyhedral
// sphere (converging to 4πR² and 4πR³/3), a sphere with a cavity (the cavity's
// volume counts negative), and the same far from the origin.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "geometry/mesh/mesh_measures.h"
#include "tests/geometry/test_meshes.h"

using skinmesh::Index;
using skinmesh::Vec3;
using skinmesh::geometry::component_measures;
using skinmesh::geometry::IndexedMesh;

namespace {

/// The unit cube [0,1]³, triangles counter-clockwise seen from outside.
IndexedMesh cube() {
  IndexedMesh m;
  for (int i = 0; i < 8; ++i) m.positions.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

/// test::sphere(levels) scaled to radius r about c; `inward` reverses every triangle.
IndexedMesh sphere(double r, const Vec3& c, int levels, bool inward) {
  IndexedMesh m = skinmesh::test::sphere(levels);
  for (Vec3& p : m.positions) p = c + r * p;
  if (inward)
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

using skinmesh::test::join;

}  // namespace

TEST_SUITE("geometry") {

TEST_CASE("measures: the unit cube has area 6 and volume 1") {
  const auto c = component_measures(cube());
  REQUIRE(c.size() == 1);
  CHECK(c[0].vertices == 8);
  CHECK(c[0].triangles == 12);
  CHECK(c[0].area == doctest::Approx(6).epsilon(1e-15));
  CHECK(c[0].volume == doctest::Approx(1).epsilon(1e-15));
}

TEST_CASE("measures: a fine sphere converges to 4πR² and 4πR³/3 from below") {
  const double R = 3.7;
  double previous_error = 1;
  for (int levels = 3; levels <= 5; ++levels) {
    const auto c = component_measures(sphere(R, Vec3(1, 2, 3), levels, false));
    REQUIRE(c.size() == 1);
    const double area = 4 * M_PI * R * R, volume = 4 * M_PI * R * R * R / 3;
    CHECK(c[0].area < area);
    CHECK(c[0].volume < volume);
    const double error = (volume - c[0].volume) / volume;
    CHECK(error < previous_error / 3);  // second order: about 4× smaller per level
    previous_error = error;
  }
  CHECK(previous_error < 2e-3);
}

TEST_CASE("measures: a cavity's surface counts negative; components in vertex order; far away the same") {
  const IndexedMesh body = sphere(5, Vec3::Zero(), 4, false), cavity = sphere(2, Vec3(0.5, 0, 0), 4, true);
  const auto c = component_measures(join(body, cavity));
  REQUIRE(c.size() == 2);
  CHECK(c[0].volume > 0);
  CHECK(c[1].volume < 0);
  CHECK(c[1].volume ==
        doctest::Approx(-component_measures(sphere(2, Vec3::Zero(), 4, false))[0].volume).epsilon(1e-12));
  CHECK(c[0].vertices == body.positions.size());
  // 10^6 Å from the origin: relative to each component's first vertex, no digits lost.
  IndexedMesh far = join(body, cavity);
  for (Vec3& p : far.positions) p += Vec3(1e6, -1e6, 1e6);
  const auto f = component_measures(far);
  CHECK(f[0].volume == doctest::Approx(c[0].volume).epsilon(1e-9));
  CHECK(f[1].volume == doctest::Approx(c[1].volume).epsilon(1e-9));
  CHECK(f[0].area == doctest::Approx(c[0].area).epsilon(1e-9));
}

TEST_CASE("measures: vertices in no triangle are not counted; an empty mesh has no component") {
  IndexedMesh m = cube();
  m.positions.emplace_back(9, 9, 9);
  const auto c = component_measures(m);
  REQUIRE(c.size() == 1);
  CHECK(c[0].vertices == 8);
  CHECK(component_measures(IndexedMesh{}).empty());
  // Labels: 1, 2, ... by smallest vertex; 0 for the isolated vertex. The
  // second cube's triangles come first, its vertices last.
  IndexedMesh two = cube();
  two.positions.emplace_back(9, 9, 9);  // vertex 8: isolated
  const IndexedMesh shifted = cube();
  for (const Vec3& p : shifted.positions) two.positions.push_back(p + Vec3(5, 0, 0));
  std::vector<std::array<Index, 3>> tris;
  for (const auto& t : shifted.triangles) tris.push_back({t[0] + 9, t[1] + 9, t[2] + 9});
  tris.insert(tris.end(), two.triangles.begin(), two.triangles.end());
  two.triangles = tris;
  const std::vector<int> label = skinmesh::geometry::vertex_components(two);
  CHECK(label[0] == 1);
  CHECK(label[7] == 1);
  CHECK(label[8] == 0);
  CHECK(label[9] == 2);
  CHECK(label[16] == 2);
  const auto measures = component_measures(two);
  REQUIRE(measures.size() == 2);
  CHECK(measures[1].volume == doctest::Approx(1));
}

}  // TEST_SUITE
