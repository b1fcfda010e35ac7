// skin/skin_mesh_io.cpp: the files of a mesh of the skin (skin_mesh_io.h) —
// the skin's vertex data as attributes of the geometric formats, and the MSMS
// format, which electrostatics solvers and surface-learning pipelines read: a
// pair of text files NAME.vert and NAME.face.
//   NAME.vert: three header lines ("# ...", "#vertex #sphere density probe_r",
//     then the counts: vertices, atoms — the largest atom index of a vertex
//     plus one, as the mesh does not know atoms without vertices —, the
//     density in vertices per Å² of mesh area and the probe radius in Å, as
//     MSMS's -density and -probe_radius), then per vertex
//     "%9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %7d %7d %2d": position (Å), unit
//     normal, the number of its surface component (1-based), the 1-based index
//     of its atom, and the MSMS type of its patch.
//   NAME.face: three header lines, then per triangle "%6d %6d %6d %2d %6d":
//     1-based vertex indices, the type, the component.
// MSMS types are 1 (toric reentrant, saddle-shaped), 2 (spheric reentrant,
// concave), 3 (contact, convex). On the skin: a sphere patch of an atom's
// vertex cell is 3, the concave sphere patch of a tetrahedron cell 2, the
// hyperboloid patches of edge and triangle cells 1 (SkinVertexData::patch); a
// triangle has the type its corners share, 1 when they differ. Positions have
// three decimals, as MSMS writes them, or more if asked (every MSMS reader we
// know splits records at blanks; the field then widens by a digit per
// decimal); normals keep three.
#include "skin/skin_mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/assert.h"
#include "core/errors.h"
#include "core/read_file.h"
#include "core/text_numbers.h"
#include "core/text_split.h"
#include "geometry/mesh/mesh_measures.h"

