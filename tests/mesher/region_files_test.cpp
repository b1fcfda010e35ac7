// tests/mesher/region_files_test.cpp: the decomposition over several
// processes (decompose/region_files.h, mesher::mesh_cuts, mesher::mesh_region,
// MeshOptions::cuts_file): the cuts and every slab's sweep written to files
// and read back must give the mesh of one process, vertex for vertex and
// triangle for triangle; files of other points or options are refused.
#include <doctest/doctest.h>

#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "core/errors.h"
#include "decompose/region_files.h"
#include "mesher/pipeline.h"
#include "skin/molecule_io.h"
#include "skin/skin_surface.h"
#include "tests/verify/check_expectations.h"

using namespace skinmesh;

namespace {

/// A fresh folder for one test's files, removed at the end.
struct Folder {
  std::filesystem::path path;
  explicit Folder(const std::string& name)
      : path(std::filesystem::temp_directory_path() / ("skinmesh-" + name + "-" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~Folder() { std::filesystem::remove_all(path); }
  std::string operator/(const std::string& file) const { return (path / file).string(); }
};

}  // namespace

TEST_SUITE("mesher") {
TEST_CASE("regions over processes: the cuts and slabs read back from files give the one-process mesh") {
  struct Case {
    const char* file;
    double probe;
    int slabs;
    bool detours;
  };
  std::size_t detour_balls = 0;
  for (const Case& c : {Case{"crambin_1crn.pdb", 1.4, 4, false}, Case{"gramicidinA_1grm_model1.pdb", 0.0, 8, true}}) {
    CAPTURE(c.file);
    const skin::Molecule mol = skin::read_molecule(std::string(SKINMESH_DATA) + "/" + c.file);
    mesher::MeshOptions options;
    options.probe_radius = c.probe;
    options.decomposition.slabs = c.slabs;
    options.decomposition.detours = c.detours;
    options.threads = 1;
    const mesher::MeshResult one = mesher::mesh_skin(mol, options);
    REQUIRE(one.ok());

    const Folder dir("regions");
    const std::vector<geometry::WeightedPoint> points = skin::weighted_points(mol, c.probe);
    const decompose::CutsFile cuts = mesher::mesh_cuts(points, options);
    REQUIRE(cuts.cuts.size() >= 2);
    decompose::write_cuts(dir / "cuts.bin", cuts);
    const decompose::CutsFile back = decompose::read_cuts(dir / "cuts.bin");
    REQUIRE(back.cuts.size() == cuts.cuts.size());
    CHECK(back.fingerprint == cuts.fingerprint);
    for (std::size_t k = 0; k < cuts.cuts.size(); ++k) {
      CHECK(back.cuts[k].height == cuts.cuts[k].height);
      REQUIRE(back.cuts[k].curves.size() == cuts.cuts[k].curves.size());
      for (std::size_t i = 0; i < cuts.cuts[k].curves.size(); ++i) {
        CHECK(back.cuts[k].curves[i].points == cuts.cuts[k].curves[i].points);
        CHECK(back.cuts[k].curves[i].cells == cuts.cuts[k].curves[i].cells);
        CHECK(back.cuts[k].curves[i].ball == cuts.cuts[k].curves[i].ball);
      }
      REQUIRE(back.cuts[k].detours.size() == cuts.cuts[k].detours.size());
      for (std::size_t d = 0; d < cuts.cuts[k].detours.size(); ++d) {
        CHECK(back.cuts[k].detours[d].upper == cuts.cuts[k].detours[d].upper);
        REQUIRE(back.cuts[k].detours[d].balls.size() == cuts.cuts[k].detours[d].balls.size());
        detour_balls += cuts.cuts[k].detours[d].balls.size();
        for (std::size_t b = 0; b < cuts.cuts[k].detours[d].balls.size(); ++b) {
          CHECK(back.cuts[k].detours[d].balls[b].center == cuts.cuts[k].detours[d].balls[b].center);
          CHECK(back.cuts[k].detours[d].balls[b].critical == cuts.cuts[k].detours[d].balls[b].critical);
        }
      }
    }

    // Every slab but the second in a file of its own; the second is swept
    // by the process that glues.
    std::vector<std::string> files;
    const std::size_t slabs = cuts.cuts.size() + 1;
    for (std::size_t k = 0; k < slabs; ++k) {
      if (k == 1) continue;
      const decompose::RegionFile region = mesher::mesh_region(points, options, back, k);
      CHECK(region.slab == decompose::slabs_between(cuts.cuts.size())[k]);
      files.push_back(dir / ("region" + std::to_string(k) + ".bin"));
      decompose::write_region(files.back(), region);
      const decompose::RegionFile read = decompose::read_region(files.back());
      CHECK(read.slab == region.slab);
      REQUIRE(read.outcome.result.has_value() == region.outcome.result.has_value());
      if (read.outcome.result) {
        CHECK(read.outcome.result->mesh.n_faces() == region.outcome.result->mesh.n_faces());
        CHECK(read.outcome.result->upper_rims == region.outcome.result->upper_rims);
        CHECK(read.outcome.result->lower_loops == region.outcome.result->lower_loops);
      } else {
        CHECK(read.outcome.error == region.outcome.error);
      }
    }
    mesher::MeshOptions glue = options;
    glue.cuts_file = dir / "cuts.bin";
    glue.region_files = files;
    const mesher::MeshResult res = mesher::mesh_skin(mol, glue);
    CHECK(res.cut_heights == one.cut_heights);
    CHECK(res.mesh.positions == one.mesh.positions);
    CHECK(res.mesh.triangles == one.mesh.triangles);
    REQUIRE(res.checked);
    test::check_every_property(res.check);

    // The files are what the glue takes: a slab whose file says it failed
    // drops its upper cut, as a slab that failed in this process would.
    decompose::RegionFile failed;
    failed.fingerprint = cuts.fingerprint;
    failed.slab = decompose::slabs_between(cuts.cuts.size())[0];
    failed.outcome.error = "a failure written to the file";
    decompose::write_region(dir / "failed.bin", failed);
    mesher::MeshOptions with_failure = glue;
    with_failure.region_files = {dir / "failed.bin"};
    const mesher::MeshResult dropped = mesher::mesh_skin(mol, with_failure);
    REQUIRE(dropped.dropped_cuts.size() == 1);
    CHECK(dropped.dropped_cuts[0].why == "a failure written to the file");
    CHECK(dropped.slabs == slabs - 1);
    CHECK(dropped.ok());

    // Files of other options are refused, before any mesh is made.
    mesher::MeshOptions other = glue;
    other.probe_radius = c.probe + 0.1;
    CHECK_THROWS_AS(mesher::mesh_skin(mol, other), InputError);
    other = options;
    other.decomposition.slabs = c.slabs + 1;
    CHECK_THROWS_AS(mesher::mesh_region(points, other, back, 0), InputError);
    other = options;
    other.sweep.patch_fallback = false;  // --no-fallback: the region's sweep may differ
    CHECK_THROWS_AS(mesher::mesh_region(points, other, back, 0), InputError);
    CHECK_THROWS_AS(mesher::mesh_region(points, options, back, slabs), std::invalid_argument);
    // A region listed twice, and a cuts file given as a region file.
    other = glue;
    other.region_files.push_back(files.front());
    CHECK_THROWS_WITH_AS(mesher::mesh_skin(mol, other), doctest::Contains("same slab"), InputError);
    other = glue;
    other.region_files = {dir / "cuts.bin"};
    CHECK_THROWS_WITH_AS(mesher::mesh_skin(mol, other), doctest::Contains("cuts.bin"), InputError);
  }
  CHECK(detour_balls > 0);  // the detours' balls went through the files too
}

TEST_CASE("regions over processes: a failed slab's file keeps its failure") {
  const Folder dir("failed");
  decompose::RegionFile failed;
  failed.fingerprint = 42;
  failed.slab = {2, 3};
  failed.outcome.error = "the hole of 6 vertices is not a simple polygon";
  failed.outcome.at_lower_cut = true;
  decompose::write_region(dir / "r.bin", failed);
  const decompose::RegionFile read = decompose::read_region(dir / "r.bin");
  CHECK(read.fingerprint == 42);
  CHECK(read.slab == failed.slab);
  CHECK_FALSE(read.outcome.result.has_value());
  CHECK(read.outcome.error == failed.outcome.error);
  CHECK(read.outcome.at_lower_cut);
  CHECK_THROWS_WITH_AS(decompose::read_region(dir / "missing.bin"), doctest::Contains("missing.bin"), InputError);
}
}
