// apps/mesh.cpp: `skinmesh mesh IN -o OUT` — mesh the skin with either
// algorithm (mesher/pipeline.h), verify it, write it and, with --stats, the
// run's summary (mesher/summary.h). Several inputs: batch.cpp.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <unistd.h>

#include "apps/mesh_command.h"
#include "apps/output.h"
#include "mesher/summary.h"
#include "skin/atom_areas.h"
#include "skin/molecule_io.h"
#include "skin/skin_measures.h"
#include "skin/skin_mesh_io.h"

namespace skinmesh::app {

namespace {

/// Peak resident memory of this process (bytes), from /proc/self/status (0 if unknown).
std::size_t peak_memory_bytes() {
  std::ifstream is("/proc/self/status");
  std::string line;
  while (std::getline(is, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024;
  return 0;
}

/// Resident memory of this process now (bytes), from /proc/self/statm (0 if unknown).
std::size_t resident_bytes() {
  std::ifstream is("/proc/self/statm");
  std::size_t pages = 0, resident = 0;
  if (!(is >> pages >> resident)) return 0;
  return resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

/// The peak resident memory of each stage (`--stats` "peak_memory_bytes_per_stage"), sampled: a thread reads
/// the resident size every kSampleMs, and a stage's peak is the largest sample between its start and its end
/// (with the sizes at both ends). The kernel's own high-water mark is left alone (resetting it would make
/// `/usr/bin/time` and other outside tools report the last stage's peak as the process's), so a spike shorter
/// than the period may be missed; the process's peak ("peak_memory_bytes") is the kernel's exact one. A stage
/// that ends twice keeps the larger peak.
class StagePeaks {
 public:
  StagePeaks() : current_max_(resident_bytes()) {
    sampler_ = std::thread([this] {
      std::unique_lock lock(mutex_);
      while (!cv_.wait_for(lock, std::chrono::milliseconds(kSampleMs), [this] { return stop_; }))
        raise(resident_bytes());
    });
  }
  ~StagePeaks() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    cv_.notify_one();
    sampler_.join();
  }
  /// Records the peak of `stage` (ended now) and starts the next stage's.
  void end(const std::string& stage) {
    const std::size_t now = resident_bytes();
    const std::size_t bytes = std::max(current_max_.exchange(now), now);
    auto it = std::find_if(stages_.begin(), stages_.end(), [&](const auto& e) { return e.first == stage; });
    if (it == stages_.end())
      stages_.emplace_back(stage, bytes);
    else
      it->second = std::max(it->second, bytes);
  }
  const std::vector<std::pair<std::string, std::size_t>>& stages() const { return stages_; }

 private:
  static constexpr int kSampleMs = 5;
  void raise(std::size_t bytes) {
    std::size_t seen = current_max_.load();
    while (bytes > seen && !current_max_.compare_exchange_weak(seen, bytes)) {
    }
  }
  std::atomic<std::size_t> current_max_;
  std::vector<std::pair<std::string, std::size_t>> stages_;
  std::mutex mutex_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::thread sampler_;
};

/// --timeout: while armed, ends the process with one line on stderr and exit
/// code 5 once `seconds` have passed. It is disarmed before anything is
/// written, so a timed-out run leaves no file behind.
class Watchdog {
 public:
  /// `after_progress`: progress lines may be on stderr (a new line ends them first).
  Watchdog(double seconds, bool after_progress) {
    if (!(seconds > 0)) return;
    thread_ = std::thread([this, seconds, after_progress] {
      std::unique_lock lock(mutex_);
      if (cv_.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return disarmed_; })) return;
      std::fprintf(stderr, "%serror: timeout: still meshing after the limit of %g s (--timeout); nothing written\n",
                   after_progress ? "\n" : "", seconds);
      std::fflush(stderr);
      std::_Exit(5);
    });
  }
  /// Stops the watchdog (before the output is written).
  void disarm() {
    if (!thread_.joinable()) return;
    {
      std::lock_guard lock(mutex_);
      disarmed_ = true;
    }
    cv_.notify_one();
    thread_.join();
  }
  ~Watchdog() { disarm(); }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  bool disarmed_ = false;
  std::thread thread_;
};

int run_mesh(MeshArgs& a) {
  // Unknown extension or unwritable folder: fail before the work.
  skin::require_mesh_format(a.out);
  if (!a.opt.sweep.dump_path.empty()) geometry::mesh_format_from_extension(a.opt.sweep.dump_path);
  require_writable(a.out);
  if (!a.stats.empty()) require_writable(a.stats);
  if (!a.area_file.empty()) require_writable(a.area_file);
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  Watchdog watchdog(a.timeout, !a.mol.quiet);

  StagePeaks peaks;
  const skin::Molecule mol = load_molecule(a.mol);
  const double read_s = since(start);
  peaks.end("read");
  mesher::MeshOptions options = mesh_options(a);
  options.stored_positions = skin::position_storage(a.out, write_options(a));
  options.skin_atom_areas = !a.area_file.empty();
  if (a.trace) options.sweep.trace = [](const std::string& line) { std::cerr << line << "\n"; };
  ProgressReporter progress(!a.mol.quiet);
  options.progress = [&progress, &peaks](const std::string& stage, double f) {
    progress.report(stage, f);
    if (f == 1.0) peaks.end(stage);  // StageClock::end() reports exactly 1
  };
  const mesher::MeshResult res = mesher::mesh_skin(mol, options);
  watchdog.disarm();
  progress.finish();
  if (!res.static_fallback.empty() && !a.mol.quiet)
    std::cerr << "note: " << res.static_fallback
              << "; the whole skin was meshed by the static restricted Delaunay baseline instead (--no-fallback to "
                 "stop with the error)\n";

  const bool failed = !res.ok();
  if (failed && !a.force) {
    for (const std::string& p : res.problems()) std::cerr << "problem: " << p << "\n";
    if (res.check.ok())
      std::cerr << "error: " << stored_check_error(a.out, res) << "\n";
    else
      std::cerr << "error: the mesh failed its checks; not written (use --force to write it anyway)\n";
    if (!a.stats.empty()) {
      // The check's report; a failed check of the stored positions beside it.
      nlohmann::ordered_json report = nlohmann::ordered_json::parse(res.check.to_json());
      if (res.stored_check) {
        report["ok"] = false;
        report["stored_positions"] = {{"storage", res.stored_as},
                                      {"max_displacement_A", res.stored_displacement},
                                      {"report", nlohmann::ordered_json::parse(res.stored_check->to_json())}};
      }
      write_text_file(a.stats, report.dump(2) + "\n");
    }
    return 3;
  }
  // The exact per-atom areas came with the mesh (stage "atom_areas"): an
  // integration that fails leaves no mesh without its area file.
  AtomAreas areas;
  if (!a.area_file.empty()) {
    areas = atom_areas(mol, res);
    // The exact areas are integrated per patch, and a patch is not split by
    // shell (papers/skin/atom_areas.md): say so where the columns differ.
    if (res.shells && res.shells->removed_bodies + res.shells->removed_cavities > 0 && !a.mol.quiet)
      std::cerr << "note: " << a.area_file
                << ": the exact skin's column counts every shell, the mesh's the kept shells only (--cavities)\n";
  }
  const auto write_start = Clock::now();
  const skin::SkinMeshWriteOptions wopt = write_options(a, &mol);
  skin::write_skin_mesh(a.out, res.mesh, res.vertex_data, wopt);
  if (!a.area_file.empty()) skin::write_area_file(a.area_file, areas.skin, areas.mesh, wopt.msms_atom_names);
  const double write_s = since(write_start);
  peaks.end("write");
  const double total = since(start);
  if (!a.stats.empty()) {
    const std::vector<geometry::WeightedPoint> points = skin::weighted_points(mol, a.mol.probe);
    mesher::SummaryContext context;
    context.input = a.mol.input;
    context.output = a.out;
    context.atoms = mol.atoms.size();
    context.exact_measures_of = &points;
    context.read_seconds = read_s;
    context.write_seconds = write_s;
    context.total_seconds = total;
    // The kernel updates its high-water mark lazily (at unmaps and exits), so a
    // sample may exceed it: the process's peak is at least both.
    context.peak_memory_bytes = peak_memory_bytes();
    for (const auto& [stage, bytes] : peaks.stages())
      context.peak_memory_bytes = std::max(context.peak_memory_bytes, bytes);
    context.stage_peak_memory_bytes = peaks.stages();
    if (!a.area_file.empty()) {
      context.area_file = a.area_file;
      context.skin_atom_areas = &areas.skin;
      context.mesh_atom_areas = &areas.mesh;
    }
    write_text_file(a.stats, mesher::run_summary(res, options, context).dump(2) + "\n");
  }
  if (!a.mol.quiet)
    std::cerr << "wrote " << a.out << ": " << res.mesh.triangles.size() << " triangles"
              << (res.checked ? ", min angle " + std::to_string(res.check.mesh.min_angle_deg) + "°" : std::string())
              << (failed ? " (FAILED its checks, written because of --force)" : "") << ", " << total << " s"
              << shells_note(res) << "\n";
  if (failed)
    for (const std::string& p : res.problems()) std::cerr << "problem: " << p << "\n";
  return failed ? 3 : 0;
}

/// Problems of the command line that CLI11 cannot see: one input and -o, or a
/// batch run (several inputs or --list, and -O); options of one algorithm
/// given with the other. Prints the problem and returns false.
bool usage_is_consistent(CLI::App& cmd, MeshArgs& mesh, bool& batch_run) {
  mesh.threads_given = cmd.count("--threads") > 0;
  batch_run = mesh.mol.inputs.size() > 1 || !mesh.list.empty() || !mesh.out_dir.empty() || mesh.mol.model == "all" ||
              mesh.mol.chains == "each";
  std::string problem;
  if (mesh.mol.inputs.empty() && mesh.list.empty())
    problem = "IN is required (a molecule file, or several with -O DIR)";
  else if (!batch_run && mesh.out.empty())
    problem = "-o OUT is required (or -O DIR for a batch run)";
  else if (batch_run && mesh.out_dir.empty())
    problem = mesh.mol.model == "all" ? "--model all writes one mesh per model: it needs -O DIR, the output folder"
              : mesh.mol.chains == "each"
                  ? "--chains each writes one mesh per chain: it needs -O DIR, the output folder"
                  : "several inputs (or --list) need -O DIR, the output folder";
  else if (batch_run)
    for (const char* name : {"--output", "--stats", "--area-file", "--trace", "--paranoid", "--max-steps",
                             "--dump-partial", "--timeout", "--cuts", "--regions"})
      if (cmd.count(name) > 0) {
        problem = std::string(name) + " applies to one input, not to a batch run (-O)";
        break;
      }
  if (problem.empty() && !mesh.opt.region_files.empty() && mesh.opt.cuts_file.empty())
    problem = "--regions needs --cuts, the cuts file the regions were swept between";
  if (problem.empty() && !batch_run && mesh.area_files)
    problem = "--area-files applies to a batch run (-O DIR); for one input write --area-file FILE";
  if (!problem.empty()) {
    std::cerr << "skinmesh mesh: " << problem << " (see 'skinmesh mesh --help')\n";
    return false;
  }
  if (!batch_run) mesh.mol.input = mesh.mol.inputs.front();
  return options_fit_algorithm(
      cmd, mesh.algorithm == "dynamic",
      {"--trace", "--paranoid", "--max-steps", "--dump-partial", "--direction", "--disc-factor",
       "--no-angle-improvement", "--no-fallback", "--no-patch", "--force-patch-every", "--slabs", "--cut-detours",
       "--detour-fallback", "--no-component-sweeps", "--cuts", "--regions", "--no-growth", "--growth-step"},
      {"--no-growth", "--growth-step"});
}

}  // namespace

AtomAreas atom_areas(const skin::Molecule& mol, const mesher::MeshResult& res) {
  AtomAreas areas;
  areas.skin = res.skin_atom_areas;
  areas.mesh = skin::mesh_atom_areas(res.mesh, res.vertex_data.atom, mol.atoms.size());
  return areas;
}

skin::SkinMeshWriteOptions write_options(const MeshArgs& a, const skin::Molecule* mol) {
  skin::SkinMeshWriteOptions w;
  if (a.msms_atom_names && mol != nullptr)
    for (const skin::Atom& atom : mol->atoms) w.msms_atom_names.push_back(skin::msms_atom_name(atom));
  w.msms_decimals = a.msms_decimals;
  w.msms_header = !a.msms_no_header;
  w.msms_split_components = a.msms_components;
  w.probe_radius = a.mol.probe;
  w.geometry.double_precision = !a.float32;
  w.geometry.off_normals = a.off_normals;
  w.geometry.ascii = a.ascii;
  return w;
}

std::string shells_note(const mesher::MeshResult& res) {
  if (!res.shells) return "";
  const skin::ShellCounts& c = *res.shells;
  char text[160];
  std::snprintf(text, sizeof text, "; kept %zu bodies and %zu cavities, left out %zu and %zu (%.3g Å³ of cavities)",
                c.bodies, c.cavities, c.removed_bodies, c.removed_cavities, c.removed_cavity_volume);
  return text;
}

std::string stored_check_error(const std::string& path, const mesher::MeshResult& res) {
  const std::vector<std::string>& p = res.stored_check->problems;
  char moved[32];
  std::snprintf(moved, sizeof moved, "%.2g", res.stored_displacement);
  std::string text = path + " stores positions as " + res.stored_as + " (up to " + moved +
                     " Å off), which breaks the mesh: " + (p.empty() ? std::string("?") : p.front()) +
                     (p.size() > 1 ? " (and more)" : "") + "; not written (";
  if (skin::is_msms_path(path))
    text += "--msms-decimals 6 or more keeps it, ";
  else
    text += ".ply, or --ascii .stl, without --float keeps positions exact, ";
  return text + "--force writes it anyway)";
}

mesher::MeshOptions mesh_options(const MeshArgs& a) {
  mesher::MeshOptions options = a.opt;
  options.algorithm = mesher::algorithm_named(a.algorithm);
  options.probe_radius = a.mol.probe;
  options.height_direction = height_direction(a.direction);
  options.check = !a.no_check;
  options.improve_angles = !a.no_angle_improvement;
  options.decomposition.components = !a.no_component_sweeps;
  options.dynamic.growth = !a.no_growth;
  options.sweep.patch_fallback = !a.no_fallback && !a.no_patch;
  options.static_fallback = !a.no_fallback;
  options.observers.memory_released = release_free_memory;
  return options;
}

Command add_mesh_command(CLI::App& app) {
  auto args = std::make_shared<MeshArgs>();
  MeshArgs& mesh = *args;
  CLI::App* cmd = app.add_subcommand(
      "mesh",
      "mesh the skin surface (shrink factor 1/2) with the advancing front of Cheng & Shi (2004), verify the "
      "mesh against the analytic skin and write it (.ply binary with normals and atom index, .off, .obj, .stl, "
      ".vtk, .vtp, .vtu, or MSMS .vert/.face)");
  add_molecule_options(*cmd, mesh.mol, /*many=*/true);
  cmd->add_option("-o,--output", mesh.out,
                  "output mesh, format by extension: .ply .off .obj .stl .vtk .vtp .vtu, or .vert (MSMS: NAME.vert and "
                  "NAME.face)");
  const char* batch = "Batch runs (several IN, or --list)";
  cmd->add_option("-O,--output-dir", mesh.out_dir,
                  "output folder of a batch run: DIR/NAME.FORMAT per input, DIR/summary.csv and DIR/summary.json")
      ->group(batch);
  cmd->add_option("--list", mesh.list,
                  "a file of molecule files, one per line ('#' comments; relative to the list's folder)")
      ->group(batch);
  cmd->add_option("--jobs,-j", mesh.jobs, "inputs meshed at the same time (each on one thread unless --threads)")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str()
      ->group(batch);
  cmd->add_option("--out-format", mesh.batch_format, "format of a batch run's meshes")
      ->check(CLI::IsMember({"ply", "off", "obj", "stl", "vtk", "vtp", "vtu", "vert"}))
      ->capture_default_str()
      ->group(batch);
  cmd->add_option("--stats", mesh.stats, "write a JSON summary to this file ('-' for stdout)");
  add_direction_option(*cmd, mesh.direction);
  add_size_options(*cmd, mesh.opt.size);
  cmd->add_option("--disc-factor", mesh.opt.sweep.disc_factor,
                  "tangent-disc radius / rho; must lie in (2C/(Q-2C), 2CQ sqrt((1+CQ)(1+3CQ))/(1+2CQ)^2]")
      ->check(number_at_least_zero(true))
      ->capture_default_str();
  cmd->add_option("--algorithm", mesh.algorithm,
                  "sweep: the advancing front of Cheng & Shi (2004); dynamic: the dynamic-skin baseline "
                  "(Cheng, Dey, Edelsbrunner & Sullivan 2001: restricted Delaunay triangulation of a sample, "
                  "3D Delaunay triangulation, the skin grown from small spheres; papers/dynamic/dynamic_skin.md)")
      ->check(CLI::IsMember({"sweep", "dynamic"}))
      ->capture_default_str();
  cmd->add_flag("--no-growth", mesh.no_growth,
                "with --algorithm dynamic: sample and refine the final skin directly (the static variant)");
  cmd->add_option("--growth-step", mesh.opt.dynamic.max_step_motion,
                  "with --algorithm dynamic: largest motion of a sample per growth step, as a fraction of "
                  "its local length scale rho (the growth schedule)")
      ->check(CLI::Range(1e-3, 1.0))
      ->capture_default_str();
  cmd->add_flag("--no-angle-improvement", mesh.no_angle_improvement,
                "skip the vertex moves that raise the smallest angles after the refinement (the mesh of "
                "the paper's algorithm alone; papers/refine/angle_improvement.md)");
  add_threads_option(*cmd, mesh.opt.threads, "0: every core", "mesh is, byte for byte,");
  cmd->add_option("--slabs", mesh.opt.decomposition.slabs,
                  "cut the skin at N - 1 heights and sweep the slabs on the threads, glued along the cut curves' "
                  "shared samples (papers/decompose/README.md); fewer slabs where no admissible cut height "
                  "exists; 1: one sweep; 0 (default): for the atoms of the largest group of components, if it holds "
                  "most of the skin, one slab per 2500 atoms up to 7,812 atoms and sqrt(atoms / 800) above (17 "
                  "for 218,760 atoms), else one sweep (the mesh depends on N, never on --threads)")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  cmd->add_flag("--cut-detours", mesh.opt.decomposition.detours,
                "every cut passes around the critical points it meets instead of being a level cut clear of them "
                "(experimental; papers/decompose/README.md, \"Detoured cuts\")");
  cmd->add_flag("--detour-fallback,!--no-detour-fallback", mesh.opt.decomposition.detour_fallback,
                "level cuts where the skin admits them, detoured cuts where it does not (the default; "
                "--no-detour-fallback: a target without an admissible level cut is skipped, and a large body "
                "is one sweep)");
  const char* regions = "One structure over several processes (skinmesh cuts, skinmesh region)";
  cmd->add_option("--cuts", mesh.opt.cuts_file,
                  "take the cuts from this file of `skinmesh cuts` (the same input and options) instead of "
                  "choosing them; the mesh is the one this command makes without it")
      ->group(regions);
  cmd->add_option("--regions", mesh.opt.region_files,
                  "with --cuts: the region files of `skinmesh region`, glued instead of being swept again (a "
                  "region without a file is swept here)")
      ->group(regions);
  cmd->add_flag(
      "--no-component-sweeps", mesh.no_component_sweeps,
      "sweep every skin component in one front, with no slab unless --slabs asks (default: each group of whole "
      "components is swept on its own, on the threads, and the meshes appended; "
      "papers/decompose/README.md, \"Groups of whole components\")");
  cmd->add_option("--timeout", mesh.timeout,
                  "stop with exit code 5 and a one-line message if reading and meshing one input take longer than "
                  "this many seconds (nothing is written; 0: no limit)")
      ->check(CLI::Range(0.0, 1e9))
      ->capture_default_str();
  add_shell_options(*cmd, mesh.opt.shells, "write (the check verifies every shell first)");
  cmd->add_option("--msms-decimals", mesh.msms_decimals,
                  "digits after the point of MSMS .vert positions (MSMS writes 3; small cavities and thin necks "
                  "may need more: the mesh is checked as the file stores it)")
      ->check(CLI::Range(skin::kMinMsmsDecimals, skin::kMaxMsmsDecimals))
      ->capture_default_str();
  cmd->add_flag("--msms-atom-names", mesh.msms_atom_names,
                "add each vertex's atom name to its MSMS .vert record as a 10th field, "
                "chain_resnum_icode_resname_atomname (MaSIF's reader needs it; Biopython's reads 9 fields only)");
  cmd->add_flag("--msms-no-header", mesh.msms_no_header,
                "MSMS .vert/.face without their three header lines (MSMS's -no_header); skinmesh check reads both");
  cmd->add_flag("--msms-components", mesh.msms_components,
                "one MSMS .vert/.face pair per surface component, as MSMS's -all_components: the first NAME.vert, "
                "the k-th NAME_{k-1}.vert, each numbering its own vertices");
  cmd->add_flag("--area-files", mesh.area_files,
                "in a batch run (-O DIR): each input's per-atom areas as DIR/NAME.area beside its mesh (the layout "
                "of --area-file), and summary.csv's skin_area_A2, their sum")
      ->group(batch);
  cmd->add_option(
      "--area-file", mesh.area_file,
      "also write each atom's area to this file in MSMS's .area layout: a header line, then per atom "
      "its 1-based number, the exact skin's area and the mesh's (Å²), and with --msms-atom-names its "
      "name (papers/skin/atom_areas.md; costs about 1.6 times --stats' exact area: 1.5 s for maltoporin on 2 "
      "threads). With --cavities remove or only, the exact column still counts every shell");
  cmd->add_flag("--float", mesh.float32,
                "float32 positions and normals in .ply, .off, .obj, .vtk, .vtp and .vtu (half the size); the mesh is "
                "checked as the file stores it (default: exact doubles)");
  cmd->add_flag("--ascii", mesh.ascii,
                "write .ply and .stl as text (TetGen reads only text PLY and STL, gmsh 4.8 only text PLY; ASCII STL "
                "keeps positions exact, "
                "binary STL rounds them to float32)");
  cmd->add_flag("--off-normals", mesh.off_normals,
                "write .off as NOFF, with each vertex's normal (default: plain OFF, which every OFF reader takes)");
  cmd->add_flag("--no-check", mesh.no_check,
                "do not verify the mesh before writing it (nor the positions as a lossy format stores them)");
  cmd->add_flag("--force", mesh.force, "write the mesh even if it fails its checks (the report says what failed)");
  const char* debug = "Debugging the sweep (papers/front/sweep.md)";
  cmd->add_flag("--paranoid", mesh.opt.sweep.paranoid, "check for folds after every operation of the sweep")
      ->group(debug);
  cmd->add_flag("--trace", mesh.trace, "print every decision of the sweep on stderr")->group(debug);
  cmd->add_flag("--no-fallback", mesh.no_fallback,
                "stop with an error where the front tangles or folds instead of re-meshing the region by "
                "restricted Delaunay or leaving it for the seal (papers/front/patch.md), and where the sweep fails "
                "instead of meshing the whole skin with the static baseline (papers/mesher/pipeline.md)")
      ->group(debug);
  cmd->add_flag("--no-patch", mesh.no_patch,
                "testing aid: where the front tangles, no local patch; the whole skin is meshed by the static "
                "baseline where the sweep then fails (papers/mesher/pipeline.md)")
      ->group(debug);
  cmd->add_option("--force-patch-every", mesh.opt.sweep.force_patch_every,
                  "testing aid: re-mesh every N-th hole of the seal by the fallback's patch (papers/front/patch.md)")
      ->group(debug);
  cmd->add_option("--max-steps", mesh.opt.sweep.max_steps, "stop the sweep after N departures")
      ->check(number_at_least_zero(false))
      ->group(debug);
  cmd->add_option("--dump-partial", mesh.opt.sweep.dump_path,
                  "write the partial mesh to this file (.ply, .off, .obj, .stl or .vtk) before the seal or when "
                  "stopped")
      ->group(debug);
  return {cmd, [args, cmd] {
            bool batch_run = false;
            if (!usage_is_consistent(*cmd, *args, batch_run)) return 2;
            return batch_run ? run_batch(*args) : run_mesh(*args);
          }};
}

}  // namespace skinmesh::app
