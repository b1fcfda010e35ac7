// geometry/io/mesh_io_msms.cpp: the MSMS format of mesh_io.h (M. F. Sanner's
// MSMS, "Reduced surface: an efficient way to compute molecular surfaces",
// Biopolymers 38, 1996), which electrostatics solvers and surface-learning
// pipelines read: a pair of text files NAME.vert and NAME.face.
//   NAME.vert: three header lines ("# ...", "#vertex #sphere density probe_r",
//     then the counts: vertices, atoms — the largest atom index of a vertex
//     plus one, as the mesh does not know atoms without vertices — and 0 0,
//     the skin having neither density nor probe), then per vertex
//     "%9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %7d %7d %2d": position (Å), unit
//     normal, the number of its surface component (1-based), the 1-based index
//     of its atom, and the MSMS type of its patch.
//   NAME.face: three header lines, then per triangle "%6d %6d %6d %2d %6d":
//     1-based vertex indices, the type, the component.
// MSMS types are 1 (toric reentrant, saddle-shaped), 2 (spheric reentrant,
// concave), 3 (contact, convex). On the skin: a sphere patch of an atom's
// vertex cell is 3, the concave sphere patch of a tetrahedron cell 2, the
// hyperboloid patches of edge and triangle cells 1 (IndexedMesh::patch); a
// triangle has the type its corners share, 1 when they differ. Positions have
// three decimals, as MSMS writes them. Declared in mesh_io_internal.h.
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "core/errors.h"
#include "core/text_split.h"
#include "geometry/io/mesh_io_internal.h"
#include "geometry/mesh/mesh_measures.h"

namespace skinmesh::geometry::mesh_io_detail {

namespace {

/// MSMS type of a vertex from the dimension of its mixed cell (0..3); 0 if unknown.
int msms_type(const IndexedMesh& m, std::size_t v) {
  if (m.patch.empty()) return 0;
  switch (m.patch[v]) {
    case 0:
      return 3;
    case 3:
      return 2;
    default:
      return 1;
  }
}

/// Reads the three header lines of an MSMS file starting at `first` and
/// returns the count on the third line; the records follow.
std::size_t msms_header(const std::string& path, const std::vector<std::string_view>& lines, std::size_t first,
                        const char* what) {
  if (lines.size() < first + 3)
    throw InputError(path, static_cast<int>(lines.size()),
                     std::string("unexpected end of the MSMS ") + what + " header");
  for (std::size_t k = first; k < first + 2; ++k)
    if (!trim(lines[k]).starts_with("#"))
      throw InputError(path, static_cast<int>(k + 1),
                       std::string("not an MSMS ") + what + " file (header lines begin with '#')");
  const std::vector<std::string_view> counts = split_blanks(lines[first + 2]);
  const int line = static_cast<int>(first + 3);
  if (counts.empty()) throw InputError(path, line, std::string("MSMS ") + what + " header without a count");
  const std::int64_t n = int_or_throw(path, line, counts[0], "count");
  if (n < 0) throw InputError(path, line, "negative count");
  if (static_cast<std::uint64_t>(n) > lines.size() - (first + 3))
    throw InputError(path, static_cast<int>(lines.size()),
                     "unexpected end of file: expected " + std::to_string(n) + " " + what + " records");
  return static_cast<std::size_t>(n);
}

}  // namespace

std::pair<std::string, std::string> msms_text(const IndexedMesh& m, const std::string& name) {
  const std::vector<int> component = vertex_components(m);
  int n_atoms = 0;
  for (std::int32_t a : m.atom) n_atoms = std::max(n_atoms, a + 1);
  char buf[160];
  std::string vert = "# MSMS-format skin surface vertices written by skinmesh for " + name + "\n";
  vert += "#vertex #sphere density probe_r\n";
  std::snprintf(buf, sizeof buf, "%7zu %6d %5.2f %5.2f\n", m.positions.size(), n_atoms, 0.0, 0.0);
  vert += buf;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const Vec3& p = m.positions[v];
    const Vec3 n = m.normals.empty() ? Vec3::Zero() : m.normals[v];
    const int atom = m.atom.empty() ? 0 : m.atom[v] + 1;
    std::snprintf(buf, sizeof buf, "%9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %7d %7d %2d\n", p.x(), p.y(), p.z(), n.x(),
                  n.y(), n.z(), component[v], atom, msms_type(m, v));
    vert += buf;
  }
  std::string face = "# MSMS-format skin surface triangles written by skinmesh for " + name + "\n";
  face += "#faces  #sphere density probe_r\n";
  std::snprintf(buf, sizeof buf, "%7zu %6d %5.2f %5.2f\n", m.triangles.size(), n_atoms, 0.0, 0.0);
  face += buf;
  for (const auto& t : m.triangles) {
    const int a = msms_type(m, t[0]), b = msms_type(m, t[1]), c = msms_type(m, t[2]);
    const int type = a == b && b == c ? a : (a == 0 || b == 0 || c == 0 ? 0 : 1);
    std::snprintf(buf, sizeof buf, "%6u %6u %6u %2d %6d\n", unsigned(t[0] + 1), unsigned(t[1] + 1), unsigned(t[2] + 1),
                  type, component[t[0]]);
    face += buf;
  }
  return {vert, face};
}

