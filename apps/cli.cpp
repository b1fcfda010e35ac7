// apps/cli.cpp: the options and helpers the commands share (apps/cli.h).
#include "apps/cli.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>

#include "morse/critical_points.h"
#include "skin/molecule_io.h"

namespace skinmesh::app {

const char* const kFormats =
    "\nInput formats (by extension, optionally .gz): .pdb .ent (PDB), .cif .mmcif (mmCIF),\n"
    ".pqr (PQR, radius from the file), .xyzr (x y z r per line), .xyzrn (MSMS: x y z r n name,\n"
    "the name kept for --msms-atom-names). Radii: Bondi by element;\n"
    "atom weight w = 2 (r + probe)^2 (shrink factor 1/2).\n"
    "Output meshes (by extension): .ply (binary, with normals and atom index; --ascii: text), .off,\n"
    ".obj, .stl (binary, for 3D printing; --ascii: text with exact positions), .vtk (legacy VTK with\n"
    "normals, atom, rho and min angle; .vtp and .vtu: XML VTK, every array read by default), and\n"
    ".vert (MSMS: NAME.vert and NAME.face, with normals and the 1-based atom of each vertex);\n"
    "--area-file F: each atom's area (exact skin and mesh) in the layout of MSMS's .area.\n"
    "Exit codes: 0 ok, 1 bad input or failed check, 2 bad command line, 3 the algorithm\n"
    "failed or the mesh failed its checks, 4 internal error.";

CLI::Validator number_at_least_zero(bool strictly) {
  return CLI::Validator(
      [strictly](std::string& s) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(s, v) || !std::isfinite(v)) return "expects a number, got '" + s + "'";
        if (strictly ? !(v > 0) : !(v >= 0))
          return std::string("must be ") + (strictly ? "> 0" : ">= 0") + ", got " + s;
        return {};
      },
      strictly ? "POSITIVE" : "NONNEGATIVE");
}

void add_molecule_options(CLI::App& cmd, MoleculeArgs& m, bool many) {
  cmd.footer(kFormats);
  if (many)
    cmd.add_option("IN", m.inputs,
                   "molecule file(s) (.pdb .ent .cif .mmcif .pqr .xyzr .xyzrn, optionally .gz); several: a batch run "
                   "(-O DIR)");
  else
    cmd.add_option("IN", m.input, "molecule file (.pdb .ent .cif .mmcif .pqr .xyzr .xyzrn, optionally .gz)")
        ->required();
  cmd.add_option("--probe", m.probe, "probe radius in Å; atom weight w = 2 (r + probe)²")
      ->check(number_at_least_zero(false))
      ->capture_default_str();
  cmd.add_flag("--keep-water", m.keep_water, "keep water molecules (default: dropped, with a note)");
  cmd.add_flag("--no-hydrogens", m.no_hydrogens, "drop hydrogen atoms (default: kept if present)");
  cmd.add_option("--format", m.format, "input format (default: by extension)")
      ->check(CLI::IsMember({"pdb", "cif", "mmcif", "pqr", "xyzr", "xyzrn"}));
  cmd.add_option("--model", m.model,
                 std::string("the model of a PDB or mmCIF file to read: N, the one numbered N (MODEL N, "
                             "pdbx_PDB_model_num N)") +
                     (many ? "; all: each model, one mesh per model (a batch run: -O DIR)" : "") +
                     " (default: the first)")
      ->check(CLI::Validator(
          [many](std::string& v) -> std::string {
            if (many && v == "all") return {};
            int n = 0;
            if (CLI::detail::lexical_cast(v, n) && n >= 1) return {};
            return std::string("expects a model number >= 1") + (many ? " or all" : "") + ", got '" + v + "'";
          },
          many ? "N|all" : "N"));
  cmd.add_option("--assembly", m.assembly,
                 "read the biological assembly ID of a PDB (REMARK 350 BIOMOLECULE) or mmCIF "
                 "(_pdbx_struct_assembly) file: the model's chains copied by the assembly's operators, the copies "
                 "named A, A2, A3... (default: the file's coordinates)");
  cmd.add_option("--chains", m.chains,
                 std::string("mesh only these chains, a comma-separated list (A,B; a copy of an --assembly is A2)") +
                     (many ? "; each: one mesh per chain (a batch run: -O DIR)" : "") + " (default: every chain)");
  cmd.add_flag("--quiet,-q", m.quiet, "no notes or progress on stderr");
}

