// apps/info.cpp: `skinmesh info IN` — the atoms, the regular triangulation,
// the mixed cells, the critical points, the Morse–Smale complex and the
// skin's expected topology, as text or JSON.
#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>

#include "apps/cli.h"
#include "morse/critical_points.h"
#include "morse/morse_smale_complex.h"
#include "skin/dual_complex.h"
#include "skin/molecule_io.h"
#include "skin/skin_surface.h"

namespace skinmesh::app {

namespace {

using json = nlohmann::ordered_json;

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
  // Every core: none of the report depends on the thread count.
  const skin::SkinSurface skin(skin::translated(points, skin::local_frame_centre(points)), 0);
  const auto& rt = skin.triangulation();
  const auto& mc = skin.mixed_complex();
  const skin::SkinTopology topo = skin::dual_complex_topology(mc, 0);
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

}  // namespace

Command add_info_command(CLI::App& app) {
  auto args = std::make_shared<InfoArgs>();
  CLI::App* cmd = app.add_subcommand(
      "info",
      "atoms, regular triangulation, mixed cells, critical points, the Morse–Smale complex and the skin's "
      "expected topology");
  add_molecule_options(*cmd, args->mol);
  add_direction_option(*cmd, args->direction);
  cmd->add_flag("--json", args->json, "print a JSON object instead of text");
  return {cmd, [args] { return run_info(*args); }};
}

}  // namespace skinmesh::app
