// apps/skinmesh.cpp: the command-line program. Parses options (strings stop
// here, STYLE.md §3), runs the pipeline, reports errors as "file:line: problem"
// with a non-zero exit code and never leaves a partial output file.
//
//   skinmesh info  IN                describe the skin of a molecule
//   skinmesh mesh  IN -o OUT         mesh the skin (Cheng & Shi 2004)
//   skinmesh check IN MESH           verify a mesh against the analytic skin
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "apps/cli.h"
#include "geometry/errors.h"
#include "front/pipeline.h"
#include "geometry/mesh_io.h"
#include "morse/critical_points.h"
#include "morse/morse_smale_complex.h"
#include "refine/skin_mesh_check.h"
#include "skin/dual_complex.h"
#include "skin/molecule_io.h"
#include "skin/skin_surface.h"

using namespace skinmesh;

namespace {

// Help Texts

constexpr const char* kMainHelp = R"(skinmesh: guaranteed-quality meshes of molecular skin surfaces
(Cheng & Shi, "Guaranteed Quality Triangulation of Molecular Skin Surfaces", IEEE Vis 2004).

Usage: skinmesh <command> [options]

Commands:
  mesh  IN -o OUT    mesh the skin of a molecule (PLY, OFF or OBJ by extension)
  check IN MESH      verify a mesh against the analytic skin; prints a JSON report
  info  IN           atoms, regular triangulation, mixed cells, critical points,
                     and the skin's expected topology

Input formats (by extension, optionally .gz): .pdb .ent (PDB), .cif .mmcif
(mmCIF), .pqr (PQR, radius from the file), .xyzr (x y z r per line).

Run 'skinmesh <command> --help' for the options of a command.
)";

constexpr const char* kMoleculeOptions = R"(Molecule options:
  --probe R          probe radius in Å (default 1.4); atom weight w = 2 (r + R)²
  --keep-water       keep water molecules (default: dropped, with a note)
  --no-hydrogens     drop hydrogen atoms (default: kept if present)
  --format F         input format: pdb, cif, pqr or xyzr (default: by extension)
  --direction X,Y,Z  height direction of the sweep (default: generic, near +y)
  --quiet            no notes or progress on stderr
)";

constexpr const char* kInfoHelp = R"(Usage: skinmesh info IN [options]

Prints the atoms read (and any skipped or repaired), the regular triangulation
(vertices, redundant atoms, simplices), the mixed cells by type, the critical
points of the height function by index, the Morse–Smale complex, and the skin's
expected topology (from the dual complex K0 of the unshrunk balls).

Options:
  --json             print a JSON object instead of text
)";

constexpr const char* kCheckHelp = R"(Usage: skinmesh check IN MESH [options]

Verifies MESH (PLY, OFF or OBJ) against the skin of molecule IN and prints a
JSON report: closed, manifold, oriented outward, exact self-intersections,
components' Euler characteristics against the expected topology, vertex
distance to the skin (|f|/|grad f| <= 1e-9 Å), angles, conditions [L] and [U]
(C, Q), and the restricted Delaunay property. Exit code 0 if every check
passes, 1 otherwise.

Options:
  -o FILE                 also write the report to FILE
  --C C --Q Q             size constants of [L] and [U] (default 0.08, 1.65)
  --min-angle DEG         smallest admissible angle (default 21.5)
  --no-self-intersections skip the exact self-intersection test
  --no-rdt                skip the restricted Delaunay test
)";

constexpr const char* kMeshHelp = R"(Usage: skinmesh mesh IN -o OUT [options]

Meshes the skin surface (shrink factor 1/2) of molecule IN with the advancing
front of Cheng & Shi (2004) and writes OUT (.ply binary with normals and atom
index, .off or .obj).

Options:
  -o OUT             output mesh (required)
  --stats FILE       write a JSON summary to FILE ('-' for stdout)
  --C C --Q Q        size constants (default 0.08, 1.65)
  --no-check         do not verify the mesh before writing it
  --force            write the mesh even if it fails its checks (the report says what failed)

Debugging the sweep (papers/front/sweep_mesher.md):
  --paranoid         check for folds after every operation of the sweep
  --trace            print every decision of the sweep on stderr
  --max-steps N      stop the sweep after N departures
  --dump-partial F   write the partial mesh to F before the seal or when stopped
)";

// Shared Pipeline Pieces

