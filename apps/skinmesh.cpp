// apps/skinmesh.cpp: the command-line program. Options are parsed here with
// CLI11, per command (an option a command does not have is an error), and the
// library takes typed structs (papers/conventions.md §3). Errors are one line
// "file:line: problem" with a non-zero exit code; no partial output file is
// ever left behind (every file is written to a temporary and renamed).
//
//   skinmesh info  IN                describe the skin of a molecule
//   skinmesh mesh  IN -o OUT         mesh the skin (Cheng & Shi 2004)
//   skinmesh check IN MESH           verify a mesh against the analytic skin
//   skinmesh trace IN -o trace.html  record the algorithm, step by step, as a page
//
// Exit codes: 0 success; 1 bad input or a mesh that fails `check`; 2 bad
// command line; 3 the algorithm failed (or the mesh failed its checks);
// 4 internal error.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <algorithm>
#include <atomic>
#include <cctype>
#include <map>
#include <mutex>
#include <optional>
#include <thread>
#include <string>
#include <utility>
#include <vector>

#if defined(__GLIBC__)
#include <malloc.h>  // mallopt
#endif
#include <unistd.h>  // readlink

#include "apps/output.h"
#include "dynamic/dynamic_skin.h"
#include "mesher/pipeline.h"
#include "core/errors.h"
#include "geometry/io/mesh_io.h"
#include "geometry/mesh/mesh_measures.h"
#include "core/parallel.h"
#include "morse/critical_points.h"
#include "morse/morse_smale_complex.h"
#include "verify/skin_mesh_check.h"
#include "skin/dual_complex.h"
#include "skin/molecule_io.h"
#include "skin/skin_measures.h"
#include "skin/skin_surface.h"
#include "trace/trace_recorder.h"

using namespace skinmesh;
using json = nlohmann::ordered_json;

namespace {

constexpr const char* kDescription =
    "skinmesh: guaranteed-quality meshes of molecular skin surfaces\n"
    "(Cheng & Shi, \"Guaranteed Quality Triangulation of Molecular Skin Surfaces\", IEEE Vis 2004).";

constexpr const char* kFormats =
    "\nInput formats (by extension, optionally .gz): .pdb .ent (PDB), .cif .mmcif (mmCIF),\n"
    ".pqr (PQR, radius from the file), .xyzr (x y z r per line). Radii: Bondi by element;\n"
    "atom weight w = 2 (r + probe)^2 (shrink factor 1/2).\n"
    "Output meshes (by extension): .ply (binary, with normals and atom index), .off, .obj,\n"
    ".stl (binary, for 3D printing), .vtk (legacy VTK with normals, atom, rho and min angle), and\n"
    ".vert (MSMS: NAME.vert and NAME.face, with normals and the 1-based atom of each vertex).\n"
    "Exit codes: 0 ok, 1 bad input or failed check, 2 bad command line, 3 the algorithm\n"
    "failed or the mesh failed its checks, 4 internal error.";

// Options Shared by the Commands

/// A validator for numbers >= 0 (positive: > 0) with a short message.
CLI::Validator number_at_least_zero(bool strictly) {
  return CLI::Validator(
      [strictly](std::string& s) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(s, v) || !std::isfinite(v)) return "expects a number, got '" + s + "'";
        if (strictly ? !(v > 0) : !(v >= 0)) return std::string("must be ") + (strictly ? "> 0" : ">= 0") + ", got " + s;
        return {};
      },
      strictly ? "POSITIVE" : "NONNEGATIVE");
}

/// The molecule options of every command.
struct MoleculeArgs {
  std::string input;
  /// `mesh` only: every IN given (one: input; several: a batch run).
  std::vector<std::string> inputs;
  double probe = 1.4;
  bool keep_water = false;
  bool no_hydrogens = false;
  std::string format;
  bool quiet = false;
};

void add_molecule_options(CLI::App& cmd, MoleculeArgs& m, bool many = false) {
  cmd.footer(kFormats);
  if (many)
    cmd.add_option("IN", m.inputs,
                   "molecule file(s) (.pdb .ent .cif .mmcif .pqr .xyzr, optionally .gz); several: a batch run "
                   "(-O DIR)");
  else
    cmd.add_option("IN", m.input, "molecule file (.pdb .ent .cif .mmcif .pqr .xyzr, optionally .gz)")->required();
  cmd.add_option("--probe", m.probe, "probe radius in Å; atom weight w = 2 (r + probe)²")
      ->check(number_at_least_zero(false))
      ->capture_default_str();
  cmd.add_flag("--keep-water", m.keep_water, "keep water molecules (default: dropped, with a note)");
  cmd.add_flag("--no-hydrogens", m.no_hydrogens, "drop hydrogen atoms (default: kept if present)");
  cmd.add_option("--format", m.format, "input format (default: by extension)")
      ->check(CLI::IsMember({"pdb", "cif", "mmcif", "pqr", "xyzr"}));
  cmd.add_flag("--quiet,-q", m.quiet, "no notes or progress on stderr");
}

/// Reads the molecule and prints (at most ten of) its notes unless quiet.
skin::Molecule load_molecule(const MoleculeArgs& m) {
  skin::ReadOptions ro;
  ro.keep_water = m.keep_water;
  ro.keep_hydrogens = !m.no_hydrogens;
  const std::map<std::string, skin::ReadOptions::Format> formats = {{"pdb", skin::ReadOptions::Format::Pdb},
                                                                     {"cif", skin::ReadOptions::Format::Mmcif},
                                                                     {"mmcif", skin::ReadOptions::Format::Mmcif},
                                                                     {"pqr", skin::ReadOptions::Format::Pqr},
                                                                     {"xyzr", skin::ReadOptions::Format::Xyzr}};
  if (!m.format.empty()) ro.format = formats.at(m.format);
  skin::Molecule mol = skin::read_molecule(m.input, ro);
  if (!m.quiet) {
    const std::size_t shown = std::min<std::size_t>(mol.notes.size(), 10);
    for (std::size_t i = 0; i < shown; ++i) std::cerr << "note: " << mol.notes[i] << "\n";
    if (mol.notes.size() > shown) std::cerr << "note: ... and " << (mol.notes.size() - shown) << " more notes\n";
  }
  return mol;
}