IndexedMesh read_msms(const std::string& vert_path, const std::string& vert, const std::string& face_path,
                      const std::string& face) {
  IndexedMesh mesh;
  const std::vector<std::string_view> vl = split_lines(vert);
  const std::size_t nv = msms_header(vert_path, vl, 0, "vertex");
  mesh.positions.reserve(nv);
  mesh.normals.reserve(nv);
  bool atoms = true;
  for (std::size_t i = 0; i < nv; ++i) {
    const int line = static_cast<int>(i + 4);
    const std::vector<std::string_view> f = split_blanks(vl[i + 3]);
    if (f.size() < 6)
      throw InputError(vert_path, line, "vertex " + std::to_string(i + 1) + " needs at least 6 numbers");
    double x[6];
    for (int k = 0; k < 6; ++k) x[k] = number_or_throw(vert_path, line, f[k], k < 3 ? "vertex coordinate" : "normal");
    mesh.positions.emplace_back(x[0], x[1], x[2]);
    mesh.normals.emplace_back(x[3], x[4], x[5]);
    if (f.size() >= 8) {
      const std::int64_t a = int_or_throw(vert_path, line, f[7], "atom index");
      if (a < 0 || a > 2147483647) throw InputError(vert_path, line, "atom index out of range");
      mesh.atom.push_back(static_cast<std::int32_t>(a - 1));
    } else {
      atoms = false;
    }
  }
  if (!atoms) mesh.atom.clear();
  const std::vector<std::string_view> fl = split_lines(face);
  const std::size_t nf = msms_header(face_path, fl, 0, "face");
  mesh.triangles.reserve(nf);
  for (std::size_t i = 0; i < nf; ++i) {
    const int line = static_cast<int>(i + 4);
    const std::vector<std::string_view> f = split_blanks(fl[i + 3]);
    if (f.size() < 3) throw InputError(face_path, line, "face " + std::to_string(i + 1) + " needs 3 vertex indices");
    std::array<Index, 3> t{};
    for (int k = 0; k < 3; ++k) {
      const std::int64_t v = int_or_throw(face_path, line, f[k], "vertex index");
      if (v < 1 || static_cast<std::uint64_t>(v) > nv)
        throw InputError(face_path, line,
                         "face " + std::to_string(i + 1) + ": vertex index " + std::to_string(v) +
                             " out of range (1.." + std::to_string(nv) + ")");
      t[k] = static_cast<Index>(v - 1);
    }
    mesh.triangles.push_back(t);
  }
  return mesh;
}

IndexedMesh read_msms_concatenated(const std::string& name, const std::string& data) {
  // The .vert part ends after its three header lines and its records.
  const std::vector<std::string_view> lines = split_lines(data);
  const std::size_t nv = msms_header(name, lines, 0, "vertex");
  const std::size_t face_line = 3 + nv;
  if (face_line >= lines.size())
    throw InputError(name, static_cast<int>(lines.size()), "no .face part after the vertices");
  const std::size_t offset = static_cast<std::size_t>(lines[face_line].data() - data.data());
  return read_msms(name, data.substr(0, offset), name, data.substr(offset));
}

}  // namespace skinmesh::geometry::mesh_io_detail
