// bench/level_curves_bench.cpp: the cost of the decomposed sweep's cut curves
// (morse/level_curves, papers/morse/level_curves.md) against the rest of a
// run: BM_LevelCurves/<molecule> traces and samples every curve of one cut at
// the middle of the height range (at the height of largest clearance within
// ±25 % of the range); the skin and the Morse–Smale complex are built once, outside
// the timing. Counters: curves, samples, traced length (Å), ns per sample.
//   build/skinmesh_bench --benchmark_filter=BM_LevelCurves
#include <algorithm>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_common.h"
#include "morse/critical_points.h"
#include "morse/level_curves.h"
#include "morse/morse_smale_complex.h"
#include "skin/skin_surface.h"

namespace skinmesh::bench {

namespace {

void BM_LevelCurves(benchmark::State& state, const char* file, double probe) {
  const skin::SkinSurface skin(molecule_points(file, probe));
  const morse::MorseSmaleComplex ms = morse::build_morse_smale_complex(skin, morse::default_height_direction());
  double lo = 1e300, hi = -1e300;
  for (const auto& p : ms.critical) lo = std::min(lo, p.height), hi = std::max(hi, p.height);
  double c = 0.5 * (lo + hi), best = -1e300;
  for (int i = 0; i <= 100; ++i) {
    const double h = 0.5 * (lo + hi) + (hi - lo) * (i - 50) / 200.0;
    if (const double cl = morse::cut_clearance(ms, h); cl > best) best = cl, c = h;
  }
  std::size_t curves = 0, samples = 0;
  double length = 0;
  for (auto _ : state) {
    const auto result = morse::level_curves(skin, ms, c);
    curves = result.size(), samples = 0, length = 0;
    for (const auto& curve : result) samples += curve.points.size(), length += curve.length;
    benchmark::DoNotOptimize(samples);
  }
  state.counters["curves"] = static_cast<double>(curves);
  state.counters["samples"] = static_cast<double>(samples);
  state.counters["length_A"] = length;
  state.counters["clearance"] = best;
  state.counters["ns_per_sample"] = benchmark::Counter(
      static_cast<double>(samples) * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK_CAPTURE(BM_LevelCurves, crambin_probe0, "crambin_1crn.pdb", 0.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_LevelCurves, maltoporin, "maltoporin_1af6.pdb", kProbeRadius)->Unit(benchmark::kMillisecond);

}  // namespace skinmesh::bench
