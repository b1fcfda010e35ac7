// bench/skin_bench.cpp: benchmarks of skin/ and morse/ on the bundled
// molecules: building the skin (regular triangulation + mixed complex),
// evaluating f / grad f / rho near the skin, the normal-line projection of
// Cheng & Shi Figure 9, and the Morse–Smale complex of the height function.
// papers/conventions.md §3 "Benchmarks"; skin/skin_surface.h,
// morse/morse_smale_complex.h.
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_common.h"
#include "core/errors.h"
#include "morse/critical_points.h"
#include "morse/morse_smale_complex.h"
#include "skin/dual_complex.h"
#include "skin/size_conditions.h"
#include "skin/skin_surface.h"

namespace skinmesh::bench {
namespace {

using skin::SkinSurface;

/// Tolerance of the setup checks, relative to the input length scale L (f in
/// Å² against L², distances in Å against L), as constructions are measured in
/// papers/skin/skin_math.md §9. Loose on purpose: the checks catch wrong results,
/// the tests pin down accuracy.
constexpr double kCheckTolerance = 1e-9;

// Skin Points ------------------------------------------------------------------

/// Attempts per atom when collecting skin points (most points of an atom's
/// shrunk sphere lie inside its neighbours' and are rejected).
constexpr int kAttemptsPerAtom = 16;

/// A point on the skin with its outward unit normal, local length scale and cell.
struct SkinPoint {
  Vec3 x;
  Vec3 normal;
  double rho;
  Index cell;
};

/// Skin points in atom order (consecutive atoms are usually bonded, so
/// consecutive points are close): for each atom, kAttemptsPerAtom random points
/// of its shrunk sphere |x - z| = sqrt(w / 2) (the sphere patch of its vertex
/// cell, papers/skin/skin_math.md §3.2), kept when their distance estimate
/// |f| / |grad f| is below a quarter of rho (pull_back converges from about
/// rho / 2) and then pulled back onto the skin. Points of buried atoms are
/// dropped that way.
std::vector<SkinPoint> skin_points(const SkinSurface& skin) {
  std::mt19937_64 rng(0x5EED2004ULL);
  std::normal_distribution<double> g;
  std::vector<SkinPoint> out;
  Index hint = kInvalidIndex;
  for (const geometry::WeightedPoint& b : skin.points()) {
    for (int k = 0; k < kAttemptsPerAtom; ++k) {
      const Vec3 dir(g(rng), g(rng), g(rng));
      if (dir.norm() < 1e-3) continue;
      const Vec3 x0 = b.z + std::sqrt(b.w / 2) * dir.normalized();
      const skin::SkinSample s0 = skin.sample(x0, hint);
      hint = s0.cell;
      const double grad = s0.gradient.norm();
      if (grad == 0 || std::abs(s0.f) / grad > 0.25 * s0.rho) continue;
      Index cell = s0.cell;
      Vec3 a;
      try {
        a = skin.pull_back(x0, cell);
      } catch (const GeometryError&) {
        continue;  // setup only: such a point is simply not used
      }
      const skin::SkinSample s = skin.sample(a, cell);
      if (s.gradient.norm() == 0) continue;
      out.push_back({a, s.gradient.normalized(), s.rho, s.cell});
    }
  }
  return out;
}

// Skin Benchmarks --------------------------------------------------------------

void BM_SkinSurface(benchmark::State& state, const char* molecule_file) {
  const auto points = molecule_points(molecule_file);
  {
    const SkinSurface skin(points);
    const skin::MixedComplex& mc = skin.mixed_complex();
    state.counters["tets"] = skin.triangulation().num_tets();
    state.counters["cells"] = mc.num_cells();
    state.counters["skin_euler"] = skin::dual_complex_topology(mc).euler_skin();
  }
  for (auto _ : state) {
    SkinSurface skin(points);
    benchmark::DoNotOptimize(skin.mixed_complex().num_cells());
  }
  state.counters["atoms"] = static_cast<double>(points.size());
  set_rate(state, "atoms_per_s", static_cast<double>(points.size()));
}

/// Sample points around a skin point a, as a fraction of rho(a): up to
/// kSampleOffset along a random tangent and up to ±kSampleOffset along the
/// normal, i.e. near the skin on both sides, at the spacing of a mesh fan
/// (tangent-disc radii are about 0.1-0.2 rho, Cheng & Shi §4.2).
constexpr double kSampleOffset = 0.2;
/// Consecutive queries around the same skin point, so that the cell hint of
/// the previous query is nearby, as in the mesher; the next group jumps to the
/// next skin point (same or next atom).
constexpr int kQueriesPerPoint = 4;

void BM_SkinSample(benchmark::State& state, const char* molecule_file) {
  const SkinSurface skin(molecule_points(molecule_file));
  const std::vector<SkinPoint> base = skin_points(skin);
  if (base.empty()) {
    state.SkipWithError("no skin points");
    return;
  }
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g;
  std::vector<Vec3> queries;
  for (const SkinPoint& a : base)
    for (int k = 0; k < kQueriesPerPoint; ++k) {
      const Vec3 t = a.normal.cross(Vec3(g(rng), g(rng), g(rng)));
      if (t.norm() < 1e-6) continue;
      const double along = kSampleOffset * u(rng), across = kSampleOffset * (2 * u(rng) - 1);
      queries.push_back(a.x + a.rho * (along * t.normalized() + across * a.normal));
    }
  // Check once: the hinted walk gives the value of an unhinted location.
  const double L = skin.length_scale();
  Index hint = base.front().cell;
  for (const Vec3& q : queries) {
    const skin::SkinSample hinted = skin.sample(q, hint);
    const skin::SkinSample cold = skin.sample(q);
    if (std::abs(hinted.f - cold.f) > kCheckTolerance * L * L) {
      state.SkipWithError("sample() with a hint differs from sample() without");
      return;
    }
    hint = hinted.cell;
  }
  hint = base.front().cell;
  for (auto _ : state) {
    for (const Vec3& q : queries) {
      const skin::SkinSample s = skin.sample(q, hint);
      benchmark::DoNotOptimize(s);
      hint = s.cell;
    }
  }
  state.counters["atoms"] = static_cast<double>(skin.points().size());
  state.counters["samples"] = static_cast<double>(queries.size());
  set_rate(state, "samples_per_s", static_cast<double>(queries.size()));
}

/// Tangent-disc radius r = 0.185 rho(a) of the projection: inside the window
/// (0.1074, 0.2077) rho of Cheng & Shi §4.2 (skin::SizeConstants), where the
/// paper's sandwiching balls guarantee the bracket [-delta, delta].
constexpr double kDiscFactor = 0.185;

struct Projection {
  Vec3 q;        ///< a + r t, t a unit tangent at a
  Vec3 normal;   ///< outward normal at a
  double delta;  ///< rho - sqrt(rho² - r²) (Figure 9)
  Index cell;    ///< cell of a: the hint
};

void BM_ProjectAlongLine(benchmark::State& state, const char* molecule_file) {
  const skin::SizeConstants size;
  if (!(kDiscFactor > size.disc_factor_lower() && kDiscFactor < size.disc_factor_upper())) {
    state.SkipWithError("kDiscFactor outside the tangent-disc window");
    return;
  }
  const SkinSurface skin(molecule_points(molecule_file));
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  std::vector<Projection> jobs;
  for (const SkinPoint& a : skin_points(skin)) {
    const Vec3 t = a.normal.cross(Vec3(g(rng), g(rng), g(rng)));
    if (t.norm() < 1e-6) continue;
    const double r = kDiscFactor * a.rho;
    jobs.push_back({a.x + r * t.normalized(), a.normal, a.rho - std::sqrt(a.rho * a.rho - r * r), a.cell});
  }
  if (jobs.empty()) {
    state.SkipWithError("no skin points");
    return;
  }
  // Check once: every projection finds its root, on the skin
  // (papers/skin/skin_math.md §7.2).
  const double L = skin.length_scale();
  std::size_t failures = 0;
  for (const Projection& p : jobs) {
    Vec3 out;
    Index cell = p.cell;
    if (!skin.project_along_line(p.q, p.normal, p.delta, out, cell) ||
        skin.distance_estimate(out, cell) > kCheckTolerance * L)
      ++failures;
  }
  if (failures > 0) {
    const std::string msg =
        std::to_string(failures) + " of " + std::to_string(jobs.size()) + " projections failed or missed the skin";
    state.SkipWithError(msg.c_str());
    return;
  }
  for (auto _ : state) {
    for (const Projection& p : jobs) {
      Vec3 out;
      Index cell = p.cell;
      const bool ok = skin.project_along_line(p.q, p.normal, p.delta, out, cell);
      benchmark::DoNotOptimize(ok);
      benchmark::DoNotOptimize(out);
    }
  }
  state.counters["atoms"] = static_cast<double>(skin.points().size());
  state.counters["projections"] = static_cast<double>(jobs.size());
  set_rate(state, "projections_per_s", static_cast<double>(jobs.size()));
}

void BM_MorseSmale(benchmark::State& state, const char* molecule_file) {
  const SkinSurface skin(molecule_points(molecule_file));
  const Vec3 e = morse::default_height_direction();
  {
    // Check once: the Morse count of all critical points, and of the live
    // ones after simplification, equals chi(skin) = 2 chi(K0)
    // (papers/skin/skin_math.md §5).
    const morse::MorseSmaleComplex msc = morse::build_morse_smale_complex(skin, e);
    const int expected = skin::dual_complex_topology(skin.mixed_complex()).euler_skin();
    const morse::MorseCount all = morse::count_critical_points(msc.critical);
    const morse::MorseCount live = msc.live_count();
    if (all.euler() != expected || live.euler() != expected) {
      const std::string msg = "Morse count " + std::to_string(all.euler()) + " (live " + std::to_string(live.euler()) +
                              ") != chi(skin) " + std::to_string(expected);
      state.SkipWithError(msg.c_str());
      return;
    }
    std::size_t failed = 0;
    for (const morse::IntegralLine& line : msc.lines) failed += line.end == kInvalidIndex;
    state.counters["critical"] = static_cast<double>(msc.critical.size());
    state.counters["saddles"] = all.saddles;
    state.counters["lines"] = static_cast<double>(msc.lines.size());
    state.counters["failed_lines"] = static_cast<double>(failed);
    state.counters["cancelled"] = static_cast<double>(msc.cancelled.size());
    state.counters["conflicts"] = static_cast<double>(msc.conflicts.size());
  }
  for (auto _ : state) {
    const morse::MorseSmaleComplex msc = morse::build_morse_smale_complex(skin, e);
    benchmark::DoNotOptimize(msc.lines.data());
  }
  state.counters["atoms"] = static_cast<double>(skin.points().size());
}

}  // namespace

// Registrations ----------------------------------------------------------------

BENCHMARK_CAPTURE(BM_SkinSurface, ligand_1hpv_amprenavir, "ligand_1hpv_amprenavir.pdb")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SkinSurface, gramicidinA_1grm_model1, "gramicidinA_1grm_model1.pdb")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SkinSurface, crambin_1crn, "crambin_1crn.pdb")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SkinSurface, adna_3dna_fiber_30bp, "adna_3dna_fiber_30bp.pdb")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SkinSurface, src_kinase_2src, "src_kinase_2src.pdb")->Unit(benchmark::kMillisecond);

