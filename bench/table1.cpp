// bench/table1.cpp: the mesher benchmark that reproduces Cheng & Shi 2004,
// Table 1 (per molecule: triangles, minimum angle, computing time of the sweep),
// on the stand-ins for its molecules listed in data/README.md, and the meshing
// rate the speed goals are stated in (papers/bench/profile.md).
// papers/conventions.md §3 "Benchmarks". (`make table1` runs the sweep against
// the dynamic-skin baseline; bench/table1/table1_main.cpp.)
//
// BM_SweepMesher/<molecule>/<threads> times the whole pipeline from weighted
// points to the output mesh (skin, critical points and Morse–Smale complex,
// sweep, local refinement, angle improvement, output), with mesher::MeshOptions::threads
// = <threads>, in real time; the verification runs once, outside the timed
// loop. This machine's run-to-run spread is 10-15 %: quote the medians of
// several repetitions, e.g.
//   build/skinmesh_bench --benchmark_filter=BM_SweepMesher --benchmark_repetitions=5
//                        --benchmark_report_aggregates_only=true
#include <map>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_common.h"
#include "geometry/kernel/weighted_point.h"
#include "geometry/mesh/indexed_mesh.h"
#include "mesher/pipeline.h"
#include "skin/skin_surface.h"
#include "verify/skin_mesh_check.h"

