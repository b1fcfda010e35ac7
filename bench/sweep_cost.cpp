// bench/sweep_cost.cpp: the sweep's cost per triangle over inputs whose local
// length scales rho span very different ranges (issue #25 item 2: costs set by
// the local size, not by a global maximum). BM_SweepCost/<input> times the
// sweep stage alone (mesher::MeshResult::seconds "sweep"; the skin and the
// Morse–Smale complex are built in every iteration but not counted) and
// reports sweep_ns_per_triangle: within a small factor across the inputs when
// the sweep's grids, searches and budgets follow the local rho.
//   build/skinmesh_bench --benchmark_filter=BM_SweepCost --benchmark_repetitions=3
//                        --benchmark_report_aggregates_only=true
// Before and after: papers/bench/sweep_cost.md.
#include <cmath>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_common.h"
#include "mesher/pipeline.h"
#include "skin/molecule_io.h"
#include "skin/skin_surface.h"

namespace skinmesh::bench {

namespace {

/// The bundled molecule `file` at probe `probe` (Å), plus, if bead > 0, one
/// atom of radius `bead` (Å) 2 bead + 20 Å beyond the molecule's largest x: a
/// separate component of large rho, which a grid sized by the largest rho
/// makes every query near the molecule pay for.
std::vector<geometry::WeightedPoint> with_bead(const char* file, double probe, double bead) {
  std::vector<geometry::WeightedPoint> points = molecule_points(file, probe);
  if (bead > 0) {
    double xmax = -1e300, ysum = 0, zsum = 0;
    for (const auto& p : points) xmax = std::max(xmax, p.z.x()), ysum += p.z.y(), zsum += p.z.z();
    const double n = static_cast<double>(points.size());
    points.push_back({Vec3(xmax + 2 * bead + 20, ysum / n, zsum / n), skin::atom_weight(bead, probe)});
  }
  return points;
}

/// A face-centred cubic lattice of 2 x 2 x 2 cells of atoms of radius 1.6 Å at
/// probe 0 whose nearest neighbours' unshrunk balls are `gap` (Å) apart: thin
/// gaps where rho falls to the gap's scale (the stress cases lattice/fcc2/nn-*).
std::vector<geometry::WeightedPoint> fcc_near_threshold(double gap) {
  const double r = 1.6, w = skin::atom_weight(r, 0.0);
  const double a = (2 * std::sqrt(w) + gap) * std::sqrt(2.0);  // nearest neighbours a / sqrt(2) apart
  const Vec3 basis[4] = {Vec3(0, 0, 0), Vec3(0.5, 0.5, 0), Vec3(0.5, 0, 0.5), Vec3(0, 0.5, 0.5)};
  std::vector<geometry::WeightedPoint> points;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k)
        for (const Vec3& b : basis) points.push_back({a * (Vec3(i, j, k) + b), w});
  return points;
}

/// Times the sweep on `points` (the whole pipeline without refinement and
/// check; before the loop the sweep's mesh is checked once to be closed with
/// the skin's Euler characteristic). Counters: triangles (of the sweep),
/// sweep_s (mean), sweep_ns_per_triangle.
void run_sweep_cost(benchmark::State& state, const std::vector<geometry::WeightedPoint>& points) {
  mesher::MeshOptions options;
  options.refine = false;
  options.check = false;
  options.threads = 1;
  std::size_t triangles = 0;
  {
    const mesher::MeshResult r = mesher::mesh_skin(points, options);
    const long chi = static_cast<long>(r.mesh.positions.size()) - static_cast<long>(r.mesh.triangles.size()) / 2;
    if (chi != r.expected_topology.euler_skin()) {
      state.SkipWithError("the sweep's mesh does not have the skin's Euler characteristic");
      return;
    }
    triangles = r.mesh.triangles.size();
  }
  double sweep = 0;
  for (auto _ : state) {
    const mesher::MeshResult r = mesher::mesh_skin(points, options);
    for (const auto& [stage, sec] : r.seconds)
      if (stage == "sweep") sweep += sec;
    benchmark::DoNotOptimize(r.mesh.triangles.data());
  }
  const double per_iteration = sweep / static_cast<double>(state.iterations());
  state.counters["atoms"] = static_cast<double>(points.size());
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["sweep_s"] = per_iteration;
  state.counters["sweep_ns_per_triangle"] = 1e9 * per_iteration / static_cast<double>(triangles);
}

void BM_SweepCost(benchmark::State& state, const char* file, double probe, double bead) {
  run_sweep_cost(state, with_bead(file, probe, bead));
}

void BM_SweepCostLattice(benchmark::State& state, double gap) { run_sweep_cost(state, fcc_near_threshold(gap)); }

/// The dense low-resolution-like dimer that bench/lowres_dimer.py builds from
/// src kinase at configure time (two copies pressed together, clashes kept,
/// coordinates with 0.3 Å of noise): issue #25's 4.2 Å dimer, whose sweep at
/// probe 0 once ran for more than 15 minutes.
void BM_SweepCostDimer(benchmark::State& state, double probe) {
  run_sweep_cost(state, bench::weighted_points(skin::read_molecule(SKINMESH_BENCH_DIMER), probe));
}

/// A regression input of tests/data/regression: PDB 3P3W, a 4.2 Å structure of
/// 11,484 atoms whose sweep at probe 0 once never ended (papers/front/
/// collision_net.md, "A triangle over another front"). One iteration: its
/// sweep at probe 0 makes 14 M triangles.
void BM_SweepCostRegression(benchmark::State& state, const char* file, double probe) {
  run_sweep_cost(state, bench::weighted_points(
                            skin::read_molecule(std::string(SKINMESH_TEST_DATA) + "/regression/" + file), probe));
}

}  // namespace

BENCHMARK_CAPTURE(BM_SweepCost, ligand_probe1 .4, "ligand_1hpv_amprenavir.pdb", 1.4, 0.0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SweepCost, crambin_probe1 .4, "crambin_1crn.pdb", 1.4, 0.0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SweepCost, crambin_probe0, "crambin_1crn.pdb", 0.0, 0.0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SweepCost, crambin_probe0_bead12, "crambin_1crn.pdb", 0.0, 12.0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SweepCost, crambin_probe0_bead40, "crambin_1crn.pdb", 0.0, 40.0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SweepCost, crambin_probe0_bead120, "crambin_1crn.pdb", 0.0, 120.0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SweepCost, hivprotease_probe0, "hivprotease_xk263_1hvr.pdb", 0.0, 0.0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SweepCostDimer, lowres_dimer_probe1 .4, 1.4)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_SweepCostDimer, lowres_dimer_probe0, 0.0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_SweepCostRegression, pdb3p3w_probe0, "pdb3p3w.pdb.gz", 0.0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_SweepCostLattice, fcc2_gap1e - 3, 1e-3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_SweepCostLattice, fcc2_gap1e - 4, 1e-4)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace skinmesh::bench
