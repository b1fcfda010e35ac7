// bench/geometry_bench.cpp: benchmarks of geometry/: the orientation and power
// predicates (plain double, filtered, exact, SoS) and the regular triangulation
// on random points, the bundled molecules and a degenerate lattice.
// papers/conventions.md §3 "Benchmarks"; geometry/kernel/predicates.h,
// geometry/triangulation/regular_triangulation.h.
//
// Predicate benchmarks evaluate one predicate per iteration, cycling through a
// batch of precomputed tuples, and report which fraction of the calls needed
// the exact layer (and SoS) from predicate_stats(). Before the loop every
// robust variant is compared once with the exact evaluation, and the plain
// double version's sign errors are counted (`fast_sign_errors`, a fraction).
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_common.h"
#include "geometry/kernel/predicates.h"
#include "geometry/triangulation/regular_triangulation.h"
#include "skin/skin_surface.h"

namespace skinmesh::bench {
namespace {

using geometry::PredicateCounters;
using geometry::RegularTriangulation;
using geometry::WeightedPoint;

// Predicate Inputs -------------------------------------------------------------

/// Tuples per predicate batch (a power of two: the loop cycles with a mask).
/// 1024 tuples of 5 weighted points are 160 KB, a cache-resident working set.
constexpr std::size_t kBatch = 1024;

/// Which layer of a predicate is timed.
enum class Layer {
  Fast,      ///< orient3d_fast / power_test_fast: plain double, not robust
  Filtered,  ///< orient3d / power_test: filter, exact expansion if uncertain
  Exact,     ///< orient3d_exact / power_test_exact: always the expansions
  Sos,       ///< power_test_sos: filter, exact, then Simulation of Simplicity
};

/// Which inputs the predicate sees.
enum class Input {
  Random,          ///< independent uniform points: the filter almost always decides
  NearDegenerate,  ///< rounded coplanar (orient3d) or cospherical (power test) points
  Cospherical,     ///< exactly cospherical integer points: the exact value is 0
};

std::mt19937_64 make_rng(std::uint64_t salt) { return std::mt19937_64(0x5EED2004ULL + salt); }

Vec3 random_point(std::mt19937_64& rng, double side) {
  std::uniform_real_distribution<double> u(0.0, side);
  return Vec3(u(rng), u(rng), u(rng));
}

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  for (;;) {
    const Vec3 v(g(rng), g(rng), g(rng));
    if (v.norm() > 1e-3) return v.normalized();
  }
}

/// Orient3d tuples in a 10 Å cube. NearDegenerate: d = a + s (b - a) + t (c - a)
/// rounded to double, so abcd is coplanar up to rounding.
std::vector<std::array<Vec3, 4>> orient_inputs(Input input) {
  auto rng = make_rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::array<Vec3, 4>> tuples(kBatch);
  for (auto& q : tuples) {
    for (Vec3& p : q) p = random_point(rng, 10.0);
    if (input == Input::NearDegenerate) q[3] = q[0] + u(rng) * (q[1] - q[0]) + u(rng) * (q[2] - q[0]);
  }
  return tuples;
}

/// Five weighted points a, b, c, d, e with orient3d(a, b, c, d) Positive, and
/// their SoS indices.
struct PowerTuple {
  std::array<WeightedPoint, 5> p;
  std::array<Index, 5> id;
};

/// The 30 integer points at distance exactly 3 from the origin: the
/// permutations of (±3, 0, 0) and (±1, ±2, ±2).
std::vector<Vec3> integer_sphere_points() {
  std::vector<Vec3> s;
  for (int x = -3; x <= 3; ++x)
    for (int y = -3; y <= 3; ++y)
      for (int z = -3; z <= 3; ++z)
        if (x * x + y * y + z * z == 9) s.emplace_back(x, y, z);
  return s;
}

/// Power-test tuples. Random: uniform centres in a 10 Å cube, weights in
/// [0, 4) Å². NearDegenerate: five points on a random sphere (radius 1-3 Å)
/// rounded to double, equal weights. Cospherical: five of the integer points
/// of integer_sphere_points() shifted by an integer vector, equal weights, so
/// e lies exactly on the orthosphere of abcd.
std::vector<PowerTuple> power_inputs(Input input) {
  auto rng = make_rng(2);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const std::vector<Vec3> sphere = integer_sphere_points();
  std::uniform_int_distribution<std::size_t> pick(0, sphere.size() - 1);
  std::uniform_int_distribution<int> shift(-50, 50);
  const double equal_weight = skin::atom_weight(1.7, kProbeRadius);
  std::vector<PowerTuple> tuples;
  while (tuples.size() < kBatch) {
    PowerTuple t;
    const Index base = static_cast<Index>(5 * tuples.size());
    if (input == Input::Random) {
      for (int i = 0; i < 5; ++i) t.p[i] = {random_point(rng, 10.0), 4.0 * u(rng)};
      for (int i = 0; i < 5; ++i) t.id[i] = base + i;
    } else if (input == Input::NearDegenerate) {
      const Vec3 centre = random_point(rng, 10.0);
      const double radius = 1.0 + 2.0 * u(rng);
      for (int i = 0; i < 5; ++i) t.p[i] = {centre + radius * random_unit(rng), equal_weight};
      for (int i = 0; i < 5; ++i) t.id[i] = base + i;
    } else {
      const Vec3 offset(shift(rng), shift(rng), shift(rng));
      std::array<std::size_t, 5> k;
      for (int i = 0; i < 5; ++i) {
        bool fresh = false;
        while (!fresh) {
          k[i] = pick(rng);
          fresh = true;
          for (int j = 0; j < i; ++j) fresh = fresh && k[j] != k[i];
        }
        t.p[i] = {sphere[k[i]] + offset, equal_weight};
        t.id[i] = static_cast<Index>(k[i]);  // the same point keeps its index
      }
    }
    const Sign o = geometry::orient3d(t.p[0].z, t.p[1].z, t.p[2].z, t.p[3].z);
    if (o == Sign::Zero) continue;  // the power test needs a proper tetrahedron
    if (o == Sign::Negative) {
      std::swap(t.p[0], t.p[1]);
      std::swap(t.id[0], t.id[1]);
    }
    tuples.push_back(t);
  }
  return tuples;
}

void set_layer_fractions(benchmark::State& state, const PredicateCounters& c, bool sos) {
  if (c.calls == 0) return;
  state.counters["exact_fraction"] = static_cast<double>(c.exact) / static_cast<double>(c.calls);
  if (sos) state.counters["sos_fraction"] = static_cast<double>(c.sos) / static_cast<double>(c.calls);
}

// Predicate Benchmarks ---------------------------------------------------------

void BM_Orient3d(benchmark::State& state, Layer layer, Input input) {
  const auto tuples = orient_inputs(input);
  // Check once: the robust variants agree with the exact sign; count the
  // plain double version's wrong signs.
  std::size_t fast_errors = 0;
  for (const auto& q : tuples) {
    const Sign exact = geometry::orient3d_exact(q[0], q[1], q[2], q[3]);
    if (geometry::orient3d(q[0], q[1], q[2], q[3]) != exact) {
      state.SkipWithError("orient3d disagrees with orient3d_exact");
      return;
    }
    if (sign_of(geometry::orient3d_fast(q[0], q[1], q[2], q[3])) != exact) ++fast_errors;
  }
  geometry::reset_predicate_stats();
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& q = tuples[i++ & (kBatch - 1)];
    if (layer == Layer::Fast) {
      benchmark::DoNotOptimize(geometry::orient3d_fast(q[0], q[1], q[2], q[3]));
    } else if (layer == Layer::Exact) {
      benchmark::DoNotOptimize(geometry::orient3d_exact(q[0], q[1], q[2], q[3]));
    } else {
      benchmark::DoNotOptimize(geometry::orient3d(q[0], q[1], q[2], q[3]));
    }
  }
  if (layer == Layer::Filtered) set_layer_fractions(state, geometry::predicate_stats().orient3d, false);
  if (layer == Layer::Fast)
    state.counters["fast_sign_errors"] = static_cast<double>(fast_errors) / static_cast<double>(kBatch);
  state.SetItemsProcessed(state.iterations());
}