namespace skinmesh::bench {

/// Times the whole pipeline `mesh(points, threads)` on a bundled molecule,
/// threads = state.range(0): `Mesher` is any callable taking
/// `const std::vector<geometry::WeightedPoint>&` (weights atom_weight(r,
/// probe), probe in Å) and an int, and returning a mesher::MeshResult. Before the loop
/// the mesh is built once and verified with verify::check_skin_mesh(), so a
/// fast broken mesh cannot win; a failing check reports the first problem as
/// the benchmark's error, and so does a later iteration whose triangle count
/// differs. Counters: atoms, vertices, triangles, min_angle_deg (of the checked
/// mesh), triangles_per_s (kIsRate) and the mean seconds of each stage
/// (mesher::MeshResult::seconds: skin_s, morse_s, sweep_s, refine_s, angles_s, output_s).
template <class Mesher>
void BM_SweepMesher(benchmark::State& state, Mesher mesh, const char* molecule_file, double probe) {
  const std::vector<geometry::WeightedPoint> points = molecule_points(molecule_file, probe);
  const int threads = static_cast<int>(state.range(0));
  std::size_t triangles = 0;
  {
    const skin::SkinSurface skin(points);
    const geometry::IndexedMesh m = mesh(points, threads).mesh;
    const verify::SkinCheckReport report = verify::check_skin_mesh(skin, m);
    if (!report.ok()) {
      state.SkipWithError(report.problems.front().c_str());
      return;
    }
    triangles = m.triangles.size();
    state.counters["vertices"] = static_cast<double>(m.positions.size());
    state.counters["min_angle_deg"] = report.mesh.min_angle_deg;
  }
  std::map<std::string, double> stage_seconds;
  for (auto _ : state) {
    const mesher::MeshResult r = mesh(points, threads);
    if (r.mesh.triangles.size() != triangles) {
      state.SkipWithError("the triangle count changed between runs");
      return;
    }
    for (const auto& [stage, sec] : r.seconds) stage_seconds[stage] += sec;
    benchmark::DoNotOptimize(r.mesh.triangles.data());
  }
  state.counters["atoms"] = static_cast<double>(points.size());
  state.counters["triangles"] = static_cast<double>(triangles);
  set_rate(state, "triangles_per_s", static_cast<double>(triangles));
  for (const auto& [stage, sec] : stage_seconds)
    state.counters[stage + "_s"] = sec / static_cast<double>(state.iterations());
}

/// Times the built-in verification alone (verify::check_skin_mesh: closed,
/// manifold, outward, exact self-intersections, topology, distance to the
/// skin, angles, [L], [U], restricted Delaunay) on the mesh of a bundled
/// molecule at probe radius `probe` (Å), built once before the loop. Its time
/// against BM_SweepMesher's on the same input is the check's share
/// (issue #7 asks for at most half). `threads`: skin::RunContext::threads (1:
/// all on this thread; 2: the mesh-only checks on a second thread).
/// Counters: triangles, triangles_per_s.
void BM_SkinMeshCheck(benchmark::State& state, const char* molecule_file, double probe, int threads) {
  const std::vector<geometry::WeightedPoint> points = molecule_points(molecule_file, probe);
  mesher::MeshOptions options;
  options.check = false;
  const mesher::MeshResult res = mesher::mesh_skin(points, options);
  // The pipeline meshes in a local frame and returns global positions; the
  // check runs on the same frame as the command line's `skinmesh check`.
  const Vec3 centre = skin::local_frame_centre(points);
  const skin::SkinSurface skin(skin::translated(points, centre));
  geometry::IndexedMesh local = res.mesh;
  for (Vec3& p : local.positions) p -= centre;
  skin::RunContext run;
  run.threads = threads;
  for (auto _ : state) {
    const verify::SkinCheckReport report = verify::check_skin_mesh(skin, local, {}, run);
    if (!report.ok()) {
      state.SkipWithError(report.problems.front().c_str());
      return;
    }
    benchmark::DoNotOptimize(report.mesh.min_angle_deg);
  }
  state.counters["triangles"] = static_cast<double>(local.triangles.size());
  set_rate(state, "triangles_per_s", static_cast<double>(local.triangles.size()));
}

/// The pipeline the command line runs (skinmesh mesh, default options but
/// `threads`), from weighted points to the output mesh.
mesher::MeshResult sweep_mesher(const std::vector<geometry::WeightedPoint>& points, int threads) {
  mesher::MeshOptions options;
  options.check = false;  // verified once, outside the timed loop
  options.threads = threads;
  return mesher::mesh_skin(points, options);
}

// Table 1 stand-ins (data/README.md), then crambin and the rest of the size
// ladder, at the paper's probe 1.4 Å, one thread; then probe 0 (the van der
// Waals skin). The three inputs of the speed goals (gramicidin A at 1.4,
// crambin at 0, maltoporin at 1.4) with 1 and 2 threads.
BENCHMARK_CAPTURE(BM_SweepMesher, ligand_1hpv_amprenavir, sweep_mesher, "ligand_1hpv_amprenavir.pdb", 1.4)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SweepMesher, gramicidinA_1grm_model1, sweep_mesher, "gramicidinA_1grm_model1.pdb", 1.4)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SweepMesher, adna_3dna_fiber_30bp, sweep_mesher, "adna_3dna_fiber_30bp.pdb", 1.4)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SweepMesher, crambin_1crn, sweep_mesher, "crambin_1crn.pdb", 1.4)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SweepMesher, hivprotease_xk263_1hvr, sweep_mesher, "hivprotease_xk263_1hvr.pdb", 1.4)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SweepMesher, maltoporin_1af6, sweep_mesher, "maltoporin_1af6.pdb", 1.4)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SweepMesher, gramicidinA_1grm_model1_probe0, sweep_mesher, "gramicidinA_1grm_model1.pdb", 0.0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SweepMesher, crambin_1crn_probe0, sweep_mesher, "crambin_1crn.pdb", 0.0)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The check's share: the same inputs as the two rates issue #7 asks for.
BENCHMARK_CAPTURE(BM_SkinMeshCheck, gramicidinA_1grm_model1_1thread, "gramicidinA_1grm_model1.pdb", 1.4, 1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SkinMeshCheck, crambin_1crn_probe0_1thread, "crambin_1crn.pdb", 0.0, 1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SkinMeshCheck, gramicidinA_1grm_model1_2threads, "gramicidinA_1grm_model1.pdb", 1.4, 2)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SkinMeshCheck, crambin_1crn_probe0_2threads, "crambin_1crn.pdb", 0.0, 2)
    ->Unit(benchmark::kMillisecond);

}  // namespace skinmesh::bench
