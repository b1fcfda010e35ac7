// bench/table1/table1_main.cpp: `make table1` — Cheng & Shi 2004, Table 1,
// reproduced: for each molecule (the three stand-ins of data/README.md, then
// crambin, HIV protease, maltoporin, and the paper's Figure 4 configuration of
// 8 weighted points at the corners of a cube) and each input convention, the
// atoms, triangles, minimum angle and seconds of the sweep, of the dynamic-skin
// baseline (growth) and of its static variant, the baseline/sweep ratio, and
// the paper's row with its ratio. Google Benchmark times every run (one
// thread; the sweep for at least --benchmark_min_time, the baselines once);
// every mesh is verified once, outside the timed loop, by
// verify::check_skin_mesh, and a failing check is printed in the table.
// Notes: papers/bench/table1.md
//
// Usage: skinmesh_table1 [--dynamic-max-atoms N] [--static-max-atoms N]
//                        [--quick] [Google Benchmark flags]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "dynamic/dynamic_skin.h"
#include "mesher/pipeline.h"
#include "skin/molecule_io.h"
#include "skin/skin_surface.h"
#include "verify/skin_mesh_check.h"

namespace {

using namespace skinmesh;

/// A row of the table: an input and, for the paper's molecules, its row.
struct Case {
  const char* name;   ///< row label
  const char* path;   ///< file under SKINMESH_DATA or SKINMESH_TEST_DATA
  bool test_data;     ///< true: SKINMESH_TEST_DATA
  const char* paper;  ///< the paper's molecule ("" if none)
  double paper_triangles, paper_angle, paper_sweep_s, paper_dynamic_s;
};

const Case kCases[] = {
    {"figure4_cube_corners", "cube_corners.xyzr", true, "", 0, 0, 0, 0},
    {"ligand_1hpv_amprenavir", "ligand_1hpv_amprenavir.pdb", false, "pdb7tmn", 24336, 27.02, 5, 600},
    {"adna_3dna_fiber_30bp", "adna_3dna_fiber_30bp.pdb", false, "A-DNA", 114316, 24.12, 51, 2112},
    {"gramicidinA_1grm_model1", "gramicidinA_1grm_model1.pdb", false, "Gramicidin A", 305186, 24.37, 202, 5723},
    {"crambin_1crn", "crambin_1crn.pdb", false, "", 0, 0, 0, 0},
    {"hivprotease_xk263_1hvr", "hivprotease_xk263_1hvr.pdb", false, "", 0, 0, 0, 0},
    {"maltoporin_1af6", "maltoporin_1af6.pdb", false, "", 0, 0, 0, 0},
};

/// An input convention: atom weight w = 2 (r + probe)², Bondi radii.
struct Convention {
  const char* name;
  double probe;
  const char* why;
};

/// Probe 0 first: it reproduces the paper's triangle counts
/// (papers/bench/input_convention.md); probe 1.4 is the paper's stated one.
const Convention kConventions[] = {
    {"probe0", 0.0, "the convention that reproduces the paper's counts, papers/bench/input_convention.md"},
    {"probe1.4", 1.4, "the paper's stated weights"}};

enum class Algorithm { Sweep, Dynamic, Static };
const char* name_of(Algorithm a) {
  return a == Algorithm::Sweep ? "sweep" : a == Algorithm::Dynamic ? "dynamic" : "static";
}

/// What one (case, convention, algorithm) measured.
struct Result {
  bool ran = false, ok = false;
  std::string problem;
  std::size_t atoms = 0, triangles = 0;
  double min_angle = 0, seconds = 0;
};

std::map<std::string, Result> g_results;
std::map<std::string, std::vector<geometry::WeightedPoint>> g_points;

std::string key(const Case& c, const Convention& v, Algorithm a) {
  return std::string(c.name) + "/" + v.name + "/" + name_of(a);
}

const std::vector<geometry::WeightedPoint>& points_of(const Case& c, const Convention& v) {
  const std::string k = std::string(c.name) + "/" + v.name;
  auto it = g_points.find(k);
  if (it != g_points.end()) return it->second;
  const std::string dir = c.test_data ? SKINMESH_TEST_DATA : SKINMESH_DATA;
  return g_points[k] = skin::weighted_points(skin::read_molecule(dir + "/" + c.path), v.probe);
}

/// The mesh of `points` by algorithm `a` (no check), and its frame centre.
geometry::IndexedMesh run(Algorithm a, const std::vector<geometry::WeightedPoint>& points) {
  mesher::MeshOptions o;
  o.check = false;
  if (a != Algorithm::Sweep) {
    o.algorithm = mesher::Algorithm::Dynamic;
    o.dynamic.growth = a == Algorithm::Dynamic;
  }
  return mesher::mesh_skin(points, o).mesh;
}

void bm_case(benchmark::State& state, const Case* c, const Convention* v, Algorithm a) {
  const auto& points = points_of(*c, *v);
  Result& r = g_results[key(*c, *v, a)];
  r.ran = true;
  r.atoms = points.size();
  double total = 0;
  std::size_t n = 0;
  geometry::IndexedMesh mesh;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    mesh = run(a, points);
    total += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ++n;
    benchmark::DoNotOptimize(mesh.triangles.data());
  }
  r.seconds = n ? total / n : 0;
  // Verify the last mesh (in the local frame, as the command line does),
  // after the timed loop.
  const Vec3 centre = skin::local_frame_centre(points);
  const skin::SkinSurface skin(skin::translated(points, centre));
  for (Vec3& p : mesh.positions) p -= centre;
  const verify::SkinCheckReport rep = verify::check_skin_mesh(skin, mesh);
  r.ok = rep.ok();
  if (!r.ok) r.problem = rep.problems.front();
  r.triangles = mesh.triangles.size();
  r.min_angle = rep.mesh.min_angle_deg;
  state.counters["atoms"] = static_cast<double>(r.atoms);
  state.counters["triangles"] = static_cast<double>(r.triangles);
  state.counters["min_angle_deg"] = r.min_angle;
  state.counters["checks_passed"] = r.ok ? 1 : 0;
}

