// geometry/io/mesh_io_obj.cpp: the Wavefront OBJ format of mesh_io.h — the writer
// (`v`, `vn`, `f`) and the reader of `v`, `vn` and `f` statements (relative
// indices allowed, per-vertex normals kept when consistent). Declared in
// mesh_io_internal.h.
#include <algorithm>
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/errors.h"
#include "core/text_split.h"
#include "geometry/io/mesh_io_internal.h"

namespace skinmesh::geometry::mesh_io_detail {

void write_obj(const IndexedMesh& m, const MeshWriteOptions& opt, ChunkedWriter& w) {
  std::string& out = w.buffer();
  out += "# written by skinmesh\n";
  // One statement `<keyword> x y z`.
  auto vector_line = [&](const char* keyword, const Vec3& v) {
    out += keyword;
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      append_number(out, v[k], opt.double_precision);
    }
    out += '\n';
    w.spill();
  };
  for (const Vec3& p : m.positions) vector_line("v", p);
  for (const Vec3& n : m.normals) vector_line("vn", n);
  for (const auto& t : m.triangles) {
    out += 'f';
    for (Index v : t) {
      out += ' ';
      append_index(out, std::uint64_t{v} + 1);
      if (!m.normals.empty()) {
        out += "//";
        append_index(out, std::uint64_t{v} + 1);
      }
    }
    out += '\n';
    w.spill();
  }
}

IndexedMesh read_obj(const std::string& path, const std::string& data) {
  IndexedMesh mesh;
  std::vector<Vec3> vn;
  std::vector<std::array<std::int64_t, 3>> face_normals;  // per triangle corner, -1 if none
  std::vector<int> face_lines;
  const std::vector<std::string_view> lines = split_lines(data);

  // An OBJ index (1-based, or negative = relative to the end) to 0-based.
  auto resolve = [&](int line, std::string_view token, std::size_t count, const char* what) -> std::int64_t {
    const std::int64_t i = int_or_throw(path, line, token, what);
    const std::int64_t n = static_cast<std::int64_t>(count);
    const std::int64_t r = i > 0 ? i - 1 : n + i;
    if (i == 0 || r < 0 || r >= n)
      throw InputError(
          path, line,
          std::string(what) + " " + std::string(token) + " out of range (" + std::to_string(n) + " defined so far)");
    return r;
  };
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const int line = static_cast<int>(k + 1);
    const std::vector<std::string_view> f = fields_before_comment(lines[k]);
    if (f.empty()) continue;
    if (f[0] == "v" || f[0] == "vn") {
      if (f.size() < 4) throw InputError(path, line, "'" + std::string(f[0]) + "' needs 3 numbers");
      const Vec3 p(number_or_throw(path, line, f[1], "coordinate"), number_or_throw(path, line, f[2], "coordinate"),
                   number_or_throw(path, line, f[3], "coordinate"));
      (f[0] == "v" ? mesh.positions : vn).push_back(p);
    } else if (f[0] == "f") {
      if (f.size() != 4)
        throw InputError(path, line,
                         "face " + std::to_string(mesh.triangles.size()) + " has " + std::to_string(f.size() - 1) +
                             " vertices; only triangles are accepted");
      std::array<Index, 3> t{};
      std::array<std::int64_t, 3> nrm{-1, -1, -1};
      for (std::size_t c = 0; c < 3; ++c) {
        const std::string_view corner = f[c + 1];
        const std::size_t s1 = corner.find('/');
        t[c] = static_cast<Index>(resolve(line, corner.substr(0, s1), mesh.positions.size(), "vertex index"));
        if (s1 != std::string_view::npos) {
          const std::size_t s2 = corner.find('/', s1 + 1);
          if (s2 != std::string_view::npos && s2 + 1 < corner.size())
            nrm[c] = resolve(line, corner.substr(s2 + 1), vn.size(), "normal index");
        }
      }
      mesh.triangles.push_back(t);
      face_normals.push_back(nrm);
      face_lines.push_back(line);
    }
  }
  // Per-vertex normals if the corners give every vertex exactly one normal.
  if (!vn.empty() && !mesh.positions.empty()) {
    std::vector<Vec3> normals(mesh.positions.size());
    std::vector<bool> set(mesh.positions.size(), false);
    bool consistent = true;
    for (std::size_t i = 0; i < mesh.triangles.size() && consistent; ++i)
      for (std::size_t c = 0; c < 3; ++c) {
        const Index v = mesh.triangles[i][c];
        const std::int64_t n = face_normals[i][c];
        if (n < 0) {
          consistent = false;
          break;
        }
        const Vec3& value = vn[static_cast<std::size_t>(n)];
        if (set[v] && normals[v] != value) {
          consistent = false;
          break;
        }
        normals[v] = value;
        set[v] = true;
      }
    if (consistent && std::all_of(set.begin(), set.end(), [](bool b) { return b; })) mesh.normals = std::move(normals);
  }
  check_indices(path, mesh, face_lines);
  return mesh;
}

}  // namespace skinmesh::geometry::mesh_io_detail
