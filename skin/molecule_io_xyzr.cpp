// skin/molecule_io_xyzr.cpp: the XYZR and XYZRN (MSMS) readers of
// read_molecule(): `x y z r` per line, extra fields ignored (.xyzr), or `x y z r
// [n [name]]` with the name kept (.xyzrn: MSMS's input with atom names, which
// it copies to its .vert output); blank lines and `#` comments allowed.
// Declared in molecule_io_internal.h.
#include <charconv>
#include <string_view>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/text_split.h"
#include "skin/molecule_io_internal.h"

namespace skinmesh::skin::molecule_io_detail {

using skinmesh::split_blanks;
using skinmesh::split_lines;

namespace {

/// Fills the atom's chain, residue number, insertion code, residue and atom
/// name from an .xyzrn name in MaSIF's form chain_resnum_icode_resname_
/// atomname[_colour] ("A_12_x_ALA_CA_Green"; 'x' for no insertion code);
/// leaves the atom alone for any other name.
void split_masif_name(std::string_view name, Atom& atom) {
  std::vector<std::string_view> parts;
  for (std::size_t start = 0;;) {
    const std::size_t end = name.find('_', start);
    parts.push_back(name.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  if (parts.size() < 5 || parts.size() > 6 || parts[2].size() != 1) return;
  int resnum = 0;
  const auto [ptr, ec] = std::from_chars(parts[1].data(), parts[1].data() + parts[1].size(), resnum);
  if (ec != std::errc() || ptr != parts[1].data() + parts[1].size()) return;
  atom.chain = std::string(parts[0]);
  atom.residue_number = resnum;
  atom.insertion_code = parts[2] == "x" ? ' ' : parts[2][0];
  atom.residue = std::string(parts[3]);
  atom.name = std::string(parts[4]);
}

}  // namespace

Molecule read_xyzr(const std::string& path, const std::string& text, bool names) {
  const std::vector<std::string_view> lines = split_lines(text);
  std::vector<Atom> atoms;
  NoteList notes(path);
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const int line_no = static_cast<int>(k + 1);
    const std::vector<std::string_view> f = fields_before_comment(lines[k]);
    if (f.empty()) continue;
    if (f.size() < 4)
      throw InputError(path, line_no, "expected 'x y z r', found " + std::to_string(f.size()) + " fields");
    Atom atom;
    atom.centre =
        Vec3(parse_number(path, line_no, f[0], "x coordinate"), parse_number(path, line_no, f[1], "y coordinate"),
             parse_number(path, line_no, f[2], "z coordinate"));
    atom.radius = parse_number(path, line_no, f[3], "radius");
    if (atom.radius <= 0.0) throw InputError(path, line_no, "non-positive radius '" + std::string(f[3]) + "'");
    atom.serial = static_cast<int>(atoms.size()) + 1;
    atom.line = line_no;
    if (names && f.size() >= 6) {
      atom.msms_name = std::string(f[5]);
      split_masif_name(f[5], atom);
    }
    atoms.push_back(std::move(atom));
  }
  return finish(path, std::move(atoms), notes);
}

}  // namespace skinmesh::skin::molecule_io_detail
