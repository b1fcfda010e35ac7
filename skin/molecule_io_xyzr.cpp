// skin/molecule_io_xyzr.cpp: the XYZR (MSMS) reader of read_molecule(): `x y z r`
// per line, extra fields ignored, blank lines and `#` comments allowed.
// Declared in molecule_io_internal.h.
#include <string_view>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/text_split.h"
#include "skin/molecule_io_internal.h"

namespace skinmesh::skin::molecule_io_detail {

using skinmesh::split_blanks;
using skinmesh::split_lines;

Molecule read_xyzr(const std::string& path, const std::string& text) {
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
    atoms.push_back(std::move(atom));
  }
  return finish(path, std::move(atoms), notes);
}

}  // namespace skinmesh::skin::molecule_io_detail