void BM_PowerTest(benchmark::State& state, Layer layer, Input input) {
  const auto tuples = power_inputs(input);
  std::size_t fast_errors = 0;
  for (const PowerTuple& t : tuples) {
    const auto& p = t.p;
    const Sign exact = geometry::power_test_exact(p[0], p[1], p[2], p[3], p[4]);
    if (geometry::power_test(p[0], p[1], p[2], p[3], p[4]) != exact) {
      state.SkipWithError("power_test disagrees with power_test_exact");
      return;
    }
    const Sign sos =
        geometry::power_test_sos(p[0], p[1], p[2], p[3], p[4], t.id[0], t.id[1], t.id[2], t.id[3], t.id[4]);
    if (sos == Sign::Zero || (exact != Sign::Zero && sos != exact)) {
      state.SkipWithError("power_test_sos is zero or disagrees with a non-zero exact sign");
      return;
    }
    if (sign_of(geometry::power_test_fast(p[0], p[1], p[2], p[3], p[4])) != exact) ++fast_errors;
  }
  geometry::reset_predicate_stats();
  std::size_t i = 0;
  for (auto _ : state) {
    const PowerTuple& t = tuples[i++ & (kBatch - 1)];
    const auto& p = t.p;
    switch (layer) {
      case Layer::Fast:
        benchmark::DoNotOptimize(geometry::power_test_fast(p[0], p[1], p[2], p[3], p[4]));
        break;
      case Layer::Filtered:
        benchmark::DoNotOptimize(geometry::power_test(p[0], p[1], p[2], p[3], p[4]));
        break;
      case Layer::Exact:
        benchmark::DoNotOptimize(geometry::power_test_exact(p[0], p[1], p[2], p[3], p[4]));
        break;
      case Layer::Sos:
        benchmark::DoNotOptimize(
            geometry::power_test_sos(p[0], p[1], p[2], p[3], p[4], t.id[0], t.id[1], t.id[2], t.id[3], t.id[4]));
        break;
    }
  }
  if (layer == Layer::Filtered || layer == Layer::Sos)
    set_layer_fractions(state, geometry::predicate_stats().power_test, layer == Layer::Sos);
  if (layer == Layer::Fast)
    state.counters["fast_sign_errors"] = static_cast<double>(fast_errors) / static_cast<double>(kBatch);
  state.SetItemsProcessed(state.iterations());
}