/// --direction X,Y,Z of info and mesh.
void add_direction_option(CLI::App& cmd, std::vector<double>& direction) {
  cmd.add_option("--direction", direction, "height direction of the sweep X,Y,Z (default: generic, near +y)")
      ->delimiter(',')
      ->expected(3);
}

/// The unit height direction from --direction, or the default.
Vec3 height_direction(const std::vector<double>& d) {
  if (d.empty()) return morse::default_height_direction();
  const Vec3 e(d[0], d[1], d[2]);
  if (!(e.norm() > 0) || !e.allFinite()) throw CLI::ValidationError("--direction", "must be a finite non-zero vector");
  return e.normalized();
}

/// --C and --Q of mesh and check.
void add_size_options(CLI::App& cmd, skin::SizeConstants& size) {
  cmd.add_option("--C", size.C, "size constant C of [L] and [U]")
      ->check(number_at_least_zero(true))
      ->capture_default_str();
  cmd.add_option("--Q", size.Q, "size constant Q of [L] and [U]")
      ->check(number_at_least_zero(true))
      ->capture_default_str();
}

// info

struct InfoArgs {
  MoleculeArgs mol;
  std::vector<double> direction;
  bool json = false;
};

int run_info(const InfoArgs& a) {
  const skin::Molecule mol = load_molecule(a.mol);
  // In the molecule's local frame, as the mesher works: the same triangulation,
  // critical points and expected topology as `skinmesh mesh` sees.
  const std::vector<geometry::WeightedPoint> points = skin::weighted_points(mol, a.mol.probe);
  const skin::SkinSurface skin(skin::translated(points, skin::local_frame_centre(points)));
  const auto& rt = skin.triangulation();
  const auto& mc = skin.mixed_complex();
  const skin::SkinTopology topo = skin::dual_complex_topology(mc);
  const Vec3 e = height_direction(a.direction);
  const morse::MorseSmaleComplex ms = morse::build_morse_smale_complex(skin, e);
  const morse::MorseCount all = morse::count_critical_points(ms.critical);
  const morse::MorseCount live = ms.live_count();
  std::size_t failed_lines = 0;
  for (const auto& l : ms.lines) failed_lines += l.end == kInvalidIndex ? 1 : 0;
  const std::size_t redundant = rt.redundant_points().size();
  const bool matches = all.euler() == topo.euler_skin();

  if (a.json) {
    json j;
    j["input"] = a.mol.input;
    j["atoms"] = mol.atoms.size();
    j["notes"] = mol.notes.size();
    j["probe_radius"] = a.mol.probe;
    j["redundant_atoms"] = redundant;
    j["mixed_cells"] = {{"vertex", mc.num_cells_of_dim(0)},
                        {"edge", mc.num_cells_of_dim(1)},
                        {"triangle", mc.num_cells_of_dim(2)},
                        {"tetrahedron", mc.num_cells_of_dim(3)}};
    j["height_direction"] = {e.x(), e.y(), e.z()};
    j["critical_points"] = {{"minima", all.minima}, {"saddles", all.saddles}, {"maxima", all.maxima}};
    j["morse_euler"] = all.euler();
    j["live_after_simplification"] = {{"minima", live.minima}, {"saddles", live.saddles}, {"maxima", live.maxima}};
    j["cancelled_pairs"] = ms.cancelled.size();
    j["remaining_sphere_conflicts"] = ms.conflicts.size();
    j["failed_integral_lines"] = failed_lines;
    j["expected_topology"] = {{"euler", topo.euler_skin()},
                              {"components", topo.components()},
                              {"body_components", topo.betti0},
                              {"cavities", topo.betti2},
                              {"total_genus", topo.total_genus()}};
    j["morse_count_matches"] = matches;
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << "input              " << a.mol.input << "\n"
              << "atoms              " << mol.atoms.size() << " (" << mol.notes.size() << " notes)\n"
              << "probe radius       " << a.mol.probe << " Å (weights w = 2 (r + probe)²)\n"
              << "redundant atoms    " << redundant << "\n"
              << "regular triangulation: " << rt.num_tets() << " tetrahedra (incl. "
              << "those of the 4 bounding points)\n"
              << "mixed cells        vertex " << mc.num_cells_of_dim(0) << ", edge " << mc.num_cells_of_dim(1)
              << ", triangle " << mc.num_cells_of_dim(2) << ", tetrahedron " << mc.num_cells_of_dim(3) << "\n"
              << "flat tetrahedra    " << mc.num_reordered_foci()
              << " foci moved into the order of their Voronoi edges (cocircular slivers)\n"
              << "height direction   (" << e.x() << ", " << e.y() << ", " << e.z() << ")\n"
              << "critical points    " << all.minima << " minima, " << all.saddles << " saddles, " << all.maxima
              << " maxima (Morse sum " << all.euler() << ")\n"
              << "simplification     " << ms.cancelled.size() << " pairs cancelled, " << live.minima << "/"
              << live.saddles << "/" << live.maxima << " live, " << ms.conflicts.size()
              << " protecting-sphere conflicts left, " << failed_lines << " integral lines failed\n"
              << "expected topology  chi = " << topo.euler_skin() << ", " << topo.components()
              << " component(s): " << topo.betti0 << " body component(s), " << topo.betti2 << " cavit"
              << (topo.betti2 == 1 ? "y" : "ies") << ", total genus " << topo.total_genus() << "\n"
              << "Morse check        " << (matches ? "ok" : "MISMATCH") << "\n";
  }
  if (!matches) {
    std::cerr << "error: Morse count " << all.euler() << " differs from the expected Euler characteristic "
              << topo.euler_skin() << "\n";
    return 1;
  }
  return 0;
}

// check

struct CheckArgs {
  MoleculeArgs mol;
  std::string mesh;
  std::string report;
  verify::SkinCheckOptions opt;
  bool no_self_intersections = false, no_rdt = false;
  bool max_vertex_distance_given = false;
};