/// Reads the molecule named by the first positional argument and prints its notes.
skin::Molecule load_molecule(const cli::Args& args, const std::string& path) {
  skin::ReadOptions ro;
  ro.keep_water = args.flag("--keep-water");
  ro.keep_hydrogens = !args.flag("--no-hydrogens");
  if (auto f = args.value("--format")) {
    const std::map<std::string, skin::ReadOptions::Format> formats = {
        {"pdb", skin::ReadOptions::Format::Pdb},
        {"cif", skin::ReadOptions::Format::Mmcif},
        {"mmcif", skin::ReadOptions::Format::Mmcif},
        {"pqr", skin::ReadOptions::Format::Pqr},
        {"xyzr", skin::ReadOptions::Format::Xyzr}};
    auto it = formats.find(*f);
    if (it == formats.end()) throw cli::UsageError("unknown --format '" + *f + "' (pdb, cif, pqr or xyzr)");
    ro.format = it->second;
  }
  skin::Molecule mol = skin::read_molecule(path, ro);
  if (!args.flag("--quiet")) {
    const std::size_t shown = std::min<std::size_t>(mol.notes.size(), 10);
    for (std::size_t i = 0; i < shown; ++i) std::cerr << "note: " << mol.notes[i] << "\n";
    if (mol.notes.size() > shown)
      std::cerr << "note: ... and " << (mol.notes.size() - shown) << " more notes\n";
  }
  return mol;
}

double probe_radius(const cli::Args& args) {
  const double p = args.number("--probe", 1.4);
  if (!(p >= 0)) throw cli::UsageError("--probe must be >= 0");
  return p;
}

Vec3 height_direction(const cli::Args& args) {
  if (auto d = args.value("--direction")) {
    const std::vector<double> v = cli::parse_numbers(*d, "--direction");
    if (v.size() != 3) throw cli::UsageError("--direction takes three numbers X,Y,Z");
    const Vec3 e(v[0], v[1], v[2]);
    if (!(e.norm() > 0)) throw cli::UsageError("--direction must be a non-zero vector");
    return e.normalized();
  }
  return morse::default_height_direction();
}

// Commands

int run_info(const cli::Args& args) {
  if (args.flag("--help")) return std::cout << kInfoHelp << kMoleculeOptions, 0;
  args.expect_positional(1, "skinmesh info IN");
  const std::string in = args.positional(0);
  const skin::Molecule mol = load_molecule(args, in);
  const double probe = probe_radius(args);
  const skin::SkinSurface skin(skin::weighted_points(mol, probe));
  const auto& rt = skin.triangulation();
  const auto& mc = skin.mixed_complex();
  const skin::SkinTopology topo = skin::dual_complex_topology(mc);
  const Vec3 e = height_direction(args);
  const morse::MorseSmaleComplex ms = morse::build_morse_smale_complex(skin, e);
  const morse::MorseCount all = morse::count_critical_points(ms.critical);
  const morse::MorseCount live = ms.live_count();
  std::size_t failed_lines = 0;
  for (const auto& l : ms.lines) failed_lines += l.end == kInvalidIndex ? 1 : 0;
  const std::size_t redundant = rt.redundant_points().size();

  if (args.flag("--json")) {
    std::cout << "{\n  \"input\": \"" << in << "\",\n  \"atoms\": " << mol.atoms.size()
              << ",\n  \"notes\": " << mol.notes.size() << ",\n  \"probe_radius\": " << probe
              << ",\n  \"redundant_atoms\": " << redundant << ",\n  \"mixed_cells\": {\"vertex\": "
              << mc.num_cells_of_dim(0) << ", \"edge\": " << mc.num_cells_of_dim(1)
              << ", \"triangle\": " << mc.num_cells_of_dim(2) << ", \"tetrahedron\": " << mc.num_cells_of_dim(3)
              << "},\n  \"height_direction\": [" << e.x() << ", " << e.y() << ", " << e.z()
              << "],\n  \"critical_points\": {\"minima\": " << all.minima << ", \"saddles\": " << all.saddles
              << ", \"maxima\": " << all.maxima << "},\n  \"morse_euler\": " << all.euler()
              << ",\n  \"live_after_simplification\": {\"minima\": " << live.minima
              << ", \"saddles\": " << live.saddles << ", \"maxima\": " << live.maxima
              << "},\n  \"cancelled_pairs\": " << ms.cancelled.size()
              << ",\n  \"remaining_sphere_conflicts\": " << ms.conflicts.size()
              << ",\n  \"failed_integral_lines\": " << failed_lines
              << ",\n  \"expected_topology\": {\"euler\": " << topo.euler_skin()
              << ", \"components\": " << topo.components() << ", \"body_components\": " << topo.betti0
              << ", \"cavities\": " << topo.betti2 << ", \"total_genus\": " << topo.total_genus()
              << "},\n  \"morse_count_matches\": " << (all.euler() == topo.euler_skin() ? "true" : "false")
              << "\n}\n";
  } else {
    std::cout << "input              " << in << "\n"
              << "atoms              " << mol.atoms.size() << " (" << mol.notes.size() << " notes)\n"
              << "probe radius       " << probe << " Å (weights w = 2 (r + probe)²)\n"
              << "redundant atoms    " << redundant << "\n"
              << "regular triangulation: " << rt.num_tets() << " tetrahedra (incl. "
              << "those of the 4 bounding points)\n"
              << "mixed cells        vertex " << mc.num_cells_of_dim(0) << ", edge " << mc.num_cells_of_dim(1)
              << ", triangle " << mc.num_cells_of_dim(2) << ", tetrahedron " << mc.num_cells_of_dim(3) << "\n"
              << "height direction   (" << e.x() << ", " << e.y() << ", " << e.z() << ")\n"
              << "critical points    " << all.minima << " minima, " << all.saddles << " saddles, "
              << all.maxima << " maxima (Morse sum " << all.euler() << ")\n"
              << "simplification     " << ms.cancelled.size() << " pairs cancelled, " << live.minima << "/"
              << live.saddles << "/" << live.maxima << " live, " << ms.conflicts.size()
              << " protecting-sphere conflicts left, " << failed_lines << " integral lines failed\n"
              << "expected topology  chi = " << topo.euler_skin() << ", " << topo.components()
              << " component(s): " << topo.betti0 << " body component(s), " << topo.betti2
              << " cavit" << (topo.betti2 == 1 ? "y" : "ies") << ", total genus " << topo.total_genus() << "\n"
              << "Morse check        " << (all.euler() == topo.euler_skin() ? "ok" : "MISMATCH") << "\n";
  }
  if (all.euler() != topo.euler_skin()) {
    std::cerr << "error: Morse count " << all.euler() << " differs from the expected Euler characteristic "
              << topo.euler_skin() << "\n";
    return 1;
  }
  return 0;
}