std::string clock(double s) {
  if (s <= 0) return "";
  const long t = std::lround(s);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
  return buf;
}

std::string thousands(std::size_t n) {
  const std::string digits = std::to_string(n);
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string cell(const Result& r, bool with_seconds = true) {
  if (!r.ran) return "— | — |" + std::string(with_seconds ? " — |" : "");
  char buf[128];
  std::snprintf(buf, sizeof buf, "%s | %.1f°%s |", thousands(r.triangles).c_str(), r.min_angle, r.ok ? "" : " FAILED");
  std::string out = buf;
  if (with_seconds) {
    // Three significant digits, but whole seconds from 1,000 s on (no exponent).
    if (r.seconds >= 999.5) {
      out += ' ';
      out += thousands(static_cast<std::size_t>(std::llround(r.seconds)));
      out += " |";
    } else {
      std::snprintf(buf, sizeof buf, " %.3g |", r.seconds);
      out += buf;
    }
  }
  return out;
}

void print_table() {
  std::printf(
      "\n## Table 1 reproduced (seconds: one thread, whole pipeline from weighted points to the mesh, "
      "check excluded; every mesh verified by skinmesh check)\n\n");
  for (const Convention& v : kConventions) {
    std::printf("### w = 2 (r + %.1f)², Bondi radii, hydrogens as in the file (%s: %s)\n\n", v.probe, v.name, v.why);
    std::printf(
        "| molecule | atoms | sweep: triangles | min angle | s | dynamic: triangles | min angle | s | "
        "static: triangles | min angle | s | dynamic / sweep | static / sweep | paper: molecule | "
        "triangles | min angle | sweep | dynamic skin | ratio |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const Case& c : kCases) {
      const Result& s = g_results[key(c, v, Algorithm::Sweep)];
      const Result& d = g_results[key(c, v, Algorithm::Dynamic)];
      const Result& t = g_results[key(c, v, Algorithm::Static)];
      if (!s.ran && !d.ran && !t.ran) continue;
      char ratio_d[32] = "—", ratio_s[32] = "—", paper_ratio[32] = "";
      if (s.ran && d.ran && s.seconds > 0) std::snprintf(ratio_d, sizeof ratio_d, "%.0f×", d.seconds / s.seconds);
      if (s.ran && t.ran && s.seconds > 0) std::snprintf(ratio_s, sizeof ratio_s, "%.1f×", t.seconds / s.seconds);
      if (c.paper_sweep_s > 0)
        std::snprintf(paper_ratio, sizeof paper_ratio, "%.0f×", c.paper_dynamic_s / c.paper_sweep_s);
      const std::size_t atoms = s.ran ? s.atoms : d.ran ? d.atoms : t.atoms;
      std::printf("| %s | %s | %s %s %s %s | %s | %s |", c.name, thousands(atoms).c_str(), cell(s).c_str(),
                  cell(d).c_str(), cell(t).c_str(), ratio_d, ratio_s, *c.paper ? c.paper : "—");
      if (*c.paper)
        std::printf(" %s | %.2f° | %s | %s | %s |\n", thousands(static_cast<std::size_t>(c.paper_triangles)).c_str(),
                    c.paper_angle, clock(c.paper_sweep_s).c_str(), clock(c.paper_dynamic_s).c_str(), paper_ratio);
      else
        std::printf(" | | | | |\n");
    }
    std::printf("\n");
  }
  for (const auto& [k, r] : g_results)
    if (r.ran && !r.ok) std::printf("check failed: %s: %s\n", k.c_str(), r.problem.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t dynamic_max_atoms = 1300, static_max_atoms = 5000;
  bool quick = false;
  std::vector<char*> rest = {argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--dynamic-max-atoms") && i + 1 < argc) {
      dynamic_max_atoms = std::strtoul(argv[++i], nullptr, 10);
    } else if (!std::strcmp(argv[i], "--static-max-atoms") && i + 1 < argc) {
      static_max_atoms = std::strtoul(argv[++i], nullptr, 10);
    } else if (!std::strcmp(argv[i], "--quick")) {
      quick = true;
    } else if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) {
      std::printf(
          "skinmesh_table1: Cheng & Shi 2004 Table 1 reproduced (sweep, dynamic-skin baseline, static variant)\n"
          "  --dynamic-max-atoms N  run the growing baseline only on inputs of at most N atoms (default 1300)\n"
          "  --static-max-atoms N   run the static variant only on inputs of at most N atoms (default 5000)\n"
          "  --quick                only the inputs of at most 400 atoms, the sweep timed once\n"
          "  Google Benchmark flags (e.g. --benchmark_filter=gramicidin) select and time the runs.\n");
      return 0;
    } else {
      rest.push_back(argv[i]);
    }
  }
  for (const Case& c : kCases) {
    for (const Convention& v : kConventions) {
      const std::size_t atoms = points_of(c, v).size();
      if (quick && atoms > 400) continue;
      for (const Algorithm a : {Algorithm::Sweep, Algorithm::Dynamic, Algorithm::Static}) {
        if (a == Algorithm::Dynamic && atoms > dynamic_max_atoms) continue;
        if (a == Algorithm::Static && atoms > static_max_atoms) continue;
        auto* b = benchmark::RegisterBenchmark(key(c, v, a).c_str(), bm_case, &c, &v, a);
        b->Unit(benchmark::kSecond)->UseRealTime();
        if (a != Algorithm::Sweep || quick)
          b->Iterations(1);
        else
          b->MinTime(2.0);
      }
    }
  }
  int n = static_cast<int>(rest.size());
  benchmark::Initialize(&n, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_table();
  return 0;
}
