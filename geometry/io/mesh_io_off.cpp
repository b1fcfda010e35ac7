// geometry/io/mesh_io_off.cpp: the OFF format of mesh_io.h (Geomview) — the OFF /
// NOFF writer and the reader of ascii [ST][C][N]OFF files (colours and texture
// coordinates ignored). Declared in mesh_io_internal.h.
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/errors.h"
#include "core/text_split.h"
#include "geometry/io/mesh_io_internal.h"

namespace skinmesh::geometry::mesh_io_detail {

void write_off(const IndexedMesh& m, const MeshWriteOptions& opt, ChunkedWriter& w) {
  std::string& out = w.buffer();
  const bool normals = opt.off_normals && !m.normals.empty();
  out += normals ? "NOFF\n" : "OFF\n";
  out += std::to_string(m.positions.size()) + " " + std::to_string(m.triangles.size()) + " 0\n";
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (k > 0) out += ' ';
      append_number(out, m.positions[i][k], opt.double_precision);
    }
    if (normals)
      for (int k = 0; k < 3; ++k) {
        out += ' ';
        append_number(out, m.normals[i][k], opt.double_precision);
      }
    out += '\n';
    w.spill();
  }
  append_triangle_lines(w, m.triangles);
}

IndexedMesh read_off(const std::string& path, const std::string& data) {
  // Records: non-empty lines with comments removed, with their line numbers.
  struct Record {
    int line;
    std::vector<std::string_view> fields;
  };
  std::vector<Record> records;
  const std::vector<std::string_view> lines = split_lines(data);
  for (std::size_t k = 0; k < lines.size(); ++k) {
    std::vector<std::string_view> f = fields_before_comment(lines[k]);
    if (!f.empty()) records.push_back({static_cast<int>(k + 1), std::move(f)});
  }
  if (records.empty()) throw InputError(path, 0, "empty OFF file");

  // Header keyword [ST][C][N]OFF, counts on the same line or the next.
  const Record& head = records[0];
  std::string_view key = head.fields[0];
  bool normals = false, colours = false;
  if (key.starts_with("ST")) key.remove_prefix(2);
  if (key.starts_with("C")) {
    colours = true;
    key.remove_prefix(1);
  }
  if (key.starts_with("N")) {
    normals = true;
    key.remove_prefix(1);
  }
  if (key != "OFF")
    throw InputError(path, head.line,
                     "not an OFF file (header '" + std::string(head.fields[0]) + "'; expected OFF, NOFF, COFF, STOFF)");
  (void)colours;  // colours follow the coordinates and are ignored
  std::size_t r = 1;
  std::vector<std::string_view> counts(head.fields.begin() + 1, head.fields.end());
  int counts_line = head.line;
  if (counts.empty()) {
    if (r >= records.size()) throw InputError(path, head.line, "OFF file without vertex and face counts");
    counts = records[r].fields;
    counts_line = records[r].line;
    ++r;
  }
  if (counts.size() < 2) throw InputError(path, counts_line, "OFF counts line needs 'vertices faces [edges]'");
  if (counts[0] == "BINARY") throw InputError(path, counts_line, "binary OFF is not supported");
  const std::int64_t nv = int_or_throw(path, counts_line, counts[0], "vertex count");
  const std::int64_t nf = int_or_throw(path, counts_line, counts[1], "face count");
  if (nv < 0 || nf < 0) throw InputError(path, counts_line, "negative OFF count");
  const std::size_t left = records.size() - r;  // nv + nf could overflow: compare one at a time
  if (static_cast<std::uint64_t>(nv) > left || static_cast<std::uint64_t>(nf) > left - static_cast<std::size_t>(nv))
    throw InputError(
        path, records.back().line,
        "unexpected end of file: expected " + std::to_string(nv) + " vertices and " + std::to_string(nf) + " faces");

  IndexedMesh mesh;
  mesh.positions.reserve(static_cast<std::size_t>(nv));
  if (normals) mesh.normals.reserve(static_cast<std::size_t>(nv));
  const std::size_t need = normals ? 6 : 3;
  for (std::int64_t i = 0; i < nv; ++i, ++r) {
    const Record& rec = records[r];
    if (rec.fields.size() < need)
      throw InputError(path, rec.line, "vertex " + std::to_string(i) + " needs " + std::to_string(need) + " numbers");
    std::array<double, 6> v{};
    for (std::size_t k = 0; k < need; ++k) v[k] = number_or_throw(path, rec.line, rec.fields[k], "vertex coordinate");
    mesh.positions.emplace_back(v[0], v[1], v[2]);
    if (normals) mesh.normals.emplace_back(v[3], v[4], v[5]);
  }
  mesh.triangles.reserve(static_cast<std::size_t>(nf));
  for (std::int64_t i = 0; i < nf; ++i, ++r) {
    const Record& rec = records[r];
    const std::int64_t n = int_or_throw(path, rec.line, rec.fields[0], "face vertex count");
    if (n != 3)
      throw InputError(
          path, rec.line,
          "face " + std::to_string(i) + " has " + std::to_string(n) + " vertices; only triangles are accepted");
    if (rec.fields.size() < 4)
      throw InputError(path, rec.line, "face " + std::to_string(i) + " lists fewer than 3 indices");
    std::array<Index, 3> t{};
    for (std::size_t k = 0; k < 3; ++k) {
      const std::int64_t v = int_or_throw(path, rec.line, rec.fields[k + 1], "vertex index");
      if (v < 0 || v >= nv)
        throw InputError(path, rec.line,
                         "face " + std::to_string(i) + ": vertex index " + std::to_string(v) + " out of range (" +
                             std::to_string(nv) + " vertices)");
      t[k] = static_cast<Index>(v);
    }
    mesh.triangles.push_back(t);
  }
  return mesh;
}

}  // namespace skinmesh::geometry::mesh_io_detail