// Regular Triangulation Benchmarks ---------------------------------------------

/// Builds the triangulation of `points` once and checks it, then times the
/// construction (including the destruction of the previous one).
void run_triangulation(benchmark::State& state, const std::vector<WeightedPoint>& points) {
  {
    const RegularTriangulation rt(points);
    const std::string problem = check_triangulation(rt);
    if (!problem.empty()) {
      state.SkipWithError(problem.c_str());
      return;
    }
    state.counters["tets"] = rt.num_tets();
    state.counters["redundant"] = static_cast<double>(rt.redundant_points().size());
    state.counters["walk_fallbacks"] = static_cast<double>(rt.build_stats().walk_fallbacks);
  }
  geometry::reset_predicate_stats();
  for (auto _ : state) {
    const RegularTriangulation rt(points);
    benchmark::DoNotOptimize(rt.num_tets());
  }
  const PredicateCounters c = geometry::predicate_stats().power_test;
  if (c.calls > 0) {
    state.counters["power_exact_fraction"] = static_cast<double>(c.exact) / static_cast<double>(c.calls);
    state.counters["power_sos_fraction"] = static_cast<double>(c.sos) / static_cast<double>(c.calls);
  }
  state.counters["points"] = static_cast<double>(points.size());
  set_rate(state, "points_per_s", static_cast<double>(points.size()));
}

/// n random weighted points shaped like heavy atoms: centres uniform in a cube
/// at about a protein's heavy-atom density, radii uniform in the range of the
/// Bondi radii of C, N, O, S (1.5-1.9 Å), weights atom_weight(r, 1.4).
struct RandomAtoms {
  std::size_t n;
};

