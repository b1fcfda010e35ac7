// tests/mesher/fallback_test.cpp: the sweep's fallback where the front tangles
// (front/patch.cpp, papers/front/patch.md), end to end. Each regression input
// fails with the fallback off — so these tests test it — and with it on gives
// a mesh that passes every check of the skin-aware verifier (closed, manifold,
// outward, embedded, on the skin, the expected topology, [L], [U], restricted
// Delaunay, angles above 21.5°).
#include <doctest/doctest.h>

#include <map>
#include <string>
#include <vector>

#include "core/errors.h"
#include "mesher/pipeline.h"
#include "mesher/summary.h"
#include "skin/dual_complex.h"
#include "skin/molecule_io.h"
#include "skin/skin_surface.h"
#include "tests/verify/check_expectations.h"

using namespace skinmesh;

TEST_SUITE("mesher") {

TEST_CASE("fallback: a C60-like cage inside a geodesic shell, whose seal tangles in three height directions") {
  // 60 atoms on a truncated icosahedron of radius 8.7 Å inside 362 on a
  // geodesic sphere (frequency 6) of radius 20 Å, radius 1.7 Å, probe 1.4:
  // four sphere-like components. In these directions a hole on the shell's
  // inner surface is tangled in every projection and its enlargement pinches.
  const std::string path =
      std::string(SKINMESH_TEST_DATA) + "/regression/cage_in_geodesic_shell_probe1.4_tangled_seal.xyzr";
  const skin::Molecule mol = skin::read_molecule(path);
  for (const Vec3& e : {Vec3(-0.437678, -0.505737, 0.743416), Vec3(-0.300188, 0.819222, -0.488633),
                        Vec3(-0.571549, -0.571405, 0.588922)}) {
    CAPTURE(e.transpose());
    mesher::MeshOptions options;
    options.height_direction = e.normalized();
    options.sweep.patch_fallback = false;
    CHECK_THROWS_AS(mesher::mesh_skin(mol, options), TopologyError);
    options.sweep.patch_fallback = true;
    // Observers (the trace's recorder among them) see every patch, and seals
    // only for the holes the seal itself closed.
    std::map<front::SweepOperation, std::size_t> seen;
    options.sweep.observer = [&seen](const front::SweepEvent& ev) { ++seen[ev.op]; };
    const mesher::MeshResult res = mesher::mesh_skin(mol, options);
    CHECK(seen[front::SweepOperation::Patch] == res.sweep.patched_holes);
    CHECK(seen[front::SweepOperation::Seal] + seen[front::SweepOperation::SmallHole] == res.sweep.seals);
    CHECK(res.sweep.patched_holes >= 1);
    CHECK(res.sweep.patch_faces > 0);
    CHECK(res.expected_topology.components() == 4);
    REQUIRE(res.checked);
    test::check_every_property(res.check);
  }
}

TEST_CASE("whole-skin fallback: the static baseline meshes the skin where the sweep fails") {
  // The cage in a shell in a direction whose seal tangles: with the local
  // fallback off the sweep throws, and MeshOptions::static_fallback meshes
  // the whole skin by restricted Delaunay refinement instead, saying why.
  const skin::Molecule mol = skin::read_molecule(std::string(SKINMESH_TEST_DATA) +
                                                 "/regression/cage_in_geodesic_shell_probe1.4_tangled_seal.xyzr");
  mesher::MeshOptions options;
  options.height_direction = Vec3(-0.437678, -0.505737, 0.743416).normalized();
  options.sweep.patch_fallback = false;
  CHECK_THROWS_AS(mesher::mesh_skin(mol, options), TopologyError);
  options.static_fallback = true;
  const mesher::MeshResult res = mesher::mesh_skin(mol, options);
  CHECK(res.algorithm == mesher::Algorithm::Dynamic);
  CHECK(res.static_fallback.find("the sweep failed: topology: seal") == 0);
  CHECK(res.sweep.creeps == 0);  // the sweep's counts are not the mesh's
  CHECK(res.dynamic.converged);
  CHECK(res.dynamic.births > 0);
  CHECK(res.expected_topology.components() == 4);
  REQUIRE(res.checked);
  test::check_every_property(res.check);
  bool timed = false;
  for (const auto& [stage, t] : res.seconds) timed |= stage == "fallback refine";
  CHECK(timed);
  // --stats and Python's stats say which mesher made the mesh, and why.
  const auto summary = mesher::run_summary(res, options, mesher::SummaryContext{});
  CHECK(summary.at("algorithm") == "dynamic");
  CHECK(summary.at("static_fallback") == res.static_fallback);
  CHECK(summary.at("growth") == false);  // the static variant, whatever options.dynamic.growth says

  SUBCASE("a sweep mesh that fails its check is replaced, and the replacement checked again") {
    // An expected topology the skin does not have (one component more):
    // every mesh fails; the one returned is the baseline's, with its report.
    mesher::MeshOptions wrong;
    skin::SkinTopology t =
        skin::dual_complex_topology(skin::SkinSurface(skin::weighted_points(mol, 1.4)).mixed_complex());
    ++t.betti0;
    wrong.checks.expected_topology = t;
    wrong.static_fallback = true;
    const mesher::MeshResult r = mesher::mesh_skin(mol, wrong);
    CHECK(r.algorithm == mesher::Algorithm::Dynamic);
    CHECK(r.static_fallback.find("the sweep's mesh failed its check") == 0);
    REQUIRE(r.checked);
    CHECK_FALSE(r.check.ok());
    bool rechecked = false;
    for (const auto& [stage, sec] : r.seconds) rechecked |= stage == "fallback check";
    CHECK(rechecked);
  }
}

TEST_CASE("fallback: an all-atom lipid bilayer at probe 0, where a fan would cover meshed surface") {
  // 2 x 16 lipids with their hydrogens (bench/lipid_bilayer.py --lipids 4
  // --seed 1), probe 0: one fan, deferred max_deferrals times, still reaches an
  // interior vertex. Built anyway (the fallback off) it lays triangles over
  // the mesh; with the fallback its vertex is left for the seal, which closes
  // the opening.
  const std::string path =
      std::string(SKINMESH_TEST_DATA) + "/regression/bilayer_allatom_probe0_fan_over_meshed_surface.xyzr";
  const skin::Molecule mol = skin::read_molecule(path);
  mesher::MeshOptions options;
  options.probe_radius = 0;
  // One sweep, where the fan met the meshed surface (in the 2 slabs of
  // DecompositionOptions::detour_fallback, with a detoured cut, no fan does).
  options.decomposition.slabs = 1;
  const mesher::MeshResult res = mesher::mesh_skin(mol, options);
  CHECK(res.sweep.left_holes >= 1);
  CHECK(res.sweep.folds == 0);
  REQUIRE(res.checked);
  test::check_every_property(res.check);
}

TEST_CASE("fallback: folds at departure vertices anywhere in the sweep are re-opened or left for the seal") {
  // No input of ours folds at a departure vertex, so folds are injected
  // (SweepOptions::injected_folds): fold checks spread over the whole sweep,
  // then a run of consecutive ones that re-open one region until its vertices
  // may not be re-opened again, so that the last ones are left for the seal.
  const skin::Molecule mol = skin::read_molecule(std::string(SKINMESH_DATA) + "/crambin_1crn.pdb");
  mesher::MeshOptions options;
  options.probe_radius = 1.4;
  const mesher::MeshResult plain = mesher::mesh_skin(mol, options);
  REQUIRE(plain.sweep.folds == 0);
  const std::size_t creeps = plain.sweep.creeps;
  REQUIRE(creeps > 1000);
  struct Injection {
    const char* what;
    std::vector<std::size_t> checks;
  };
  std::vector<std::size_t> run;
  for (std::size_t i = 0; i < 40; ++i) run.push_back(creeps / 3 + i);
  for (const Injection& inj : {Injection{"spread", {0, 7, creeps / 10, creeps / 2, creeps - creeps / 10}},
                               Injection{"a run in one place", run}}) {
    CAPTURE(inj.what);
    options.sweep.injected_folds = inj.checks;
    options.sweep.patch_fallback = false;
    CHECK_THROWS_WITH_AS(mesher::mesh_skin(mol, options), doctest::Contains("folds"), TopologyError);
    options.sweep.patch_fallback = true;
    const mesher::MeshResult res = mesher::mesh_skin(mol, options);
    CHECK(res.sweep.folds >= inj.checks.size() / 2);
    if (inj.checks.size() > 10) CHECK(res.sweep.left_holes >= 1);
    REQUIRE(res.checked);
    test::check_every_property(res.check);
  }
}

TEST_CASE("fallback: every hole of the seal re-meshed by the patch") {
  // The patch is the seal's last resort; forced on every hole
  // (SweepOptions::force_patch_every = 1), each must be re-meshed (no
  // "forced patch failed" in the trace) and the mesh pass every check.
  for (const char* name : {"crambin_1crn.pdb", "gramicidinA_1grm_model1.pdb"}) {
    CAPTURE(name);
    const skin::Molecule mol = skin::read_molecule(std::string(SKINMESH_DATA) + "/" + name);
    mesher::MeshOptions options;
    options.probe_radius = 1.4;
    options.sweep.force_patch_every = 1;
    std::size_t failed = 0;
    options.sweep.trace = [&failed](const std::string& line) {
      failed += line.find("forced patch failed") != std::string::npos;
    };
    const mesher::MeshResult res = mesher::mesh_skin(mol, options);
    CHECK(failed == 0);
    CHECK(res.sweep.patched_holes >= 5);
    REQUIRE(res.checked);
    test::check_every_property(res.check);
  }
}

}  // TEST_SUITE
