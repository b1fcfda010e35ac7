// tests/front/molecules_test.cpp: end to end on bundled molecules — read the
// file, build the skin and the Morse–Smale complex, sweep and refine, then
// verify with the skin-aware checker: closed, manifold, outward, embedded,
// vertices on the skin, the expected topology, angles above 21.5° and no
// [L] / [U] / restricted-Delaunay violation (issue #2, "Done when" item 2).
#include <doctest/doctest.h>

#include <string>

#include "front/pipeline.h"
#include "skin/molecule_io.h"
#include "tests/refine/check_expectations.h"

using namespace skinmesh;

namespace {

void mesh_and_check(const std::string& path, double probe = 1.4) {
  INFO(path);
  MeshOptions options;
  options.probe_radius = probe;
  const MeshResult res = mesh_skin(skin::read_molecule(path), options);
  REQUIRE(res.checked);
  test::check_every_property(res.check);
}

}  // namespace

TEST_SUITE("front") {

const std::string kData = SKINMESH_DATA;
const std::string kRegression = std::string(SKINMESH_TEST_DATA) + "/regression/";

TEST_CASE("molecules: ligand_1hpv_amprenavir") { mesh_and_check(kData + "/ligand_1hpv_amprenavir.pdb"); }
TEST_CASE("molecules: gramicidinA_1grm_model1") { mesh_and_check(kData + "/gramicidinA_1grm_model1.pdb"); }
TEST_CASE("molecules: crambin_1crn") { mesh_and_check(kData + "/crambin_1crn.pdb"); }
TEST_CASE("molecules: adna_3dna_fiber_30bp (genus 1)") { mesh_and_check(kData + "/adna_3dna_fiber_30bp.pdb"); }
TEST_CASE("molecules: ligand_1hvr_xk263") { mesh_and_check(kData + "/ligand_1hvr_xk263.pdb"); }

// Inputs that once broke the sweep (see papers/front/creep.md and papers/front/hole_filling.md).
TEST_CASE("regression: a neighbour's narrow spike that no fan fits (Figure 7), random 50 atoms") {
  mesh_and_check(kRegression + "random50_probe1.4_figure7_stuck.xyzr");
}
TEST_CASE("regression: forced wings chained next to a held vertex, gramicidin A at probe 0") {
  // Before wing_max_edge_factor: the wings of a held vertex's neighbours joined
  // it to ever farther front vertices (an edge of 3.7 r), the small hole left
  // there could not be sealed, and its enlargement swallowed the whole front
  // ("seal: no ear in a hole of 190 vertices").
  mesh_and_check(kData + "/gramicidinA_1grm_model1.pdb", 0.0);
}
TEST_CASE("regression: a hole tangled in every projection, random atoms with probe 0") {
  mesh_and_check(kRegression + "random_probe0_tangled_hole.xyzr", 0.0);
}

}  // TEST_SUITE
