// bench/bench_main.cpp: main() of skinmesh_bench and the shared helpers of
// bench/bench_common.h. papers/conventions.md §3 "Benchmarks".
//
// Usage (Release build), one line:
//   skinmesh_bench --benchmark_out=bench.json --benchmark_out_format=json
//                  --benchmark_context=commit=$(git rev-parse HEAD)
// Google Benchmark records the machine (CPUs, caches, load) in the JSON
// context; --benchmark_context adds the commit. --benchmark_filter=BM_Skin
// selects a stage, --benchmark_min_time=0.05 gives a quick smoke run.
#include <array>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_common.h"
#include "geometry/kernel/predicates.h"
#include "skin/molecule_io.h"
#include "skin/skin_surface.h"

namespace skinmesh::bench {

std::string data_path(const std::string& file) { return std::string(SKINMESH_DATA) + "/" + file; }

skin::Molecule load_molecule(const std::string& file) { return skin::read_molecule(data_path(file)); }

std::vector<geometry::WeightedPoint> weighted_points(const skin::Molecule& molecule, double probe) {
  std::vector<geometry::WeightedPoint> points;
  points.reserve(molecule.atoms.size());
  for (const skin::Atom& a : molecule.atoms) points.push_back({a.centre, skin::atom_weight(a.radius, probe)});
  return points;
}

std::vector<geometry::WeightedPoint> molecule_points(const std::string& file, double probe) {
  return bench::weighted_points(load_molecule(file), probe);
}

std::string check_triangulation(const geometry::RegularTriangulation& rt) {
  using geometry::RegularTriangulation;
  int outer_faces = 0;
  for (Index t = 0; t < rt.num_tets(); ++t) {
    const std::array<Index, 4>& v = rt.tet(t);
    if (geometry::orient3d(rt.point(v[0]).z, rt.point(v[1]).z, rt.point(v[2]).z, rt.point(v[3]).z) != Sign::Positive)
      return "tetrahedron " + std::to_string(t) + " is not positively oriented";
    for (int i = 0; i < 4; ++i) {
      const Index u = rt.neighbor(t, i);
      if (u == kInvalidIndex) {
        ++outer_faces;
        continue;
      }
      int j = -1;
      for (int k = 0; k < 4; ++k)
        if (rt.neighbor(u, k) == t) j = k;
      if (j < 0) return "tetrahedra " + std::to_string(t) + " and " + std::to_string(u) + " are not mutual neighbours";
      const Index opposite = rt.tet(u)[j];
      if (rt.local_index(t, opposite) >= 0)
        return "tetrahedra " + std::to_string(t) + " and " + std::to_string(u) + " share all four vertices";
      if (rt.conflict(t, opposite) != Sign::Negative)
        return "face " + std::to_string(i) + " of tetrahedron " + std::to_string(t) + " is not locally regular";
    }
  }
  if (outer_faces != 4) return std::to_string(outer_faces) + " outer faces instead of 4";
  return {};
}

void set_rate(benchmark::State& state, const std::string& name, double per_iteration) {
  state.counters[name] =
      benchmark::Counter(per_iteration * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

}  // namespace skinmesh::bench

BENCHMARK_MAIN();