int run_check(CheckArgs& a) {
  if (!a.report.empty()) app::require_writable(a.report);
  const skin::Molecule mol = load_molecule(a.mol);
  geometry::IndexedMesh mesh = geometry::read_mesh(a.mesh);
  // Formats that round positions: the vertices' distance to the skin is
  // checked to the rounding (unless --max-vertex-distance says otherwise).
  if (!a.max_vertex_distance_given) {
    const double rounding = geometry::position_rounding(a.mesh, mesh);
    if (rounding > a.opt.max_vertex_distance) {
      a.opt.max_vertex_distance = rounding;
      if (!a.mol.quiet)
        std::cerr << "note: " << a.mesh << " stores rounded positions: vertex distances to the skin are checked to "
                  << rounding << " Å (--max-vertex-distance)\n";
    }
  }
  // The check works in the molecule's local frame, as the mesher does.
  const std::vector<geometry::WeightedPoint> points = skin::weighted_points(mol, a.mol.probe);
  const Vec3 centre = skin::local_frame_centre(points);
  for (Vec3& p : mesh.positions) p -= centre;
  const skin::SkinSurface skin(skin::translated(points, centre));
  a.opt.check_self_intersections = !a.no_self_intersections;
  a.opt.check_restricted_delaunay = !a.no_rdt;
  const verify::SkinCheckReport rep = verify::check_skin_mesh(skin, mesh, a.opt);
  const std::string text = rep.to_json();
  std::cout << text;
  if (!a.report.empty()) app::write_text_file(a.report, text);
  if (!a.mol.quiet)
    for (const std::string& p : rep.problems) std::cerr << "problem: " << p << "\n";
  return rep.ok() ? 0 : 1;
}

// mesh

struct MeshArgs {
  MoleculeArgs mol;
  std::string out, stats;
  std::vector<double> direction;
  mesher::MeshOptions opt;
  bool no_check = false, force = false, trace = false, no_angle_improvement = false;
  /// "sweep" (Cheng & Shi 2004, default) or "dynamic" (the dynamic-skin baseline).
  std::string algorithm = "sweep";
  bool no_growth = false;
  double growth_step = dynamic::DynamicOptions{}.max_step_motion;
  // Batch runs (several IN or --list): outputs DIR/<name>.<format>.
  std::string out_dir, list, batch_format = "ply";
  int jobs = 1;
  bool threads_given = false;
};

