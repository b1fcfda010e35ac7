// bench/mesh_bench.cpp: the meshing rate of the whole pipeline, the number the
// speed goals are stated in (papers/bench/profile.md): triangles of the output
// mesh per second of mesh_skin() from the weighted points to the output mesh —
// skin, Morse–Smale complex, sweep, refinement, angle improvement and output,
// without the built-in check (which `skinmesh mesh` runs after it) and
// without reading or writing files.
//
//   build/skinmesh_bench --benchmark_filter=BM_Mesh --benchmark_repetitions=5
//
// (this machine's run-to-run spread is large, 10-15 %: quote the "_median"
// rows of several repetitions).
//
// Arguments: the thread count (1 or 2; MeshOptions::threads). Counters:
// "triangles" (of the output mesh), "triangles/s" (the meshing rate), and the
// seconds of each stage, from MeshResult::seconds, averaged over the
// iterations. The first iteration's mesh is checked (every check of
// refine/skin_mesh_check.h) and the benchmark reports an error if it fails,
// so a rate is never quoted for a wrong mesh; every later iteration must give
// the same triangle count.
#include <map>
#include <string>

#include <benchmark/benchmark.h>

#include "bench/bench_common.h"
#include "front/pipeline.h"

namespace skinmesh::bench {
namespace {

void BM_Mesh(benchmark::State& state, const std::string& file, double probe) {
  const std::vector<geometry::WeightedPoint> points = molecule_points(file, probe);
  MeshOptions opt;
  opt.threads = static_cast<int>(state.range(0));
  {
    MeshOptions checked = opt;
    checked.check = true;
    const MeshResult r = mesh_skin(points, checked);
    if (!r.ok()) {
      state.SkipWithError(("the mesh of " + file + " fails its check").c_str());
      return;
    }
  }
  opt.check = false;
  std::size_t triangles = 0;
  std::map<std::string, double> stage_seconds;
  for (auto _ : state) {
    const MeshResult r = mesh_skin(points, opt);
    if (triangles != 0 && r.mesh.triangles.size() != triangles) {
      state.SkipWithError("the triangle count changed between iterations");
      return;
    }
    triangles = r.mesh.triangles.size();
    for (const auto& [stage, s] : r.seconds) stage_seconds[stage] += s;
    benchmark::DoNotOptimize(r.mesh.positions.data());
  }
  state.counters["triangles"] = static_cast<double>(triangles);
  set_rate(state, "triangles/s", static_cast<double>(triangles));
  for (const auto& [stage, s] : stage_seconds)
    state.counters[stage + "_s"] = s / static_cast<double>(state.iterations());
}

}  // namespace

// The three inputs of the speed goals, with 1 and 2 threads; real time, since
// the second thread's work is not in the main thread's CPU time.
BENCHMARK_CAPTURE(BM_Mesh, gramicidinA_probe1_4, "gramicidinA_1grm_model1.pdb", 1.4)
    ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Mesh, crambin_probe0, "crambin_1crn.pdb", 0.0)
    ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Mesh, maltoporin_probe1_4, "maltoporin_1af6.pdb", 1.4)
    ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace skinmesh::bench
