// tests/mesher/atom_areas_test.cpp: the mesh's area per atom (skin/atom_areas.h)
// sums to the mesh's area and approaches the exact skin's per-atom areas
// (skin::atom_areas) as the mesh is refined (smaller C): the two attributions,
// one by the vertices' atoms and one by the power bisectors cutting the
// patches, agree atom by atom.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "geometry/mesh/mesh_measures.h"
#include "mesher/pipeline.h"
#include "skin/atom_areas.h"
#include "skin/molecule_io.h"
#include "skin/skin_measures.h"
#include "skin/skin_surface.h"

using namespace skinmesh;

namespace {

/// Σ |mesh_i - skin_i| / Σ skin_i over the atoms.
double relative_l1(const std::vector<double>& mesh, const std::vector<double>& exact) {
  double diff = 0, total = 0;
  for (std::size_t i = 0; i < exact.size(); ++i) diff += std::abs(mesh[i] - exact[i]), total += exact[i];
  return diff / total;
}

}  // namespace

TEST_SUITE("mesher") {

TEST_CASE("atom areas: the mesh's sum to its area and converge to the exact skin's atom by atom") {
  const skin::Molecule mol = skin::read_molecule(std::string(SKINMESH_DATA) + "/gramicidinA_1grm_model1.pdb");
  const double probe = 1.4;
  const std::vector<double> exact = skin::atom_areas(skin::weighted_points(mol, probe), 2);
  double exact_sum = 0;
  for (double a : exact) exact_sum += a;
  double previous = 1.0;
  for (const double C : {0.12, 0.08, 0.04}) {
    CAPTURE(C);
    mesher::MeshOptions options;
    options.probe_radius = probe;
    options.size.C = C;
    options.sweep.disc_factor = 0.5 * (options.size.disc_factor_lower() + options.size.disc_factor_upper());
    options.check = false;
    const mesher::MeshResult res = mesher::mesh_skin(mol, options);
    const std::vector<double> areas = skin::mesh_atom_areas(res.mesh, res.vertex_data.atom, mol.atoms.size());
    double sum = 0, mesh_area = 0;
    for (double a : areas) sum += a;
    for (const auto& c : geometry::component_measures(res.mesh)) mesh_area += c.area;
    CHECK(sum == doctest::Approx(mesh_area).epsilon(1e-12));
    CHECK(std::abs(sum / exact_sum - 1) < 0.01);
    // Atoms of no skin get no mesh area, as far as the vertices' atoms go.
    for (std::size_t i = 0; i < exact.size(); ++i)
      if (exact[i] == 0) CHECK(areas[i] == 0);
    const double l1 = relative_l1(areas, exact);
    MESSAGE("C = " << C << ": " << res.mesh.triangles.size() << " triangles, relative L1 difference " << l1);
    CHECK(l1 < previous);
    previous = l1;
  }
  CHECK(previous < 0.01);  // 0.0045 measured at C = 0.04
}

TEST_CASE("atom areas: a vertex without an atom adds to none; bad input is refused") {
  geometry::IndexedMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(3, 0, 0), Vec3(0, 4, 0)};
  mesh.triangles = {{0, 1, 2}};
  const std::vector<double> a = skin::mesh_atom_areas(mesh, {0, 1, -1}, 2);
  CHECK(a == std::vector<double>{2.0, 2.0});
  CHECK_THROWS_AS(skin::mesh_atom_areas(mesh, {0, 1}, 2), std::invalid_argument);
  mesh.triangles = {{0, 1, 5}};
  CHECK_THROWS_AS(skin::mesh_atom_areas(mesh, {0, 1, 1}, 2), std::invalid_argument);
}

}  // TEST_SUITE
