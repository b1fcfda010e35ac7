// skin/molecule_io_pqr.cpp: the PQR reader of read_molecule() (whitespace
// separated fields; radii from the file, elements guessed from atom names).
// Declared in molecule_io_internal.h.
#include <cctype>
#include <string_view>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/text_split.h"
#include "skin/element_radii.h"
#include "skin/molecule_io_internal.h"

namespace skinmesh::skin::molecule_io_detail {

namespace {

using skinmesh::split_blanks;
using skinmesh::split_lines;

/// Element guessed from a PQR atom name: the residue name if the residue is a
/// single ion named after its element ("NA NA", "ZN ZN"), else the first letter of
/// the name after leading digits ("1HB" -> H). Empty if nothing is recognised.
std::string pqr_element(std::string_view name, std::string_view residue) {
  if (uppercase(name) == uppercase(residue) && name.size() <= 2) {
    std::string s = canonical_element_symbol(name);
    if (!s.empty()) return s;
  }
  while (!name.empty() && std::isdigit(static_cast<unsigned char>(name.front()))) name.remove_prefix(1);
  if (name.empty()) return {};
  return canonical_element_symbol(name.substr(0, 1));
}

}  // namespace

Molecule read_pqr(const std::string& path, const std::string& text, const ReadOptions& opt) {
  const std::vector<std::string_view> lines = split_lines(text);
  std::vector<Atom> atoms;
  NoteList notes(path);
  bool seen_atom = false;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const int line_no = static_cast<int>(k + 1);
    const std::vector<std::string_view> f = split_blanks(lines[k]);
    if (f.empty()) continue;
    const std::string record = uppercase(f[0]);
    if (record == "END" || (record == "ENDMDL" && seen_atom)) break;
    if (record != "ATOM" && record != "HETATM") continue;
    seen_atom = true;
    if (f.size() < 10)
      throw InputError(path, line_no,
                       "PQR record has " + std::to_string(f.size()) +
                           " fields; expected 'ATOM serial name resName [chain] resSeq x y z charge radius'");
    const std::size_t n = f.size();
    Atom atom;
    atom.line = line_no;
    atom.serial = leading_int(f[1]);
    atom.name = std::string(f[2]);
    atom.residue = std::string(f[3]);
    const std::size_t middle = n - 9;  // fields between resName and x
    if (middle == 1) {
      atom.residue_number = leading_int(f[4]);
    } else {
      atom.chain = std::string(f[4]);
      atom.residue_number = leading_int(f[5]);
    }
    const double x = parse_number(path, line_no, f[n - 5], "x coordinate");
    const double y = parse_number(path, line_no, f[n - 4], "y coordinate");
    const double z = parse_number(path, line_no, f[n - 3], "z coordinate");
    parse_number(path, line_no, f[n - 2], "charge");
    const double radius = parse_number(path, line_no, f[n - 1], "radius");
    atom.centre = Vec3(x, y, z);
    atom.element = pqr_element(atom.name, atom.residue);
    // Named only for a note or an error: most atoms get neither.
    const auto who = [&] { return describe(atom.name, atom.residue, atom.chain, atom.residue_number); };
    const bool hydrogen = atom.element == "H" || atom.element == "D";
    if (is_water_residue(atom.residue) && !opt.keep_water) {
      notes.add(line_no,
                "water " + atom.residue + " " + std::to_string(atom.residue_number) + " skipped (use --keep-water)");
      continue;
    }
    if (hydrogen && radius == 0.0) {
      notes.add(line_no, "hydrogen " + who() + " has radius 0; skipped");
      continue;
    }
    if (radius <= 0.0)
      throw InputError(path, line_no, "non-positive radius '" + std::string(f[n - 1]) + "' for " + who());
    if (hydrogen && !opt.keep_hydrogens) {
      notes.add(line_no, "hydrogen " + who() + " skipped (hydrogens not kept)");
      continue;
    }
    atom.radius = radius;
    atoms.push_back(std::move(atom));
  }
  return finish(path, std::move(atoms), notes);
}

}  // namespace skinmesh::skin::molecule_io_detail
