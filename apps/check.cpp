// apps/check.cpp: `skinmesh check IN MESH` — the verifier of a mesh file
// against the analytic skin of a molecule (verify/skin_mesh_check.h), with a
// JSON report; exit 0 if every check passes, 1 otherwise.
#include <iostream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/cli.h"
#include "apps/output.h"
#include "skin/molecule_io.h"
#include "skin/skin_mesh_io.h"
#include "skin/skin_surface.h"
#include "verify/skin_mesh_check.h"

namespace skinmesh::app {

namespace {

struct CheckArgs {
  MoleculeArgs mol;
  std::string mesh;
  std::string report;
  verify::SkinCheckOptions opt;
  /// C and Q (--C, --Q) and the threads (--threads, 0: every core).
  skin::RunContext run = [] {
    skin::RunContext r;
    r.threads = 0;
    return r;
  }();
  bool no_self_intersections = false, no_rdt = false;
  /// --max-vertex-distance: "auto" (the file's rounding, else 1e-9 Å) or a distance in Å.
  std::string max_vertex_distance = "auto";
  bool strict = false;
};

int run_check(CheckArgs& a) {
  if (!a.report.empty()) app::require_writable(a.report);
  const skin::Molecule mol = load_molecule(a.mol);
  geometry::IndexedMesh mesh = skin::read_skin_mesh(a.mesh);
  // Formats that round positions: the vertices' distance to the skin is
  // checked to the rounding (unless --max-vertex-distance says otherwise).
  // [L], [U] and the restricted Delaunay property are strict inequalities
  // that the refinement meets with margins as small as it happens to leave:
  // a rounding tips some without damage a reader sees, so on rounded
  // positions they are left out (--strict keeps them), as the mesher does when
  // it checks the positions a lossy file will hold (mesher/pipeline.h,
  // MeshOptions::stored_positions).
  const double rounding = skin::position_rounding(a.mesh, mesh);
  std::string tolerance_from = "given (--max-vertex-distance)";
  if (a.max_vertex_distance == "auto") {
    tolerance_from = "auto: exact positions";
    if (rounding > a.opt.max_vertex_distance) {
      a.opt.max_vertex_distance = rounding;
      tolerance_from = "auto: the rounding of the file's positions";
      if (!a.mol.quiet)
        std::cerr << "note: " << a.mesh << " stores rounded positions: vertex distances to the skin are checked to "
                  << rounding << " Å (--max-vertex-distance auto)\n";
    }
  } else {
    a.opt.max_vertex_distance = std::stod(a.max_vertex_distance);  // validated by the option
  }
  const bool rounded = rounding > 0;
  if (rounded && !a.strict && !a.mol.quiet)
    std::cerr << "note: " << a.mesh
              << " stores rounded positions: [L], [U] and the restricted Delaunay property, which hold for the "
                 "exact positions, are not checked (--strict checks them)\n";
  // The check works in the molecule's local frame, as the mesher does.
  const std::vector<geometry::WeightedPoint> points = skin::weighted_points(mol, a.mol.probe);
  const Vec3 centre = skin::local_frame_centre(points);
  for (Vec3& p : mesh.positions) p -= centre;
  const skin::SkinSurface skin(skin::translated(points, centre), a.run.threads);
  a.opt.check_self_intersections = !a.no_self_intersections;
  a.opt.check_restricted_delaunay = !a.no_rdt && (!rounded || a.strict);
  a.opt.check_size_conditions = !rounded || a.strict;
  const verify::SkinCheckReport rep = verify::check_skin_mesh(skin, mesh, a.opt, a.run);
  // Where the tolerance came from, after the tolerance itself.
  nlohmann::ordered_json report = nlohmann::ordered_json::parse(rep.to_json()), out;
  for (auto it = report.begin(); it != report.end(); ++it) {
    out[it.key()] = it.value();
    if (it.key() == "vertex_distance_tolerance") {
      out["vertex_distance_tolerance_from"] = tolerance_from;
      out["position_rounding_A"] = rounding;
    }
  }
  const std::string text = out.dump(2) + "\n";
  std::cout << text;
  if (!a.report.empty()) app::write_text_file(a.report, text);
  if (!a.mol.quiet)
    for (const std::string& p : rep.problems) std::cerr << "problem: " << p << "\n";
  return rep.ok() ? 0 : 1;
}

}  // namespace

Command add_check_command(CLI::App& app) {
  auto args = std::make_shared<CheckArgs>();
  CheckArgs& check = *args;
  CLI::App* cmd = app.add_subcommand(
      "check",
      "verify MESH against the skin of molecule IN and print a JSON report: closed, manifold, oriented outward, "
      "exact self-intersections, topology, distance to the skin, angles, [L], [U], restricted Delaunay; exit 0 "
      "if every check passes, 1 otherwise");
  add_molecule_options(*cmd, check.mol);
  cmd->add_option("MESH", check.mesh, "mesh file (.ply, .off, .obj, .stl, .vtk, .vtp, .vtu, or .vert/.face for MSMS)")
      ->required();
  cmd->add_option("-o,--output", check.report, "also write the report to this file");
  add_size_options(*cmd, check.run.size);
  cmd->add_option("--min-angle", check.opt.min_angle_deg, "smallest admissible angle in degrees")
      ->capture_default_str();
  add_threads_option(*cmd, check.run.threads, "0: every core", "report is");
  add_shell_options(*cmd, check.opt.shells, "expect in MESH (as `skinmesh mesh` kept them)");
  cmd->add_flag("--no-self-intersections", check.no_self_intersections, "skip the exact self-intersection test");
  cmd->add_flag("--no-rdt", check.no_rdt, "skip the restricted Delaunay test");
  cmd->add_flag("--strict", check.strict,
                "check [L], [U] and the restricted Delaunay property also on a file that rounds positions (MSMS, "
                "STL, float32 PLY/OBJ/OFF/VTK), where they are left out by default: they hold for the exact "
                "positions, and a rounding can tip them without visible damage");
  cmd->add_option("--max-vertex-distance", check.max_vertex_distance,
                  "largest admissible distance of a vertex to the skin in Å, or auto: 1e-9 for exact positions, "
                  "else the rounding of the file's own precision (1e-3 for MSMS; the float32 rounding for STL and "
                  "for PLY, OBJ, OFF or VTK whose coordinates are all float32, as other tools re-save them); the "
                  "report says which (vertex_distance_tolerance_from, position_rounding_A)")
      ->check(CLI::Validator([](std::string& v) { return v == "auto" ? std::string() : number_at_least_zero(true)(v); },
                             "auto|DIST"))
      ->capture_default_str();
  return {cmd, [args] { return run_check(*args); }};
}

}  // namespace skinmesh::app