/// Peak resident memory of this process (bytes), from /proc/self/status (0 if unknown).
std::size_t peak_memory_bytes() {
  std::ifstream is("/proc/self/status");
  std::string line;
  while (std::getline(is, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024;
  return 0;
}

/// The JSON summary of a mesh run (`--stats`).
json mesh_summary(const MeshArgs& a, const skin::Molecule& mol, const mesher::MeshResult& res,
                  const dynamic::DynamicResult* dyn, double read_s, double write_s, double total_s) {
  json j;
  j["input"] = a.mol.input;
  j["output"] = a.out;
  j["atoms"] = mol.atoms.size();
  j["probe_radius"] = a.mol.probe;
  j["vertices"] = res.mesh.positions.size();
  j["triangles"] = res.mesh.triangles.size();
  {
    // Area and enclosed volume from the mesh, per component and in all.
    json parts = json::array();
    double area = 0, volume = 0;
    for (const geometry::ComponentMeasure& c : geometry::component_measures(res.mesh)) {
      parts.push_back({{"vertices", c.vertices},
                       {"triangles", c.triangles},
                       {"area_A2", c.area},
                       {"volume_A3", c.volume},
                       {"kind", c.volume >= 0 ? "body" : "cavity"}});
      area += c.area;
      volume += c.volume;
    }
    j["surface"] = {{"area_A2", area}, {"volume_A3", volume}, {"components", std::move(parts)}};
    // The same two numbers of the exact skin, integrated over its sphere and
    // hyperboloid patches (skin/skin_measures.h), and how far the mesh is off.
    // A failure here (a broken complex) leaves the mesh's numbers standing.
    const auto start = std::chrono::steady_clock::now();
    try {
      const skin::SkinMeasures exact =
          skin::skin_measures(skin::weighted_points(mol, a.mol.probe), a.opt.threads);
      j["surface"]["analytic"] = {
          {"area_A2", exact.area},
          {"volume_A3", exact.volume},
          {"patch_cells", exact.patch_cells},
          {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()}};
      j["surface"]["mesh_relative_difference"] = {{"area", area / exact.area - 1},
                                                  {"volume", volume / exact.volume - 1}};
    } catch (const GeometryError& e) {
      j["surface"]["analytic"] = {{"error", e.what()}};
      std::fprintf(stderr, "skinmesh: warning: no exact area and volume: %s\n", e.what());
    }
  }
  if (res.checked) {
    j["min_angle_deg"] = res.check.mesh.min_angle_deg;
    j["max_angle_deg"] = res.check.mesh.max_angle_deg;
    j["checks_passed"] = res.check.ok();
  }
  j["critical_points"] = {{"minima", res.critical.minima}, {"saddles", res.critical.saddles},
                          {"maxima", res.critical.maxima}};
  j["live_critical_points"] = {{"minima", res.live.minima}, {"saddles", res.live.saddles},
                               {"maxima", res.live.maxima}};
  j["algorithm"] = a.algorithm;
  j["threads"] = thread_count(a.opt.threads);
  if (dyn) {
    const dynamic::DynamicStats& d = dyn->stats;
    const dynamic::SampleStats& st = d.samples;
    j["growth"] = !a.no_growth;
    j["operations"] = {{"growth_steps", d.steps},
                       {"start_level", d.start_level},
                       {"sphere_patches_seeded", d.births},
                       {"seeds", st.seeds},
                       {"u_insertions", st.u_insertions},
                       {"bounding_insertions", st.bounding_insertions},
                       {"manifold_insertions", st.manifold_insertions},
                       {"l_deletions", st.l_deletions},
                       {"ring_samples", st.ring_samples},
                       {"isolated_deletions", st.isolated_deletions},
                       {"lost_samples", d.lost_samples},
                       {"failed_insertions", st.failed_insertions},
                       {"moves", d.moves},
                       {"kinetic_moves", d.kinetic_moves},
                       {"voronoi_vertices_evaluated", st.tets_classified},
                       {"peak_samples", d.peak_samples},
                       {"peak_tetrahedra", d.peak_tets},
                       {"refine_rounds", st.rounds},
                       {"converged", d.converged},
                       {"L_left", st.L_left},
                       {"U_left", st.U_left},
                       {"nonmanifold_left", st.nonmanifold_left}};
    const auto& dt = d.delaunay;
    j["delaunay"] = {{"insertions", dt.insertions},       {"removals", dt.removals},
                     {"kinetic_moves", dt.kinetic_moves}, {"conflict_tets", dt.conflict_tets},
                     {"star_tets", dt.star_tets},         {"link_vertices", dt.link_vertices},
                     {"local_tets", dt.local_tets},       {"walk_steps", dt.walk_steps}};
    const auto& pr = d.predicates;
    j["predicates"] = {
        {"orient3d", {{"calls", pr.orient3d.calls}, {"exact", pr.orient3d.exact}, {"sos", pr.orient3d.sos}}},
        {"power_test", {{"calls", pr.power_test.calls}, {"exact", pr.power_test.exact}, {"sos", pr.power_test.sos}}}};
  } else {
  const front::SweepStats& s = res.sweep;
  const refine::RefineStats& r = res.refinement;
  j["operations"] = {{"creations", s.creations},
                     {"creeps", s.creeps},
                     {"wings", s.wings},
                     {"bridges", s.bridges},
                     {"seals", s.seals},
                     {"held", s.held},
                     {"deferred", s.deferred},
                     {"bridge_rows", s.bridge_rows},
                     {"contacts", s.contacts},
                     {"collisions", s.collisions},
                     {"stuck", s.stuck},
                     {"enlarged_holes", s.enlarged_holes},
                     {"reopened_holes", s.reopened_holes},
                     {"merged_minima", s.merged_minima},
                     {"released_saddles", s.released},
                     {"flips", r.flips},
                     {"contractions", r.contractions},
                     {"insertions", r.insertions},
                     {"refine_rounds", r.rounds},
                     {"refused_contractions", r.refused_contractions},
                     {"protected_contractions", r.protected_contractions},
                     {"refused_insertions", r.refused_insertions},
                     {"crowded_insertions", r.crowded_insertions},
                     {"flip_caps", r.flip_caps},
                     {"L_left", r.L_left},
                     {"U_left", r.U_left}};
  const refine::AngleImprovementStats& ai = res.angle_improvement;
  j["angle_improvement"] = {{"enabled", a.opt.improve_angles},
                            {"low_triangles", ai.low_triangles},
                            {"passes", ai.passes},
                            {"attempts", ai.attempts},
                            {"moves", ai.moves},
                            {"refused", ai.refused},
                            {"refused_orientation", ai.refused_orientation},
                            {"refused_rdt", ai.refused_rdt},
                            {"refused_intersection", ai.refused_intersection},
                            {"refused_L", ai.refused_L},
                            {"refused_U", ai.refused_U},
                            {"skipped", ai.skipped},
                            {"min_angle_before_deg", ai.min_angle_before_deg},
                            {"min_angle_after_deg", ai.min_angle_after_deg}};
  }
  json seconds = json::object();
  seconds["read"] = read_s;
  for (const auto& [stage, t] : res.seconds) seconds[stage] = t;
  seconds["write"] = write_s;
  seconds["total"] = total_s;
  j["seconds"] = seconds;
  j["peak_memory_bytes"] = peak_memory_bytes();
  return j;
}

/// Meshes `mol` with the algorithm of `a` (sweep: mesher::mesh_skin with `opt`;
/// dynamic: mesh_skin_dynamic, whose result is also kept in `dyn`) and returns
/// the fields the writer and the summary share.
mesher::MeshResult run_algorithm(const MeshArgs& a, const skin::Molecule& mol, const mesher::MeshOptions& opt,
                         std::optional<dynamic::DynamicResult>& dyn) {
  if (a.algorithm != "dynamic") return mesher::mesh_skin(mol, opt);
  dynamic::DynamicOptions d;
  d.probe_radius = a.mol.probe;
  d.size = opt.size;
  d.growth = !a.no_growth;
  d.max_step_motion = a.growth_step;
  d.check = opt.check;
  d.checks.threads = opt.threads;
  d.progress = opt.progress;
  dyn = dynamic::mesh_skin_dynamic(mol, d);
  mesher::MeshResult res;
  res.mesh = std::move(dyn->mesh);
  res.expected_topology = dyn->expected_topology;
  res.checked = dyn->checked;
  res.check = std::move(dyn->check);
  res.seconds = dyn->seconds;
  res.frame_centre = dyn->frame_centre;
  return res;
}

int run_mesh(MeshArgs& a) {
  // Unknown extension or unwritable folder: fail before the work.
  geometry::mesh_format_from_extension(a.out);
  app::require_writable(a.out);
  if (!a.stats.empty()) app::require_writable(a.stats);
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };

  const skin::Molecule mol = load_molecule(a.mol);
  const double read_s = since(start);
  a.opt.probe_radius = a.mol.probe;
  a.opt.height_direction = height_direction(a.direction);
  a.opt.check = !a.no_check;
  a.opt.improve_angles = !a.no_angle_improvement;
  if (a.trace) a.opt.sweep.trace = [](const std::string& line) { std::cerr << line << "\n"; };
  app::ProgressReporter progress(!a.mol.quiet);
  a.opt.progress = [&progress](const std::string& stage, double f) { progress.report(stage, f); };
  std::optional<dynamic::DynamicResult> dyn;
  mesher::MeshResult res = run_algorithm(a, mol, a.opt, dyn);
  progress.finish();

  const bool failed = !res.ok();
  if (failed && !a.force) {
    for (const std::string& p : res.check.problems) std::cerr << "problem: " << p << "\n";
    std::cerr << "error: the mesh failed its checks; not written (use --force to write it anyway)\n";
    if (!a.stats.empty()) app::write_text_file(a.stats, res.check.to_json());
    return 3;
  }
  const auto write_start = Clock::now();
  geometry::write_mesh(a.out, res.mesh);
  const double write_s = since(write_start);
  const double total = since(start);
  if (!a.stats.empty())
    app::write_text_file(a.stats, mesh_summary(a, mol, res, dyn ? &*dyn : nullptr, read_s, write_s, total).dump(2) + "\n");
  if (!a.mol.quiet)
    std::cerr << "wrote " << a.out << ": " << res.mesh.triangles.size() << " triangles"
              << (res.checked ? ", min angle " + std::to_string(res.check.mesh.min_angle_deg) + "°" : std::string())
              << (failed ? " (FAILED its checks, written because of --force)" : "") << ", " << total << " s\n";
  if (failed)
    for (const std::string& p : res.check.problems) std::cerr << "problem: " << p << "\n";
  return failed ? 3 : 0;
}

// trace

struct TraceArgs {
  MoleculeArgs mol;
  std::string out, viewer;
  std::vector<double> direction;
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
  app::require_writable(a.out);
  std::string viewer_template;
  if (ext == ".html") {
    const std::string path = find_viewer(a.viewer);
    viewer_template = app::read_text_file(path);
    if (viewer_template.find(trace::kTracePlaceholder) == std::string::npos)
      throw InputError(path, 0, std::string("not a trace viewer template (no ") + trace::kTracePlaceholder + ")");
  }
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const skin::Molecule mol = load_molecule(a.mol);
  trace::TraceOptions& o = a.opt;
  o.input = std::filesystem::path(a.mol.input).filename().string();
  o.probe = a.mol.probe;
  o.title = o.input + ", probe " + CLI::detail::to_string(a.mol.probe) + " Å, " + o.algorithm;
  o.mesh.probe_radius = a.mol.probe;
  o.mesh.height_direction = height_direction(a.direction);
  o.mesh.check = !a.no_check;
  o.mesh.improve_angles = !a.no_angle_improvement;
  o.dynamic.probe_radius = a.mol.probe;
  o.dynamic.size = o.mesh.size;
  o.dynamic.growth = !a.no_growth;
  o.dynamic.check = !a.no_check;
  o.dynamic.checks.threads = o.mesh.threads;
  app::ProgressReporter progress(!a.mol.quiet);
  o.progress = [&progress](const std::string& stage, double f) { progress.report(stage, f); };
  trace::TraceSummary summary;
  const nlohmann::json doc = trace::record_trace(skin::weighted_points(mol, a.mol.probe), o, &summary);
  progress.finish();
  const std::string text = ext == ".html" ? trace::fill_viewer_template(viewer_template, doc)
                                          : doc.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  app::write_text_file(a.out, text);
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

// mesh: batch runs

std::string one_line(std::string s);

/// One input of a batch run and what became of it.
struct BatchItem {
  std::string input, output;
  std::size_t atoms = 0, triangles = 0;
  double min_angle = 0, area = 0, volume = 0, seconds = 0;
  bool checked = false;
  int exit_code = -1;      ///< as `skinmesh mesh` on this input alone; -1: not run
  std::string status = "not run", message;
};

/// The inputs of a batch: the IN arguments, then the lines of --list (blank
/// lines and '#' comments skipped; relative paths are relative to the list's
/// folder). Throws InputError for an unreadable or empty list.
std::vector<std::string> batch_inputs(const MeshArgs& a) {
  std::vector<std::string> inputs = a.mol.inputs;
  if (!a.list.empty()) {
    const std::string text = app::read_text_file(a.list);
    const std::filesystem::path folder = std::filesystem::path(a.list).parent_path();
    std::size_t at = 0;
    while (at <= text.size()) {
      const std::size_t end = std::min(text.find('\n', at), text.size());
      std::string entry = text.substr(at, end - at);
      if (const std::size_t hash = entry.find('#'); hash != std::string::npos) entry.resize(hash);
      while (!entry.empty() && std::isspace(static_cast<unsigned char>(entry.back()))) entry.pop_back();
      std::size_t first = 0;
      while (first < entry.size() && std::isspace(static_cast<unsigned char>(entry[first]))) ++first;
      entry = entry.substr(first);
      if (!entry.empty()) {
        const std::filesystem::path p(entry);
        inputs.push_back(p.is_absolute() || folder.empty() ? entry : (folder / p).string());
      }
      at = end + 1;
    }
  }
  if (inputs.empty()) throw InputError(a.list, 0, "no molecule files listed");
  return inputs;
}

/// The output name of an input: its file name without .gz and its extension
/// (run_batch keeps the whole file name when two inputs share this name).
std::string batch_stem(const std::string& input) {
  std::filesystem::path p = std::filesystem::path(input).filename();
  if (p.extension() == ".gz" || p.extension() == ".GZ") p = p.stem();
  return p.stem().string();
}

/// Meshes one input of a batch (never throws: the outcome is in the item).
void run_batch_item(const MeshArgs& a, const mesher::MeshOptions& base, BatchItem& item) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  try {
    MoleculeArgs m = a.mol;
    m.input = item.input;
    m.quiet = true;
    const skin::Molecule mol = load_molecule(m);
    item.atoms = mol.atoms.size();
    std::optional<dynamic::DynamicResult> dyn;
    const mesher::MeshResult res = run_algorithm(a, mol, base, dyn);
    item.triangles = res.mesh.triangles.size();
    item.checked = res.checked;
    if (res.checked) item.min_angle = res.check.mesh.min_angle_deg;
    for (const geometry::ComponentMeasure& c : geometry::component_measures(res.mesh))
      item.area += c.area, item.volume += c.volume;
    if (!res.ok()) {
      item.exit_code = 3;
      item.status = "failed check";
      item.message = res.check.problems.empty() ? std::string() : res.check.problems.front();
      if (!a.force) {
        item.message += " (not written; --force writes it)";
        item.seconds = std::chrono::duration<double>(Clock::now() - start).count();
        return;
      }
    }
    geometry::write_mesh(item.output, res.mesh);
    if (item.exit_code == -1) item.exit_code = 0, item.status = "ok";
  } catch (const InputError& e) {
    item.exit_code = 1, item.status = "bad input", item.message = e.what();
  } catch (const TopologyError& e) {
    item.exit_code = 3, item.status = "topology error", item.message = e.what();
  } catch (const GeometryError& e) {
    item.exit_code = 3, item.status = "geometry error", item.message = e.what();
  } catch (const std::invalid_argument& e) {
    item.exit_code = 2, item.status = "bad option", item.message = e.what();
  } catch (const std::exception& e) {
    item.exit_code = 4, item.status = "internal error", item.message = e.what();
  }
  item.seconds = std::chrono::duration<double>(Clock::now() - start).count();
}

/// A CSV field, quoted if it needs to be (RFC 4180).
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

/// `skinmesh mesh IN IN ... -O DIR` (or --list): every input meshed by --jobs
/// workers, one failing input does not stop the others; a summary table on
/// stdout and in DIR/summary.csv and DIR/summary.json. Exit code: 0 if every
/// input succeeded, else the largest of their exit codes.
int run_batch(MeshArgs& a) {
  if (a.out_dir.empty()) throw CLI::ValidationError("-O", "several inputs (or --list) need an output folder -O DIR");
  const std::vector<std::string> inputs = batch_inputs(a);
  std::vector<BatchItem> items(inputs.size());
  // Outputs DIR/NAME.FORMAT; inputs that share a NAME (crambin.pdb and
  // crambin.pqr) keep their whole file name (crambin.pdb.ply, crambin.pqr.ply).
  std::map<std::string, int> stems;
  for (const std::string& in : inputs) ++stems[batch_stem(in)];
  std::map<std::string, std::string> taken;  // output -> input
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    items[i].input = inputs[i];
    const std::string stem = batch_stem(inputs[i]);
    const std::string name = stems[stem] > 1 ? std::filesystem::path(inputs[i]).filename().string() : stem;
    items[i].output = (std::filesystem::path(a.out_dir) / (name + "." + a.batch_format)).string();
    if (auto [it, fresh] = taken.emplace(items[i].output, inputs[i]); !fresh)
      throw InputError(inputs[i], 0, "would write " + items[i].output + " as " + it->second + " does (rename one)");
  }
  std::error_code made;
  std::filesystem::create_directories(a.out_dir, made);
  if (made) throw InputError(a.out_dir, 0, "cannot create the output folder (" + made.message() + ")");
  app::require_writable(items.front().output);
  mesher::MeshOptions base = a.opt;
  base.probe_radius = a.mol.probe;
  base.height_direction = height_direction(a.direction);
  base.check = !a.no_check;
  base.improve_angles = !a.no_angle_improvement;
  if (!a.threads_given) base.threads = 1;  // the workers share the cores
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  std::atomic<std::size_t> next{0}, done{0};
  std::mutex print;
  const int jobs = std::max(1, std::min<int>(a.jobs, static_cast<int>(items.size())));
  auto worker = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < items.size();) {
      run_batch_item(a, base, items[i]);
      const std::size_t k = ++done;
      if (a.mol.quiet) continue;
      const BatchItem& it = items[i];
      std::lock_guard<std::mutex> lock(print);
      std::fprintf(stderr, "[%zu/%zu] %s: %s", k, items.size(), it.input.c_str(), it.status.c_str());
      if (it.exit_code == 0) std::fprintf(stderr, ", %zu triangles, min angle %.2f°, %.2f s", it.triangles, it.min_angle, it.seconds);
      if (!it.message.empty()) std::fprintf(stderr, ": %s", one_line(it.message).c_str());
      std::fprintf(stderr, "\n");
    }
  };
  std::vector<std::thread> pool;
  for (int j = 1; j < jobs; ++j) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();

  // The summary: a table on stdout, CSV and JSON in the output folder.
  std::string table, csv = "input,output,atoms,triangles,min_angle_deg,area_A2,volume_A3,seconds,status,message\n";
  json rows = json::array();
  char line[512];
  std::snprintf(line, sizeof line, "%-36s %8s %10s %9s %8s  %s\n", "input", "atoms", "triangles", "min angle", "seconds",
                "status");
  table += line;
  int exit_code = 0;
  double sum = 0;
  for (const BatchItem& it : items) {
    const std::string name = std::filesystem::path(it.input).filename().string();
    std::snprintf(line, sizeof line, "%-36s %8zu %10zu %9.3f %8.2f  %s\n", name.c_str(), it.atoms, it.triangles,
                  it.min_angle, it.seconds, it.status.c_str());
    table += line;
    char num[160];
    std::snprintf(num, sizeof num, ",%zu,%zu,%.6f,%.6f,%.6f,%.3f,", it.atoms, it.triangles, it.min_angle, it.area,
                  it.volume, it.seconds);
    const bool written = it.exit_code == 0 || (a.force && it.status == "failed check");
    csv += csv_field(it.input) + "," + csv_field(written ? it.output : "") + num +
           csv_field(it.status) + "," + csv_field(one_line(it.message)) + "\n";
    json row = {{"input", it.input},       {"atoms", it.atoms},         {"triangles", it.triangles},
                {"min_angle_deg", it.min_angle}, {"area_A2", it.area}, {"volume_A3", it.volume},
                {"seconds", it.seconds},   {"status", it.status},       {"exit_code", it.exit_code}};
    if (written) row["output"] = it.output;
    if (!it.message.empty()) row["message"] = it.message;
    rows.push_back(std::move(row));
    exit_code = std::max(exit_code, it.exit_code);
    sum += it.seconds;
  }
  const std::size_t failed = static_cast<std::size_t>(
      std::count_if(items.begin(), items.end(), [](const BatchItem& it) { return it.exit_code != 0; }));
  std::snprintf(line, sizeof line, "%zu inputs, %zu failed; wall %.2f s with %d jobs (sum of the inputs' times %.2f s)\n",
                items.size(), failed, wall, jobs, sum);
  table += line;
  std::cout << table << std::flush;
  const std::string csv_path = (std::filesystem::path(a.out_dir) / "summary.csv").string();
  const std::string json_path = (std::filesystem::path(a.out_dir) / "summary.json").string();
  app::write_text_file(csv_path, csv);
  app::write_text_file(json_path, json{{"inputs", std::move(rows)},
                                       {"failed", failed},
                                       {"jobs", jobs},
                                       {"wall_seconds", wall},
                                       {"sum_seconds", sum}}
                                      .dump(2, ' ', false, json::error_handler_t::replace) + "\n");
  if (!a.mol.quiet) std::cerr << "wrote " << csv_path << " and " << json_path << "\n";
  return exit_code;
}

