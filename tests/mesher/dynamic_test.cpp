// tests/mesher/dynamic_test.cpp: the dynamic-skin baseline through the
// pipeline (Algorithm::Dynamic): the local frame of far-away inputs and the
// refusal of singular skins, shared with the sweep.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "core/errors.h"
#include "mesher/pipeline.h"
#include "skin/molecule_io.h"

using skinmesh::Vec3;
using skinmesh::geometry::WeightedPoint;
namespace mesher = skinmesh::mesher;

namespace {

std::vector<WeightedPoint> test_points(const std::string& name) {
  return skinmesh::skin::weighted_points(skinmesh::skin::read_molecule(std::string(SKINMESH_TEST_DATA) + "/" + name),
                                         0.0);
}

mesher::MeshOptions dynamic_options(bool growth) {
  mesher::MeshOptions opt;
  opt.algorithm = mesher::Algorithm::Dynamic;
  opt.dynamic.growth = growth;
  return opt;
}

}  // namespace

TEST_SUITE("mesher") {

TEST_CASE("dynamic: a molecule far from the origin meshes like the same molecule at the origin") {
  std::vector<WeightedPoint> pts = test_points("two_atoms.xyzr");
  const mesher::MeshResult near = mesher::mesh_skin(pts, dynamic_options(false));
  for (auto& p : pts) p.z += Vec3(1e5, -2e5, 3e5);
  const mesher::MeshResult far = mesher::mesh_skin(pts, dynamic_options(false));
  REQUIRE(far.checked);
  for (const std::string& p : far.check.problems) INFO(p);
  CHECK(far.check.ok());
  CHECK(far.algorithm == mesher::Algorithm::Dynamic);
  CHECK(far.dynamic.converged);
  CHECK(far.mesh.triangles.size() == near.mesh.triangles.size());
  CHECK(far.frame_centre.isApprox(near.frame_centre + Vec3(1e5, -2e5, 3e5)));
}

TEST_CASE("dynamic: a singular skin is refused with the atoms named, as the sweep refuses it") {
  // Two balls of radius sqrt(8) Å at distance sqrt(32) Å touch exactly (the
  // sweep's test of the same refusal, tests/mesher/sweep_test.cpp).
  const double w = skinmesh::skin::atom_weight(1.5, 0.5);
  const std::vector<WeightedPoint> touching = {{Vec3(20, 0, 0), w}, {Vec3(0, 0, 0), w}, {Vec3(4, 4, 0), w}};
  for (const bool growth : {false, true}) {
    try {
      (void)mesher::mesh_skin(touching, dynamic_options(growth));
      FAIL("a skin with a cone point was meshed");
    } catch (const skinmesh::InputError& e) {
      CHECK(std::string(e.what()).find("#2 and #3") != std::string::npos);
    }
  }
}

TEST_CASE("dynamic: the stages are timed in order, and the baseline's counts are reported") {
  const mesher::MeshResult res = mesher::mesh_skin(test_points("two_atoms.xyzr"), dynamic_options(true));
  std::vector<std::string> stages;
  for (const auto& [stage, seconds] : res.seconds) {
    stages.push_back(stage);
    CHECK(seconds >= 0);
  }
  CHECK(stages == std::vector<std::string>{"skin", "growth", "refine", "output", "check"});
  CHECK(res.dynamic.steps >= 3);
  CHECK(res.dynamic.predicates.orient3d.calls > 0);
  CHECK(res.critical.euler() == 0);  // the baseline has no Morse stage
  CHECK(res.check.ok());
}

}  // TEST_SUITE
