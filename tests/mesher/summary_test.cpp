// tests/mesher/summary_test.cpp: the result schema (mesher/summary.h) — the
// same keys in the same order for both algorithms where they share them,
// every timing under "seconds", the mesh's measures equal to its own.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "geometry/mesh/mesh_measures.h"
#include "mesher/summary.h"
#include "tests/skin/skin_test_util.h"

namespace mesher = skinmesh::mesher;
using json = nlohmann::ordered_json;

namespace {

std::vector<std::string> keys_of(const json& j) {
  std::vector<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
  return keys;
}

/// True if a key named "seconds" or "peak_memory_bytes" occurs anywhere but at the top level.
bool timing_below_top(const json& j, bool top) {
  if (!j.is_object() && !j.is_array()) return false;
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (j.is_object() && !top && (it.key() == "seconds" || it.key() == "peak_memory_bytes")) return true;
    if (timing_below_top(*it, false)) return true;
  }
  return false;
}

}  // namespace

TEST_SUITE("mesher") {

TEST_CASE("summary: both algorithms share the schema; every timing is under seconds") {
  const auto points = skinmesh::test::two_balls();
  for (const mesher::Algorithm algorithm : {mesher::Algorithm::Sweep, mesher::Algorithm::Dynamic}) {
    mesher::MeshOptions options;
    options.algorithm = algorithm;
    const mesher::MeshResult res = mesher::mesh_skin(points, options);
    mesher::SummaryContext context;
    context.input = "two_balls";
    context.atoms = points.size();
    context.exact_measures_of = &points;
    context.read_seconds = 0.5;
    context.total_seconds = 2.0;
    const json j = mesher::run_summary(res, options, context);
    INFO(mesher::algorithm_name(algorithm));
    const std::vector<std::string> head = {
        "input",         "output",   "atoms",           "probe_radius",         "vertices",
        "triangles",     "surface",  "checked",         "min_angle_deg",        "max_angle_deg",
        "checks_passed", "problems", "critical_points", "live_critical_points", "algorithm",
        "threads"};
    const std::vector<std::string> keys = keys_of(j);
    REQUIRE(keys.size() > head.size());
    CHECK(std::vector<std::string>(keys.begin(), keys.begin() + head.size()) == head);
    CHECK(keys.back() == "seconds");  // no peak memory given
    CHECK(j["algorithm"] == mesher::algorithm_name(algorithm));
    CHECK(j["triangles"] == res.mesh.triangles.size());
    CHECK(j["checks_passed"] == res.check.ok());
    CHECK_FALSE(timing_below_top(j, true));
    // The program's seconds frame the pipeline's stages; the exact integration's are among them.
    const std::vector<std::string> stages = keys_of(j["seconds"]);
    CHECK(stages.front() == "read");
    CHECK(stages.back() == "total");
    CHECK(j["seconds"].contains("analytic"));
    CHECK(j["seconds"].size() == res.seconds.size() + 3);
    double area = 0;
    for (const auto& c : skinmesh::geometry::component_measures(res.mesh)) area += c.area;
    CHECK(j["surface"]["area_A2"].get<double>() == area);
    CHECK(std::abs(j["surface"]["mesh_relative_difference"]["area"].get<double>()) < 0.01);
    if (algorithm == mesher::Algorithm::Dynamic) {
      CHECK(j.contains("delaunay"));
      CHECK(j["operations"]["growth_steps"].get<std::size_t>() == res.dynamic.steps);
    } else {
      CHECK(j.contains("angle_improvement"));
      CHECK(j["operations"]["creeps"].get<std::size_t>() == res.sweep.creeps);
    }
  }
}

}  // TEST_SUITE