/// One line, at most ~300 characters: details belong in --trace.
std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  if (s.size() > 300) s = s.substr(0, 297) + "...";
  return s;
}

}  // namespace

int main(int argc, char** argv) {
#if defined(__GLIBC__)
  // Large arrays (the mixed complex, the mesh's property arrays, the check's
  // tables) come from their own mappings and go back to the system when freed.
  // By default glibc raises this threshold each time such an array is freed,
  // after which the next ones come from the heap and their memory stays
  // resident after the stage that used them: maltoporin's peak resident size
  // was 255 MB instead of 230 MB (papers/bench/profile.md, "Session of 2026-11-22 (fourth): memory").
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
#endif
  CLI::App app{kDescription, "skinmesh"};
  app.footer(kFormats);
  app.require_subcommand(1);

  InfoArgs info;
  CLI::App* info_cmd = app.add_subcommand(
      "info", "atoms, regular triangulation, mixed cells, critical points, the Morse–Smale complex and the skin's "
              "expected topology");
  add_molecule_options(*info_cmd, info.mol);
  add_direction_option(*info_cmd, info.direction);
  info_cmd->add_flag("--json", info.json, "print a JSON object instead of text");

  MeshArgs mesh;
  CLI::App* mesh_cmd = app.add_subcommand(
      "mesh",
      "mesh the skin surface (shrink factor 1/2) with the advancing front of Cheng & Shi (2004), verify the "
      "mesh against the analytic skin and write it (.ply binary with normals and atom index, .off, .obj, .stl, "
      ".vtk, or MSMS .vert/.face)");
  add_molecule_options(*mesh_cmd, mesh.mol, /*many=*/true);
  mesh_cmd->add_option("-o,--output", mesh.out,
                       "output mesh, format by extension: .ply .off .obj .stl .vtk, or .vert (MSMS: NAME.vert and "
                       "NAME.face)");
  const char* batch = "Batch runs (several IN, or --list)";
  mesh_cmd->add_option("-O,--output-dir", mesh.out_dir,
                       "output folder of a batch run: DIR/NAME.FORMAT per input, DIR/summary.csv and DIR/summary.json")
      ->group(batch);
  mesh_cmd->add_option("--list", mesh.list,
                       "a file of molecule files, one per line ('#' comments; relative to the list's folder)")
      ->group(batch);
  mesh_cmd->add_option("--jobs,-j", mesh.jobs, "inputs meshed at the same time (each on one thread unless --threads)")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str()
      ->group(batch);
  mesh_cmd->add_option("--out-format", mesh.batch_format, "format of a batch run's meshes")
      ->check(CLI::IsMember({"ply", "off", "obj", "stl", "vtk", "vert"}))
      ->capture_default_str()
      ->group(batch);
  mesh_cmd->add_option("--stats", mesh.stats, "write a JSON summary to this file ('-' for stdout)");
  add_direction_option(*mesh_cmd, mesh.direction);
  add_size_options(*mesh_cmd, mesh.opt.size);
  mesh_cmd
      ->add_option("--disc-factor", mesh.opt.sweep.disc_factor,
                   "tangent-disc radius / rho; must lie in (2C/(Q-2C), 2CQ sqrt((1+CQ)(1+3CQ))/(1+2CQ)^2]")
      ->check(number_at_least_zero(true))
      ->capture_default_str();
  mesh_cmd->add_option("--algorithm", mesh.algorithm,
                       "sweep: the advancing front of Cheng & Shi (2004); dynamic: the dynamic-skin baseline "
                       "(Cheng, Dey, Edelsbrunner & Sullivan 2001: restricted Delaunay triangulation of a sample, "
                       "3D Delaunay triangulation, the skin grown from small spheres; papers/dynamic/dynamic_skin.md)")
      ->check(CLI::IsMember({"sweep", "dynamic"}))
      ->capture_default_str();
  mesh_cmd->add_flag("--no-growth", mesh.no_growth,
                     "with --algorithm dynamic: sample and refine the final skin directly (the static variant)");
  mesh_cmd->add_option("--growth-step", mesh.growth_step,
                       "with --algorithm dynamic: largest motion of a sample per growth step, as a fraction of "
                       "its local length scale rho (the growth schedule)")
      ->check(CLI::Range(1e-3, 1.0))
      ->capture_default_str();
  mesh_cmd->add_flag("--no-angle-improvement", mesh.no_angle_improvement,
                     "skip the vertex moves that raise the smallest angles after the refinement (the mesh of "
                     "the paper's algorithm alone; papers/refine/angle_improvement.md)");
  mesh_cmd
      ->add_option("--threads", mesh.opt.threads,
                   "threads (0: every core); the mesh is the same, byte for byte, for every count")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  mesh_cmd->add_flag("--no-check", mesh.no_check, "do not verify the mesh before writing it");
  mesh_cmd->add_flag("--force", mesh.force, "write the mesh even if it fails its checks (the report says what failed)");
  const char* debug = "Debugging the sweep (papers/front/sweep.md)";
  mesh_cmd->add_flag("--paranoid", mesh.opt.sweep.paranoid, "check for folds after every operation of the sweep")
      ->group(debug);
  mesh_cmd->add_flag("--trace", mesh.trace, "print every decision of the sweep on stderr")->group(debug);
  mesh_cmd->add_option("--max-steps", mesh.opt.sweep.max_steps, "stop the sweep after N departures")
      ->check(number_at_least_zero(false))
      ->group(debug);
  mesh_cmd->add_option("--dump-partial", mesh.opt.sweep.dump_path,
                       "write the partial mesh to this file before the seal or when stopped")
      ->group(debug);

  CheckArgs check;
  CLI::App* check_cmd = app.add_subcommand(
      "check",
      "verify MESH against the skin of molecule IN and print a JSON report: closed, manifold, oriented outward, "
      "exact self-intersections, topology, distance to the skin, angles, [L], [U], restricted Delaunay; exit 0 "
      "if every check passes, 1 otherwise");
  add_molecule_options(*check_cmd, check.mol);
  check_cmd->add_option("MESH", check.mesh, "mesh file (.ply, .off, .obj, .stl, .vtk, or .vert/.face for MSMS)")
      ->required();
  check_cmd->add_option("-o,--output", check.report, "also write the report to this file");
  add_size_options(*check_cmd, check.opt.size);
  check_cmd->add_option("--min-angle", check.opt.min_angle_deg, "smallest admissible angle in degrees")
      ->capture_default_str();
  check_cmd
      ->add_option("--threads", check.opt.threads,
                   "threads (0: every core, at most 2 are used); the report is the same for every count")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  check_cmd->add_flag("--no-self-intersections", check.no_self_intersections, "skip the exact self-intersection test");
  check_cmd->add_flag("--no-rdt", check.no_rdt, "skip the restricted Delaunay test");
  check_cmd
      ->add_option("--max-vertex-distance", check.opt.max_vertex_distance,
                   "largest admissible distance of a vertex to the skin in Å (default: 1e-9, or the rounding of the "
                   "format: 1e-3 for MSMS, the float32 rounding for STL)")
      ->check(number_at_least_zero(true));

  TraceArgs tr;
  CLI::App* trace_cmd = app.add_subcommand(
      "trace",
      "run the algorithm and record it step by step as one self-contained page (.html: the Morse–Smale complex, "
      "every operation of the sweep, the refinement, the final mesh's quality; opens offline in a browser) or as "
      "its data alone (.json; format in trace/FORMAT.md)");
  add_molecule_options(*trace_cmd, tr.mol);
  trace_cmd->add_option("-o,--output", tr.out, "output page (.html) or data (.json)")->required();
  trace_cmd->add_option("--algorithm", tr.opt.algorithm, "sweep (Cheng & Shi 2004) or dynamic (the dynamic-skin baseline)")
      ->check(CLI::IsMember({"sweep", "dynamic"}))
      ->capture_default_str();
  trace_cmd->add_option("--steps", tr.opt.max_steps,
                        "record at most about this many steps: beyond it, consecutive operations are merged")
      ->check(CLI::Range(10, 1000000))
      ->capture_default_str();
  trace_cmd->add_option("--every", tr.opt.every,
                        "record every N-th operation (default: chosen from --steps by a first, counting run)")
      ->check(CLI::Range(1, 1000000000));
  trace_cmd->add_option("--viewer", tr.viewer,
                        "the viewer template (default: trace_viewer.html beside the program, built by 'make viewer')");
  add_direction_option(*trace_cmd, tr.direction);
  add_size_options(*trace_cmd, tr.opt.mesh.size);
  trace_cmd->add_flag("--no-angle-improvement", tr.no_angle_improvement, "skip the angle improvement (sweep)");
  trace_cmd->add_flag("--no-growth", tr.no_growth, "with --algorithm dynamic: the static variant");
  trace_cmd->add_flag("--no-check", tr.no_check, "do not verify the final mesh");
  trace_cmd
      ->add_option("--threads", tr.opt.mesh.threads,
                   "threads (0: every core); the trace is the same for every count")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();

  if (argc < 2) {
    std::cerr << app.help();
    return 2;
  }
  if (const std::string first = argv[1]; first[0] != '-' && first != "info" && first != "mesh" && first != "check" &&
      first != "trace") {
    std::cerr << "skinmesh: unknown command '" << first << "' (commands: info, mesh, check, trace; see 'skinmesh --help')\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string cmd;
    for (CLI::App* sub : app.get_subcommands()) cmd = " " + sub->get_name();
    std::cerr << "skinmesh" << cmd << ": " << one_line(e.what()) << " (see 'skinmesh" << cmd << " --help')\n";
    return 2;
  }
  // One input and -o, or a batch run (several inputs or --list, and -O).
  bool batch_run = false;
  if (mesh_cmd->parsed()) {
    mesh.threads_given = mesh_cmd->count("--threads") > 0;
    batch_run = mesh.mol.inputs.size() > 1 || !mesh.list.empty() || !mesh.out_dir.empty();
    std::string problem;
    if (mesh.mol.inputs.empty() && mesh.list.empty()) problem = "IN is required (a molecule file, or several with -O DIR)";
    else if (!batch_run && mesh.out.empty()) problem = "-o OUT is required (or -O DIR for a batch run)";
    else if (batch_run && mesh.out_dir.empty()) problem = "several inputs (or --list) need -O DIR, the output folder";
    else if (batch_run)
      for (const char* name : {"--output", "--stats", "--trace", "--paranoid", "--max-steps", "--dump-partial"})
        if (mesh_cmd->count(name) > 0) {
          problem = std::string(name) + " applies to one input, not to a batch run (-O)";
          break;
        }
    if (!problem.empty()) {
      std::cerr << "skinmesh mesh: " << problem << " (see 'skinmesh mesh --help')\n";
      return 2;
    }
    if (!batch_run) mesh.mol.input = mesh.mol.inputs.front();
  }
  // Options of one algorithm given with the other: an error, not silently ignored.
  if (mesh_cmd->parsed()) {
    const bool dynamic = mesh.algorithm == "dynamic";
    for (const char* name :
         {"--trace", "--paranoid", "--max-steps", "--dump-partial", "--direction", "--disc-factor",
         "--no-angle-improvement", "--no-growth", "--growth-step"}) {
      const bool sweep_only = std::string(name) != "--no-growth" && std::string(name) != "--growth-step";
      if (mesh_cmd->count(name) > 0 && sweep_only == dynamic) {
        std::cerr << "skinmesh mesh: " << name << " applies to --algorithm " << (sweep_only ? "sweep" : "dynamic")
                  << " only (see 'skinmesh mesh --help')\n";
        return 2;
      }
    }
  }
  if (trace_cmd->parsed()) {
    const bool dynamic = tr.opt.algorithm == "dynamic";
    for (const char* name : {"--direction", "--no-angle-improvement", "--no-growth"}) {
      const bool sweep_only = std::string(name) != "--no-growth";
      if (trace_cmd->count(name) > 0 && sweep_only == dynamic) {
        std::cerr << "skinmesh trace: " << name << " applies to --algorithm " << (sweep_only ? "sweep" : "dynamic")
                  << " only (see 'skinmesh trace --help')\n";
        return 2;
      }
    }
  }
  try {
    if (info_cmd->parsed()) return run_info(info);
    if (check_cmd->parsed()) {
      check.max_vertex_distance_given = check_cmd->count("--max-vertex-distance") > 0;
      return run_check(check);
    }
    if (trace_cmd->parsed()) return run_trace(tr);
    return batch_run ? run_batch(mesh) : run_mesh(mesh);
  } catch (const CLI::ValidationError& e) {
    std::cerr << "skinmesh: " << one_line(e.what()) << "\n";
    return 2;
  } catch (const InputError& e) {
    std::cerr << "error: " << one_line(e.what()) << "\n";
    return 1;
  } catch (const TopologyError& e) {
    std::cerr << "error: topology: " << one_line(e.what())
              << (mesh_cmd->parsed() ? " (rerun with --trace for the sweep's decisions)" : "") << "\n";
    return 3;
  } catch (const GeometryError& e) {
    std::cerr << "error: geometry: " << one_line(e.what()) << "\n";
    return 3;
  } catch (const std::invalid_argument& e) {
    std::cerr << "skinmesh: " << one_line(e.what()) << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << one_line(e.what()) << "\n";
    return 4;
  }
}