skin::Molecule load_molecule(const MoleculeArgs& m) {
  skin::ReadOptions ro;
  ro.keep_water = m.keep_water;
  ro.keep_hydrogens = !m.no_hydrogens;
  const std::map<std::string, skin::ReadOptions::Format> formats = {
      {"pdb", skin::ReadOptions::Format::Pdb},     {"cif", skin::ReadOptions::Format::Mmcif},
      {"mmcif", skin::ReadOptions::Format::Mmcif}, {"pqr", skin::ReadOptions::Format::Pqr},
      {"xyzr", skin::ReadOptions::Format::Xyzr},   {"xyzrn", skin::ReadOptions::Format::Xyzrn}};
  if (!m.format.empty()) ro.format = formats.at(m.format);
  if (!m.model.empty()) ro.model = std::stoi(m.model);  // validated by the option; "all" is expanded by the batch
  ro.assembly = m.assembly;
  if (m.chains == "each") throw CLI::ValidationError("--chains", "each applies to `skinmesh mesh` with -O DIR");
  for (std::size_t at = 0; !m.chains.empty() && at <= m.chains.size();) {
    const std::size_t comma = std::min(m.chains.find(',', at), m.chains.size());
    ro.chains.emplace_back(m.chains.substr(at, comma - at));
    at = comma + 1;
  }
  skin::Molecule mol = skin::read_molecule(m.input, ro);
  if (!m.quiet) {
    const std::size_t shown = std::min<std::size_t>(mol.notes.size(), 10);
    for (std::size_t i = 0; i < shown; ++i) std::cerr << "note: " << mol.notes[i] << "\n";
    if (mol.notes.size() > shown) std::cerr << "note: ... and " << (mol.notes.size() - shown) << " more notes\n";
  }
  return mol;
}

void add_direction_option(CLI::App& cmd, std::vector<double>& direction) {
  cmd.add_option("--direction", direction, "height direction of the sweep X,Y,Z (default: generic, near +y)")
      ->delimiter(',')
      ->expected(3);
}

Vec3 height_direction(const std::vector<double>& d) {
  if (d.empty()) return morse::default_height_direction();
  const Vec3 e(d[0], d[1], d[2]);
  if (!(e.norm() > 0) || !e.allFinite()) throw CLI::ValidationError("--direction", "must be a finite non-zero vector");
  return e.normalized();
}

void add_threads_option(CLI::App& cmd, int& threads, const char* zero, const char* what) {
  cmd.add_option("--threads", threads, std::string("threads (") + zero + "); the " + what + " the same for every count")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
}

void add_shell_options(CLI::App& cmd, skin::ShellSelection& shells, const char* what) {
  cmd.add_option_function<std::string>(
         "--cavities", [&shells](const std::string& name) { shells.cavities = skin::cavity_choice_named(name); },
         std::string("which shells to ") + what +
             ": keep (every one), remove (the outer surfaces only, as MSMS writes), only (the cavities only); a "
             "cavity is a shell enclosing a negative volume (default: keep)")
      ->check(CLI::IsMember({"keep", "remove", "only"}));
  cmd.add_option("--min-cavity-volume", shells.min_cavity_volume,
                 "leave out the cavities enclosing less than this volume in Å³ (default: 0, none)")
      ->check(number_at_least_zero(false));
}

void add_size_options(CLI::App& cmd, skin::SizeConstants& size) {
  cmd.add_option("--C", size.C, "size constant C of [L] and [U]")
      ->check(number_at_least_zero(true))
      ->capture_default_str();
  cmd.add_option("--Q", size.Q, "size constant Q of [L] and [U]")
      ->check(number_at_least_zero(true))
      ->capture_default_str();
}

bool options_fit_algorithm(const CLI::App& cmd, bool dynamic, const std::vector<std::string>& names,
                           const std::vector<std::string>& dynamic_only) {
  for (const std::string& name : names) {
    const bool sweep_only = std::find(dynamic_only.begin(), dynamic_only.end(), name) == dynamic_only.end();
    if (cmd.count(name) > 0 && sweep_only == dynamic) {
      std::cerr << "skinmesh " << cmd.get_name() << ": " << name << " applies to --algorithm "
                << (sweep_only ? "sweep" : "dynamic") << " only (see 'skinmesh " << cmd.get_name() << " --help')\n";
      return false;
    }
  }
  return true;
}

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  if (s.size() > 300) s = s.substr(0, 297) + "...";
  return s;
}

}  // namespace skinmesh::app