int run_check(const cli::Args& args) {
  if (args.flag("--help")) return std::cout << kCheckHelp << kMoleculeOptions, 0;
  args.expect_positional(2, "skinmesh check IN MESH");
  const skin::Molecule mol = load_molecule(args, args.positional(0));
  const geometry::IndexedMesh mesh = geometry::read_mesh(args.positional(1));
  const skin::SkinSurface skin(skin::weighted_points(mol, probe_radius(args)));
  refine::SkinCheckOptions opt;
  opt.size.C = args.number("--C", opt.size.C);
  opt.size.Q = args.number("--Q", opt.size.Q);
  opt.min_angle_deg = args.number("--min-angle", opt.min_angle_deg);
  opt.check_self_intersections = !args.flag("--no-self-intersections");
  opt.check_restricted_delaunay = !args.flag("--no-rdt");
  const refine::SkinCheckReport rep = refine::check_skin_mesh(skin, mesh, opt);
  const std::string json = rep.to_json();
  std::cout << json;
  if (auto out = args.value("-o")) cli::write_text_file(*out, json);
  if (!args.flag("--quiet"))
    for (const std::string& p : rep.problems) std::cerr << "problem: " << p << "\n";
  return rep.ok() ? 0 : 1;
}

/// Peak resident memory of this process (bytes), from /proc/self/status (0 if unknown).
std::size_t peak_memory_bytes() {
  std::ifstream is("/proc/self/status");
  std::string line;
  while (std::getline(is, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024;
  return 0;
}

int run_mesh(const cli::Args& args) {
  if (args.flag("--help")) return std::cout << kMeshHelp << kMoleculeOptions, 0;
  args.expect_positional(1, "skinmesh mesh IN -o OUT");
  const auto out = args.value("-o");
  if (!out) throw cli::UsageError("mesh needs an output file: -o OUT");
  geometry::mesh_format_from_extension(*out);  // unknown extension: fail before the work
  const bool quiet = args.flag("--quiet");
  using Clock = std::chrono::steady_clock;
  std::vector<std::pair<std::string, double>> seconds;
  auto t0 = Clock::now();
  auto lap = [&](const std::string& stage) {
    const auto t1 = Clock::now();
    seconds.emplace_back(stage, std::chrono::duration<double>(t1 - t0).count());
    t0 = t1;
  };
  const auto start = Clock::now();

  const skin::Molecule mol = load_molecule(args, args.positional(0));
  lap("read");
  MeshOptions mopt;
  mopt.probe_radius = probe_radius(args);
  mopt.height_direction = height_direction(args);
  mopt.size.C = args.number("--C", mopt.size.C);
  mopt.size.Q = args.number("--Q", mopt.size.Q);
  mopt.sweep.paranoid = args.flag("--paranoid");
  if (args.flag("--trace")) mopt.sweep.trace = [](const std::string& line) { std::cerr << line << "\n"; };
  mopt.sweep.max_steps = static_cast<long>(args.number("--max-steps", -1));
  if (auto d = args.value("--dump-partial")) mopt.sweep.dump_path = *d;
  mopt.check = !args.flag("--no-check");
  const MeshResult res = mesh_skin(mol, mopt);
  seconds.insert(seconds.end(), res.seconds.begin(), res.seconds.end());
  t0 = Clock::now();
  const bool checked = res.checked;
  const refine::SkinCheckReport& rep = res.check;
  const bool failed = !res.ok();
  if (failed && !args.flag("--force")) {
    for (const std::string& p : rep.problems) std::cerr << "problem: " << p << "\n";
    std::cerr << "error: the mesh failed its checks; not written (use --force to write it anyway)\n";
    if (auto st = args.value("--stats")) cli::write_text_file(*st, rep.to_json());
    return 3;
  }
  geometry::write_mesh(*out, res.mesh);
  lap("write");
  const double total = std::chrono::duration<double>(Clock::now() - start).count();

  std::ostringstream js;
  js << "{\n  \"input\": \"" << args.positional(0) << "\",\n  \"output\": \"" << *out
     << "\",\n  \"atoms\": " << mol.atoms.size() << ",\n  \"vertices\": " << res.mesh.positions.size()
     << ",\n  \"triangles\": " << res.mesh.triangles.size();
  if (checked)
    js << ",\n  \"min_angle_deg\": " << rep.mesh.min_angle_deg << ",\n  \"max_angle_deg\": "
       << rep.mesh.max_angle_deg << ",\n  \"checks_passed\": " << (rep.ok() ? "true" : "false");
  js << ",\n  \"operations\": {\"creations\": " << res.sweep.creations << ", \"creeps\": " << res.sweep.creeps
     << ", \"wings\": " << res.sweep.wings << ", \"bridges\": " << res.sweep.bridges
     << ", \"seals\": " << res.sweep.seals << ", \"held\": " << res.sweep.held
     << ", \"deferred\": " << res.sweep.deferred << ", \"bridge_rows\": " << res.sweep.bridge_rows
     << ", \"contacts\": " << res.sweep.contacts << ", \"released_saddles\": " << res.sweep.released
     << ", \"flips\": " << res.refinement.flips << ", \"contractions\": " << res.refinement.contractions
     << ", \"insertions\": " << res.refinement.insertions << ", \"refine_rounds\": " << res.refinement.rounds
     << ", \"L_left\": " << res.refinement.L_left << ", \"U_left\": " << res.refinement.U_left << "}";
  js << ",\n  \"seconds\": {";
  for (std::size_t i = 0; i < seconds.size(); ++i)
    js << (i ? ", " : "") << "\"" << seconds[i].first << "\": " << seconds[i].second;
  js << ", \"total\": " << total << "}";
  js << ",\n  \"peak_memory_bytes\": " << peak_memory_bytes() << "\n}\n";
  if (auto st = args.value("--stats")) cli::write_text_file(*st, js.str());
  if (!quiet)
    std::cerr << "wrote " << *out << ": " << res.mesh.triangles.size() << " triangles"
              << (checked ? ", min angle " + std::to_string(rep.mesh.min_angle_deg) + "°" : std::string())
              << (failed ? " (FAILED its checks, written because of --force)" : "") << ", " << total << " s\n";
  if (failed)
    for (const std::string& p : rep.problems) std::cerr << "problem: " << p << "\n";
  return failed ? 3 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc < 2) return std::cerr << kMainHelp, 2;
    const std::string cmd = argv[1];
    if (cmd == "--help" || cmd == "-h" || cmd == "help") return std::cout << kMainHelp, 0;
    const cli::Args args(argc - 2, argv + 2);
    if (cmd == "info") return run_info(args);
    if (cmd == "check") return run_check(args);
    if (cmd == "mesh") return run_mesh(args);
    std::cerr << "skinmesh: unknown command '" << cmd << "'\n\n" << kMainHelp;
    return 2;
  } catch (const InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  } catch (const cli::UsageError& e) {
    std::cerr << "skinmesh: " << e.what() << " (see 'skinmesh --help')\n";
    return 2;
  } catch (const TopologyError& e) {
    std::cerr << "error: topology: " << e.what() << "\n";
    return 3;
  } catch (const GeometryError& e) {
    std::cerr << "error: geometry: " << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << e.what() << "\n";
    return 4;
  }
}
