// apps/trace.cpp: `skinmesh trace IN -o trace.html|json` — the algorithm
// recorded step by step (trace/trace_recorder.h) as one self-contained page
// of the trace viewer or as its data alone.
#include <unistd.h>  // readlink

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>

#include "apps/cli.h"
#include "apps/output.h"
#include "core/errors.h"
#include "core/read_file.h"
#include "skin/molecule_io.h"
#include "trace/trace_recorder.h"

namespace skinmesh::app {

namespace {

struct TraceArgs {
  MoleculeArgs mol;
  std::string out, viewer;
  std::vector<double> direction;
  /// "sweep" (Cheng & Shi 2004) or "dynamic" (the dynamic-skin baseline).
  std::string algorithm = "sweep";
  trace::TraceOptions opt;
  bool no_check = false, no_angle_improvement = false, no_growth = false;
};

/// The folder of this executable ("" if unknown).
std::string executable_folder() {
  char buf[4096];
  const ssize_t n = ::readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return {};
  return std::filesystem::path(std::string(buf, static_cast<std::size_t>(n))).parent_path().string();
}

/// The viewer template: --viewer, else $SKINMESH_VIEWER, else
/// trace_viewer.html beside the executable (the build tree) or in
/// ../share/skinmesh/ (an installation). Throws InputError if none is found.
std::string find_viewer(const std::string& given) {
  if (!given.empty()) return given;
  if (const char* env = std::getenv("SKINMESH_VIEWER"); env && *env) return env;
  const std::string dir = executable_folder();
  for (const std::string& candidate : {dir + "/trace_viewer.html", dir + "/../share/skinmesh/trace_viewer.html"})
    if (!dir.empty() && std::filesystem::exists(candidate)) return candidate;
  throw InputError("trace_viewer.html", 0,
                   "the trace viewer page is not built: run 'make viewer' (needs node and npm), or give --viewer "
                   "FILE, or write the data alone with -o trace.json");
}

int run_trace(TraceArgs& a) {
  const std::string ext = std::filesystem::path(a.out).extension().string();
  if (ext != ".html" && ext != ".json")
    throw InputError(a.out, 0, "unknown trace format '" + ext + "' (.html: the page, .json: the data alone)");
  require_writable(a.out);
  std::string viewer_template;
  if (ext == ".html") {
    const std::string path = find_viewer(a.viewer);
    viewer_template = read_file(path);
    if (viewer_template.find(trace::kTracePlaceholder) == std::string::npos)
      throw InputError(path, 0, std::string("not a trace viewer template (no ") + trace::kTracePlaceholder + ")");
  }
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const skin::Molecule mol = load_molecule(a.mol);
  trace::TraceOptions& o = a.opt;
  o.input = std::filesystem::path(a.mol.input).filename().string();
  o.probe = a.mol.probe;
  o.title = o.input + ", probe " + CLI::detail::to_string(a.mol.probe) + " Å, " + a.algorithm;
  o.mesh.algorithm = mesher::algorithm_named(a.algorithm);
  o.mesh.probe_radius = a.mol.probe;
  o.mesh.height_direction = height_direction(a.direction);
  o.mesh.check = !a.no_check;
  o.mesh.improve_angles = !a.no_angle_improvement;
  o.mesh.dynamic.growth = !a.no_growth;
  o.mesh.observers.memory_released = release_free_memory;
  ProgressReporter progress(!a.mol.quiet);
  o.mesh.progress = [&progress](const std::string& stage, double f) { progress.report(stage, f); };
  trace::TraceSummary summary;
  const nlohmann::json doc = trace::record_trace(skin::weighted_points(mol, a.mol.probe), o, &summary);
  progress.finish();
  const std::string text = ext == ".html" ? trace::fill_viewer_template(viewer_template, doc)
                                          : doc.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  write_text_file(a.out, text);
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (!a.mol.quiet) {
    char line[400];
    std::snprintf(line, sizeof line,
                  "wrote %s: %zu steps of %zu operations, %zu vertices, %zu face records, %.1f MB, %.2f s; final mesh "
                  "%zu triangles, min angle %.4f°%s\n",
                  a.out.c_str(), summary.steps, summary.operations, summary.vertices, summary.face_records,
                  double(text.size()) / 1e6, seconds, summary.triangles, summary.min_angle_deg,
                  summary.checked ? (summary.ok ? ", every check passed" : " (FAILED its checks)") : ", not checked");
    std::cerr << line;
    if (text.size() > 50u << 20)
      std::cerr << "note: the page is above 50 MB; --every N records every N-th operation only\n";
  }
  if (!summary.ok) {
    for (const std::string& p : summary.problems) std::cerr << "problem: " << p << "\n";
    std::cerr << "error: the traced mesh failed its checks (the trace was written and shows it)\n";
    return 3;
  }
  return 0;
}

}  // namespace

Command add_trace_command(CLI::App& app) {
  auto args = std::make_shared<TraceArgs>();
  TraceArgs& tr = *args;
  CLI::App* cmd = app.add_subcommand(
      "trace",
      "run the algorithm and record it step by step as one self-contained page (.html: the Morse–Smale complex, "
      "every operation of the sweep, the refinement, the final mesh's quality; opens offline in a browser) or as "
      "its data alone (.json; format in trace/FORMAT.md)");
  add_molecule_options(*cmd, tr.mol);
  cmd->add_option("-o,--output", tr.out, "output page (.html) or data (.json)")->required();
  cmd->add_option("--algorithm", tr.algorithm, "sweep (Cheng & Shi 2004) or dynamic (the dynamic-skin baseline)")
      ->check(CLI::IsMember({"sweep", "dynamic"}))
      ->capture_default_str();
  cmd->add_option("--steps", tr.opt.max_steps,
                  "record at most about this many steps: beyond it, consecutive operations are merged")
      ->check(CLI::Range(10, 1000000))
      ->capture_default_str();
  cmd->add_option("--every", tr.opt.every,
                  "record every N-th operation (default: chosen from --steps by a first, counting run)")
      ->check(CLI::Range(1, 1000000000));
  cmd->add_option("--viewer", tr.viewer,
                  "the viewer template (default: trace_viewer.html beside the program, built by 'make viewer')");
  add_direction_option(*cmd, tr.direction);
  add_size_options(*cmd, tr.opt.mesh.size);
  cmd->add_flag("--no-angle-improvement", tr.no_angle_improvement, "skip the angle improvement (sweep)");
  cmd->add_flag("--no-growth", tr.no_growth, "with --algorithm dynamic: the static variant");
  cmd->add_flag("--no-check", tr.no_check, "do not verify the final mesh");
  add_threads_option(*cmd, tr.opt.mesh.threads, "0: every core", "trace is");
  return {cmd, [args, cmd] {
            if (!options_fit_algorithm(*cmd, args->algorithm == "dynamic",
                                       {"--direction", "--no-angle-improvement", "--no-growth"}, {"--no-growth"}))
              return 2;
            return run_trace(*args);
          }};
}

}  // namespace skinmesh::app
