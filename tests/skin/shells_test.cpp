// tests/skin/shells_test.cpp: skin::select_shells — which components a
// selection keeps (by the sign and size of the volume each encloses), that the
// kept mesh and its per-vertex data stay in order and consistent, and the
// topology the kept shells must have.
#include <doctest/doctest.h>

#include <algorithm>
#include <stdexcept>

#include "geometry/mesh/mesh_measures.h"
#include "skin/shells.h"
#include "tests/geometry/test_meshes.h"

namespace {

using skinmesh::Index;
using skinmesh::Vec3;
using skinmesh::geometry::IndexedMesh;
using namespace skinmesh::skin;

/// `m` scaled by s about the origin, moved by d, and turned inside out if
/// `cavity` (the triangles reversed: a cavity's shell faces into the cavity).
IndexedMesh placed(IndexedMesh m, double s, const Vec3& d, bool cavity) {
  for (Vec3& p : m.positions) p = s * p + d;
  if (cavity)
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

/// A body of radius 10 with two cavities inside it (radii 3 and 0.5), and a
/// second body (a torus) beside it: four shells, in that vertex order.
IndexedMesh shells_mesh() {
  using skinmesh::test::join;
  using skinmesh::test::sphere;
  IndexedMesh m = placed(sphere(2), 10, Vec3::Zero(), false);
  m = join(m, placed(sphere(1), 3, Vec3(2, 0, 0), true));
  m = join(m, placed(sphere(1), 0.5, Vec3(-5, 0, 0), true));
  return join(m, placed(skinmesh::test::torus(24, 12), 1, Vec3(30, 0, 0), false));
}

/// Per-vertex data whose every entry names its vertex: atom = old index.
SkinVertexData data_of(const IndexedMesh& m) {
  SkinVertexData d;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    d.atom.push_back(static_cast<std::int32_t>(v));
    d.rho.push_back(static_cast<double>(v) / 2);
  }
  return d;  // patch left empty: it stays empty
}

}  // namespace

TEST_SUITE("skin") {

TEST_CASE("shells: names and what a selection keeps") {
  for (CavityChoice c : {CavityChoice::Keep, CavityChoice::Remove, CavityChoice::Only})
    CHECK(cavity_choice_named(cavity_choice_name(c)) == c);
  CHECK_THROWS_AS(cavity_choice_named("none"), std::invalid_argument);
  CHECK_FALSE(ShellSelection{}.selects());
  const ShellSelection remove{CavityChoice::Remove, 0}, only{CavityChoice::Only, 0}, big{CavityChoice::Keep, 1.0};
  CHECK(remove.keeps(5));
  CHECK_FALSE(remove.keeps(-5));
  CHECK_FALSE(only.keeps(5));
  CHECK(only.keeps(-1e-9));
  CHECK(big.keeps(1e-9));  // bodies are kept whatever their size
  CHECK(big.keeps(-1.0));
  CHECK_FALSE(big.keeps(-0.999));
  CHECK(big.partial_cavities());
  CHECK_FALSE(ShellSelection{CavityChoice::Remove, 1.0}.partial_cavities());
}

TEST_CASE("shells: select_shells keeps the chosen components, in order, with their data") {
  const IndexedMesh all = shells_mesh();
  const auto measures = skinmesh::geometry::component_measures(all);
  REQUIRE(measures.size() == 4);
  REQUIRE(measures[1].volume < 0);
  REQUIRE(measures[2].volume < 0);
  REQUIRE(-measures[2].volume < 1.0);  // the small cavity: under 1 Å³
  struct Case {
    ShellSelection selection;
    std::vector<int> kept;  // component numbers (0-based) kept
  };
  for (const Case& c : {Case{{CavityChoice::Keep, 0}, {0, 1, 2, 3}}, Case{{CavityChoice::Remove, 0}, {0, 3}},
                        Case{{CavityChoice::Only, 0}, {1, 2}}, Case{{CavityChoice::Keep, 1.0}, {0, 1, 3}},
                        Case{{CavityChoice::Only, 1.0}, {1}}}) {
    CAPTURE(cavity_choice_name(c.selection.cavities));
    CAPTURE(c.selection.min_cavity_volume);
    IndexedMesh m = all;
    m.normals = m.positions;  // any per-vertex array follows its vertex
    SkinVertexData data = data_of(m);
    std::vector<Index> cells(m.positions.size());
    for (std::size_t v = 0; v < cells.size(); ++v) cells[v] = static_cast<Index>(3 * v);
    const ShellCounts counts = select_shells(m, &data, &cells, c.selection);

    std::size_t bodies = 0, cavities = 0, vertices = 0, triangles = 0;
    double removed_volume = 0;
    for (int k : c.kept) (measures[k].volume < 0 ? cavities : bodies)++;
    for (int k = 0; k < 4; ++k) {
      const bool kept = std::find(c.kept.begin(), c.kept.end(), k) != c.kept.end();
      if (kept) vertices += measures[k].vertices, triangles += measures[k].triangles;
      if (!kept && measures[k].volume < 0) removed_volume -= measures[k].volume;
    }
    CHECK(counts.bodies == bodies);
    CHECK(counts.cavities == cavities);
    CHECK(counts.removed_bodies == 2 - bodies);
    CHECK(counts.removed_cavities == 2 - cavities);
    CHECK(counts.removed_cavity_volume == doctest::Approx(removed_volume));
    CHECK(counts.kept_euler.size() == c.kept.size());
    CHECK(counts.kept_euler.size() + counts.removed_euler.size() == 4);
    REQUIRE(m.positions.size() == vertices);
    CHECK(m.triangles.size() == triangles);
    REQUIRE(data.atom.size() == vertices);
    REQUIRE(data.rho.size() == vertices);
    REQUIRE(cells.size() == vertices);
    CHECK(data.patch.empty());
    // Every kept vertex is its old self (in order), with its data.
    for (std::size_t v = 0; v < vertices; ++v) {
      const auto old = static_cast<std::size_t>(data.atom[v]);
      CHECK(m.positions[v] == all.positions[old]);
      CHECK(m.normals[v] == all.positions[old]);
      CHECK(data.rho[v] == static_cast<double>(old) / 2);
      CHECK(cells[v] == static_cast<Index>(3 * old));
      if (v > 0) CHECK(data.atom[v] > data.atom[v - 1]);
    }
    // The kept components are those of the selection, with their measures.
    const auto after = skinmesh::geometry::component_measures(m);
    REQUIRE(after.size() == c.kept.size());
    for (std::size_t i = 0; i < after.size(); ++i)
      CHECK(after[i].volume == doctest::Approx(measures[c.kept[i]].volume));
    // The topology of the kept shells: the body's sphere, the cavities' spheres, the torus.
    SkinTopology skin;
    skin.betti0 = 2;
    skin.betti2 = 2;
    skin.euler_k0 = (2 + 2 + 2 + 0) / 2;
    const SkinTopology t = kept_topology(skin, counts);
    CHECK(t.components() == static_cast<int>(c.kept.size()));
    std::int64_t euler = 0;
    for (int k : c.kept) euler += k == 3 ? 0 : 2;
    CHECK(t.euler_skin() == euler);
  }
}

}  // TEST_SUITE
