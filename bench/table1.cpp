// bench/table1.cpp: the mesher benchmark that reproduces Cheng & Shi 2004,
// Table 1 (per molecule: triangles, minimum angle, computing time of the sweep
// and of the dynamic skin algorithm), on the stand-ins for its molecules listed
// in data/README.md. STYLE.md §3 "Benchmarks".
//
// *** PLACEHOLDER: NOTHING IS REGISTERED YET. ***
// The sweep mesher (front/) does not exist yet. BM_SweepMesher below is written
// against any callable `mesh(points) -> geometry::IndexedMesh`, so plugging
// front::mesh_skin in is a matter of adding the registrations at the end of
// this file. A benchmark that times nothing is deliberately not registered.
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_common.h"
#include "geometry/indexed_mesh.h"
#include "geometry/weighted_point.h"
#include "refine/skin_mesh_check.h"
#include "skin/skin_surface.h"

namespace skinmesh::bench {

/// Times the whole pipeline `mesh(points)` on a bundled molecule: `Mesher` is
/// any callable taking `const std::vector<geometry::WeightedPoint>&` (weights
/// atom_weight(r, 1.4)) and returning a geometry::IndexedMesh. Before the
/// loop the mesh is built once and verified with refine::check_skin_mesh(), so
/// a fast broken mesh cannot win; a failing check reports the first problem
/// as the benchmark's error. Counters: atoms, vertices, triangles,
/// min_angle_deg (of the checked mesh) and triangles_per_s (kIsRate).
template <class Mesher>
void BM_SweepMesher(benchmark::State& state, Mesher mesh, const char* molecule_file) {
  const std::vector<geometry::WeightedPoint> points = molecule_points(molecule_file);
  double triangles = 0;
  {
    const skin::SkinSurface skin(points);
    const geometry::IndexedMesh m = mesh(points);
    const refine::SkinCheckReport report = refine::check_skin_mesh(skin, m);
    if (!report.ok()) {
      state.SkipWithError(report.problems.front().c_str());
      return;
    }
    triangles = static_cast<double>(m.triangles.size());
    state.counters["vertices"] = static_cast<double>(m.positions.size());
    state.counters["min_angle_deg"] = report.mesh.min_angle_deg;
  }
  for (auto _ : state) {
    const geometry::IndexedMesh m = mesh(points);
    benchmark::DoNotOptimize(m.triangles.data());
  }
  state.counters["atoms"] = static_cast<double>(points.size());
  state.counters["triangles"] = triangles;
  set_rate(state, "triangles_per_s", triangles);
}

// ---- Table 1 registrations: add when front/ provides the sweep mesher. ----
// With a free function (or a namespace-scope lambda) adapting its signature,
// e.g.
//
//   geometry::IndexedMesh sweep_mesh(const std::vector<geometry::WeightedPoint>& p) {
//     return front::mesh_skin(p, front::MeshingOptions{});
//   }
//
// register one benchmark per Table 1 stand-in (data/README.md), named
// BM_SweepMesher/<molecule>:
//
//   BENCHMARK_CAPTURE(BM_SweepMesher, ligand_1hpv_amprenavir, sweep_mesh,
//                     "ligand_1hpv_amprenavir.pdb")->Unit(benchmark::kMillisecond);
//   BENCHMARK_CAPTURE(BM_SweepMesher, gramicidinA_1grm_model1, sweep_mesh,
//                     "gramicidinA_1grm_model1.pdb")->Unit(benchmark::kMillisecond);
//   BENCHMARK_CAPTURE(BM_SweepMesher, adna_3dna_fiber_30bp, sweep_mesh,
//                     "adna_3dna_fiber_30bp.pdb")->Unit(benchmark::kMillisecond);
//
// (crambin_1crn and src_kinase_2src are not in the paper's table but make the
// size ladder continuous.) The dynamic-skin baseline can reuse the same
// template as BM_DynamicSkin/<molecule>.

}  // namespace skinmesh::bench