BENCHMARK_CAPTURE(BM_SkinSample, ligand_1hpv_amprenavir, "ligand_1hpv_amprenavir.pdb")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SkinSample, gramicidinA_1grm_model1, "gramicidinA_1grm_model1.pdb")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SkinSample, crambin_1crn, "crambin_1crn.pdb")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SkinSample, adna_3dna_fiber_30bp, "adna_3dna_fiber_30bp.pdb")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SkinSample, src_kinase_2src, "src_kinase_2src.pdb")->Unit(benchmark::kMicrosecond);

BENCHMARK_CAPTURE(BM_ProjectAlongLine, ligand_1hpv_amprenavir, "ligand_1hpv_amprenavir.pdb")
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ProjectAlongLine, gramicidinA_1grm_model1, "gramicidinA_1grm_model1.pdb")
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ProjectAlongLine, crambin_1crn, "crambin_1crn.pdb")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ProjectAlongLine, adna_3dna_fiber_30bp, "adna_3dna_fiber_30bp.pdb")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ProjectAlongLine, src_kinase_2src, "src_kinase_2src.pdb")->Unit(benchmark::kMicrosecond);

BENCHMARK_CAPTURE(BM_MorseSmale, ligand_1hpv_amprenavir, "ligand_1hpv_amprenavir.pdb")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MorseSmale, gramicidinA_1grm_model1, "gramicidinA_1grm_model1.pdb")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MorseSmale, crambin_1crn, "crambin_1crn.pdb")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MorseSmale, adna_3dna_fiber_30bp, "adna_3dna_fiber_30bp.pdb")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MorseSmale, src_kinase_2src, "src_kinase_2src.pdb")->Unit(benchmark::kMillisecond);

}  // namespace skinmesh::bench