namespace skinmesh::skin {

using geometry::IndexedMesh;
using geometry::VertexAttribute;

namespace {

/// MSMS type of vertex `v` from the dimension of its mixed cell (0..3); 0 if unknown.
int msms_type(const SkinVertexData& data, std::size_t v) {
  if (data.patch.empty()) return 0;
  switch (data.patch[v]) {
    case 0:
      return 3;
    case 3:
      return 2;
    default:
      return 1;
  }
}

/// The records of an MSMS file written without its header (MSMS's
/// -no_header: the first line does not begin with '#'): their number, every
/// line up to the last one that is not blank.
std::size_t headerless_count(const std::vector<std::string_view>& lines) {
  std::size_t n = lines.size();
  while (n > 0 && trim(lines[n - 1]).empty()) --n;
  return n;
}

/// The first record line of an MSMS file: 3 after its header, 0 without one.
std::size_t msms_first_record(const std::vector<std::string_view>& lines) {
  return !lines.empty() && !trim(lines[0]).starts_with("#") ? 0 : 3;
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

/// The header line of counts of an MSMS file: `count` records, `n_atoms`,
/// the density (vertices per Å² of mesh area, 0 for no area) and the probe
/// radius (Å).
std::string msms_counts(std::size_t count, int n_atoms, double density, double probe) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%7zu %6d %5.2f %5.2f\n", count, n_atoms, density, probe);
  return buf;
}

/// Writes the MSMS .vert file of `m` with its vertex data into `w`; `name`
/// goes into the comment lines, `component` is vertex_components(m), `counts`
/// msms_counts(); positions with `decimals` digits after the point; each
/// vertex's atom name from `atom_names` (indexed by atom) if not empty; without
/// the three header lines unless `header` (MSMS's -no_header).
void write_msms_vert(const IndexedMesh& m, const SkinVertexData& data, const std::string& name,
                     const std::vector<int>& component, const std::string& counts, int decimals,
                     const std::vector<std::string>& atom_names, bool header, geometry::ChunkedWriter& w) {
  char buf[256];
  std::string& vert = w.buffer();
  if (header) {
    vert += "# MSMS-format skin surface vertices written by skinmesh for " + name + "\n";
    vert += "#vertex #sphere density probe_r\n";
    vert += counts;
  }
  const int width = 6 + decimals;  // 9 at MSMS's three decimals
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const Vec3& p = m.positions[v];
    const Vec3 n = m.normals.empty() ? Vec3::Zero() : m.normals[v];
    const int atom = data.atom.empty() ? 0 : data.atom[v] + 1;
    std::snprintf(buf, sizeof buf, "%*.*f %*.*f %*.*f %9.3f %9.3f %9.3f %7d %7d %2d", width, decimals, p.x(), width,
                  decimals, p.y(), width, decimals, p.z(), n.x(), n.y(), n.z(), component[v], atom, msms_type(data, v));
    vert += buf;
    if (!atom_names.empty()) {
      vert += ' ';
      vert += atom >= 1 && static_cast<std::size_t>(atom) <= atom_names.size() ? atom_names[atom - 1] : "x_0_x_UNK_X";
    }
    vert += '\n';
    w.spill();
  }
}

/// Writes the MSMS .face file of `m` into `w` (as write_msms_vert()).
void write_msms_face(const IndexedMesh& m, const SkinVertexData& data, const std::string& name,
                     const std::vector<int>& component, const std::string& counts, bool header,
                     geometry::ChunkedWriter& w) {
  char buf[160];
  std::string& face = w.buffer();
  if (header) {
    face += "# MSMS-format skin surface triangles written by skinmesh for " + name + "\n";
    face += "#faces  #sphere density probe_r\n";
    face += counts;
  }
  for (const auto& t : m.triangles) {
    const int a = msms_type(data, t[0]), b = msms_type(data, t[1]), c = msms_type(data, t[2]);
    const int type = a == b && b == c ? a : (a == 0 || b == 0 || c == 0 ? 0 : 1);
    std::snprintf(buf, sizeof buf, "%6u %6u %6u %2d %6d\n", unsigned(t[0] + 1), unsigned(t[1] + 1), unsigned(t[2] + 1),
                  type, component[t[0]]);
    face += buf;
    w.spill();
  }
}

/// Reads the MSMS .vert and .face files (their paths for messages); the atoms
/// into `atom` (0-based; empty unless every vertex record has one).
IndexedMesh read_msms(const std::string& vert_path, const std::string& vert, const std::string& face_path,
                      const std::string& face, std::vector<std::int32_t>& atom) {
  IndexedMesh mesh;
  atom.clear();
  // With its three header lines, as MSMS writes by default, or without (-no_header).
  const std::vector<std::string_view> vl = split_lines(vert);
  const std::size_t v0 = msms_first_record(vl);
  const std::size_t nv = v0 == 0 ? headerless_count(vl) : msms_header(vert_path, vl, 0, "vertex");
  mesh.positions.reserve(nv);
  mesh.normals.reserve(nv);
  bool atoms = true;
  for (std::size_t i = 0; i < nv; ++i) {
    const int line = static_cast<int>(i + v0 + 1);
    const std::vector<std::string_view> f = split_blanks(vl[i + v0]);
    if (f.size() < 6)
      throw InputError(vert_path, line, "vertex " + std::to_string(i + 1) + " needs at least 6 numbers");
    double x[6];
    for (int k = 0; k < 6; ++k) x[k] = number_or_throw(vert_path, line, f[k], k < 3 ? "vertex coordinate" : "normal");
    mesh.positions.emplace_back(x[0], x[1], x[2]);
    mesh.normals.emplace_back(x[3], x[4], x[5]);
    if (f.size() >= 8) {
      const std::int64_t a = int_or_throw(vert_path, line, f[7], "atom index");
      if (a < 0 || a > 2147483647) throw InputError(vert_path, line, "atom index out of range");
      atom.push_back(static_cast<std::int32_t>(a - 1));
    } else {
      atoms = false;
    }
  }
  if (!atoms) atom.clear();
  const std::vector<std::string_view> fl = split_lines(face);
  const std::size_t f0 = msms_first_record(fl);
  const std::size_t nf = f0 == 0 ? headerless_count(fl) : msms_header(face_path, fl, 0, "face");
  mesh.triangles.reserve(nf);
  for (std::size_t i = 0; i < nf; ++i) {
    const int line = static_cast<int>(i + f0 + 1);
    const std::vector<std::string_view> f = split_blanks(fl[i + f0]);
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

}  // namespace

IndexedMesh read_msms_from_bytes(const std::string& data, const std::string& name, SkinVertexData* vertex_data) {
  // With headers, the .vert part ends after its three header lines and the
  // count of records they give; without (-no_header), at the first line of
  // fewer than 6 fields: a vertex record has at least 6 numbers, an MSMS face
  // record 5 (or 3, from tools that write the indices alone).
  const std::vector<std::string_view> lines = split_lines(data);
  std::size_t face_line = 0;
  if (msms_first_record(lines) == 0) {
    while (face_line < lines.size() && split_blanks(lines[face_line]).size() >= 6) ++face_line;
  } else {
    face_line = 3 + msms_header(name, lines, 0, "vertex");
  }
  if (face_line >= lines.size())
    throw InputError(name, static_cast<int>(lines.size()), "no .face part after the vertices");
  const std::size_t offset = static_cast<std::size_t>(lines[face_line].data() - data.data());
  std::vector<std::int32_t> atom;
  IndexedMesh mesh = read_msms(name, data.substr(0, offset), name, data.substr(offset), atom);
  if (vertex_data != nullptr) *vertex_data = SkinVertexData{std::move(atom), {}, {}};
  return mesh;
}

namespace {

/// `data`'s vertex data read from the file attributes of `path`: `atom` (an
/// integer attribute, every value >= -1) and `rho`. Throws InputError(path, 0, ...).
SkinVertexData vertex_data_of(const std::string& path, const std::vector<VertexAttribute>& attributes) {
  SkinVertexData data;
  if (const VertexAttribute* atom = geometry::find_attribute(attributes, "atom")) {
    if (!atom->integer) throw InputError(path, 0, "vertex attribute 'atom' must have an integer type");
    data.atom.reserve(atom->values.size());
    for (double a : atom->values) {
      if (a < -1)
        throw InputError(path, 0, "atom index " + std::to_string(static_cast<long long>(a)) + " (expected >= -1)");
      data.atom.push_back(static_cast<std::int32_t>(a));
    }
  }
  if (const VertexAttribute* rho = geometry::find_attribute(attributes, "rho")) data.rho = rho->values;
  return data;
}

}  // namespace

bool is_msms_path(const std::string& path) {
  const std::string p = lowercase(path);
  return p.ends_with(".vert") || p.ends_with(".face");
}

std::pair<std::string, std::string> msms_paths(const std::string& path) {
  if (!is_msms_path(path)) throw InputError(path, 0, "an MSMS mesh is named NAME.vert or NAME.face");
  const std::string base = path.substr(0, path.size() - 5);
  return {base + ".vert", base + ".face"};
}

void require_mesh_format(const std::string& path) {
  if (!is_msms_path(path) && !geometry::mesh_format_of(path))
    throw InputError(
        path, 0, "unknown mesh format (expected .ply, .off, .obj, .stl, .vtk, .vtp, .vtu, or .vert/.face for MSMS)");
}

std::vector<VertexAttribute> file_attributes(const SkinVertexData& data, geometry::MeshFormat format) {
  std::vector<VertexAttribute> out;
  const bool vtk =
      format == geometry::MeshFormat::Vtk || format == geometry::MeshFormat::Vtp || format == geometry::MeshFormat::Vtu;
  if (format != geometry::MeshFormat::Ply && !vtk) return out;
  if (!data.atom.empty()) out.push_back({"atom", true, std::vector<double>(data.atom.begin(), data.atom.end())});
  if (vtk && !data.rho.empty()) out.push_back({"rho", false, data.rho});
  return out;
}

std::string msms_atom_name(const Atom& atom) {
  if (!atom.msms_name.empty()) return atom.msms_name;  // an .xyzrn name, passed through as MSMS does
  auto part = [](const std::string& text, const char* blank) {
    std::string out;
    for (char c : text) out += std::isspace(static_cast<unsigned char>(c)) ? '-' : c;
    const std::size_t first = out.find_first_not_of('-'), last = out.find_last_not_of('-');
    return first == std::string::npos ? std::string(blank) : out.substr(first, last - first + 1);
  };
  const char icode[2] = {atom.insertion_code, '\0'};
  return part(atom.chain, "x") + "_" + std::to_string(atom.residue_number) + "_" + part(icode, "x") + "_" +
         part(atom.residue, "UNK") + "_" + part(atom.name, "X");
}

geometry::PositionStorage position_storage(const std::string& path, const SkinMeshWriteOptions& opt) {
  if (is_msms_path(path)) return {geometry::PositionStorage::Kind::Decimals, opt.msms_decimals};
  return geometry::position_storage(geometry::mesh_format_from_extension(path), opt.geometry);
}

void write_skin_mesh(const std::string& path, const IndexedMesh& mesh, const SkinVertexData& data,
                     const SkinMeshWriteOptions& opt) {
  require_mesh_format(path);
  const std::size_t n = mesh.positions.size();
  SKINMESH_ASSERT_MSG(data.atom.empty() || data.atom.size() == n, "one atom id per vertex");
  SKINMESH_ASSERT_MSG(data.rho.empty() || data.rho.size() == n, "one rho per vertex");
  SKINMESH_ASSERT_MSG(data.patch.empty() || data.patch.size() == n, "one patch dimension per vertex");
  if (!is_msms_path(path)) {
    const geometry::MeshFormat format = geometry::mesh_format_from_extension(path);
    geometry::write_mesh(path, mesh, opt.geometry, file_attributes(data, format));
    return;
  }
  geometry::check_writable(mesh);
  if (opt.msms_decimals < kMinMsmsDecimals || opt.msms_decimals > kMaxMsmsDecimals)
    throw std::invalid_argument("MSMS decimals must lie in [" + std::to_string(kMinMsmsDecimals) + ", " +
                                std::to_string(kMaxMsmsDecimals) + "]");
  const auto [vert_path, face_path] = msms_paths(path);
  const std::string name = vert_path.substr(vert_path.find_last_of('/') + 1);
  const std::string stem = name.substr(0, name.size() - 5);
  const std::vector<int> component = vertex_components(mesh);
  int n_atoms = 0;
  for (std::int32_t a : data.atom) n_atoms = std::max(n_atoms, a + 1);
  double area = 0;
  for (const geometry::ComponentMeasure& c : geometry::component_measures(mesh, component)) area += c.area;
  const double density = area > 0 ? mesh.positions.size() / area : 0;
  using geometry::ChunkedWriter;
  using geometry::FileProducer;
  // The .face first, then the .vert: a reader polling for the .vert finds the pair complete.
  if (!opt.msms_split_components) {
    const std::string vert_counts = msms_counts(mesh.positions.size(), n_atoms, density, opt.probe_radius);
    const std::string face_counts = msms_counts(mesh.triangles.size(), n_atoms, density, opt.probe_radius);
    geometry::write_files_atomically(
        {{face_path,
          [&](ChunkedWriter& w) { write_msms_face(mesh, data, stem, component, face_counts, opt.msms_header, w); }},
         {vert_path,
          [&](ChunkedWriter& w) {
            write_msms_vert(mesh, data, stem, component, vert_counts, opt.msms_decimals, opt.msms_atom_names,
                            opt.msms_header, w);
          }}},
        "mesh");
    return;
  }
  // One pair per component (MSMS's -all_components): the first NAME.vert/.face,
  // component k >= 2 NAME_{k-1}.vert/.face, each with its own vertex numbers.
  const int components = component.empty() ? 0 : *std::max_element(component.begin(), component.end());
  struct Part {
    IndexedMesh mesh;
    SkinVertexData data;
    std::vector<int> component;
    std::string vert_path, face_path, stem;
  };
  std::vector<Part> parts(static_cast<std::size_t>(components));
  std::vector<Index> local(mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    if (component[v] == 0) continue;  // in no triangle, so in no component: no part writes it
    Part& part = parts[static_cast<std::size_t>(component[v] - 1)];
    local[v] = static_cast<Index>(part.mesh.positions.size());
    part.mesh.positions.push_back(mesh.positions[v]);
    if (!mesh.normals.empty()) part.mesh.normals.push_back(mesh.normals[v]);
    if (!data.atom.empty()) part.data.atom.push_back(data.atom[v]);
    if (!data.patch.empty()) part.data.patch.push_back(data.patch[v]);
    part.component.push_back(component[v]);
  }
  for (const auto& t : mesh.triangles)
    parts[static_cast<std::size_t>(component[t[0]] - 1)].mesh.triangles.push_back(
        {local[t[0]], local[t[1]], local[t[2]]});
  const std::string base = vert_path.substr(0, vert_path.size() - 5);
  std::vector<std::pair<std::string, FileProducer>> files;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    Part& part = parts[k];
    std::string suffix;  // built by appends: GCC 12 warns falsely (-Wrestrict) on "_" + std::to_string(k)
    if (k > 0) suffix.append(1, '_').append(std::to_string(k));
    part.vert_path = base + suffix + ".vert";
    part.face_path = base + suffix + ".face";
    part.stem = stem + suffix;
    files.emplace_back(part.face_path, [&part, &opt, n_atoms, density](ChunkedWriter& w) {
      write_msms_face(part.mesh, part.data, part.stem, part.component,
                      msms_counts(part.mesh.triangles.size(), n_atoms, density, opt.probe_radius), opt.msms_header, w);
    });
    files.emplace_back(part.vert_path, [&part, &opt, n_atoms, density](ChunkedWriter& w) {
      write_msms_vert(part.mesh, part.data, part.stem, part.component,
                      msms_counts(part.mesh.positions.size(), n_atoms, density, opt.probe_radius), opt.msms_decimals,
                      opt.msms_atom_names, opt.msms_header, w);
    });
  }
  geometry::write_files_atomically(files, "mesh");
}

IndexedMesh read_skin_mesh(const std::string& path, SkinVertexData* data) {
  if (is_msms_path(path)) {
    const auto [vert_path, face_path] = msms_paths(path);
    const std::string vert = read_file(vert_path);  // the .vert first: errors name it first
    std::vector<std::int32_t> atom;
    IndexedMesh mesh = read_msms(vert_path, vert, face_path, read_file(face_path), atom);
    if (data != nullptr) *data = SkinVertexData{std::move(atom), {}, {}};
    return mesh;
  }
  std::vector<VertexAttribute> attributes;
  IndexedMesh mesh = geometry::read_mesh(path, &attributes);
  SkinVertexData read = vertex_data_of(path, attributes);
  if (data != nullptr) *data = std::move(read);
  return mesh;
}

double position_rounding(const std::string& path, const IndexedMesh& mesh) {
  constexpr double kMsmsRounding = 1e-3;  // Å; [derived] three decimals move a vertex by at most 0.87e-3
  if (is_msms_path(path)) return kMsmsRounding;
  const geometry::MeshFormat format = geometry::mesh_format_from_extension(path);
  // A file of float32 coordinates (a PLY `float`, or text another tool wrote
  // from floats) holds only floats or their shortest text; a mesh of exact
  // doubles off the skin's surface all but never does.
  if (geometry::float32_coordinates(mesh))
    return std::max(geometry::position_rounding(format, mesh),
                    2 * geometry::PositionStorage{geometry::PositionStorage::Kind::Float32Text, 0}.max_error(mesh));
  return geometry::position_rounding(format, mesh);
}

}  // namespace skinmesh::skin