/// An n x n x n lattice with spacing 3 Å and equal weights: every unit cube has
/// 8 cospherical points, so every decision between its tetrahedra is SoS.
struct EqualWeightLattice {
  int n;
};

void BM_RegularTriangulation(benchmark::State& state, RandomAtoms cloud) {
  constexpr double kDensity = 0.05;  // atoms per Å³, about a protein's heavy atoms
  const double side = std::cbrt(static_cast<double>(cloud.n) / kDensity);
  auto rng = make_rng(3);
  std::uniform_real_distribution<double> radius(1.5, 1.9);
  std::vector<WeightedPoint> points(cloud.n);
  for (WeightedPoint& b : points) b = {random_point(rng, side), skin::atom_weight(radius(rng), kProbeRadius)};
  run_triangulation(state, points);
}

void BM_RegularTriangulation(benchmark::State& state, EqualWeightLattice lattice) {
  const double w = skin::atom_weight(1.7, kProbeRadius);
  std::vector<WeightedPoint> points;
  for (int x = 0; x < lattice.n; ++x)
    for (int y = 0; y < lattice.n; ++y)
      for (int z = 0; z < lattice.n; ++z) points.push_back({3.0 * Vec3(x, y, z), w});
  run_triangulation(state, points);
}

void BM_RegularTriangulation(benchmark::State& state, const char* molecule_file) {
  const auto points = molecule_points(molecule_file);
  state.counters["atoms"] = static_cast<double>(points.size());
  run_triangulation(state, points);
}

}  // namespace

// Registrations ----------------------------------------------------------------

BENCHMARK_CAPTURE(BM_Orient3d, fast_random, Layer::Fast, Input::Random);
BENCHMARK_CAPTURE(BM_Orient3d, filtered_random, Layer::Filtered, Input::Random);
BENCHMARK_CAPTURE(BM_Orient3d, exact_random, Layer::Exact, Input::Random);
BENCHMARK_CAPTURE(BM_Orient3d, fast_near_coplanar, Layer::Fast, Input::NearDegenerate);
BENCHMARK_CAPTURE(BM_Orient3d, filtered_near_coplanar, Layer::Filtered, Input::NearDegenerate);

BENCHMARK_CAPTURE(BM_PowerTest, fast_random, Layer::Fast, Input::Random);
BENCHMARK_CAPTURE(BM_PowerTest, filtered_random, Layer::Filtered, Input::Random);
BENCHMARK_CAPTURE(BM_PowerTest, exact_random, Layer::Exact, Input::Random);
BENCHMARK_CAPTURE(BM_PowerTest, sos_random, Layer::Sos, Input::Random);
BENCHMARK_CAPTURE(BM_PowerTest, fast_near_cospherical, Layer::Fast, Input::NearDegenerate);
BENCHMARK_CAPTURE(BM_PowerTest, filtered_near_cospherical, Layer::Filtered, Input::NearDegenerate);
BENCHMARK_CAPTURE(BM_PowerTest, sos_near_cospherical, Layer::Sos, Input::NearDegenerate);
BENCHMARK_CAPTURE(BM_PowerTest, sos_cospherical, Layer::Sos, Input::Cospherical);

BENCHMARK_CAPTURE(BM_RegularTriangulation, random_10k, RandomAtoms{10'000})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RegularTriangulation, random_100k, RandomAtoms{100'000})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RegularTriangulation, lattice_20x20x20, EqualWeightLattice{20})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RegularTriangulation, ligand_1hpv_amprenavir, "ligand_1hpv_amprenavir.pdb")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RegularTriangulation, gramicidinA_1grm_model1, "gramicidinA_1grm_model1.pdb")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RegularTriangulation, crambin_1crn, "crambin_1crn.pdb")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RegularTriangulation, adna_3dna_fiber_30bp, "adna_3dna_fiber_30bp.pdb")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RegularTriangulation, src_kinase_2src, "src_kinase_2src.pdb")->Unit(benchmark::kMillisecond);

}  // namespace skinmesh::bench
