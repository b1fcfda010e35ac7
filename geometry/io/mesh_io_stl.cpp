// geometry/io/mesh_io_stl.cpp: the STL format of mesh_io.h (3D Systems'
// stereolithography format, as 3D printers and slicers read it) — the binary
// writer and the reader of binary and ascii files. STL stores each triangle
// with its own three corners (float32 in binary files): the reader merges
// corners with bit-identical coordinates into one vertex, in order of first
// appearance. Declared in mesh_io_internal.h.
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/errors.h"
#include "core/text_split.h"
#include "geometry/io/mesh_io_internal.h"

namespace skinmesh::geometry::mesh_io_detail {

namespace {

static_assert(std::endian::native == std::endian::little, "the STL writer assumes a little-endian machine");

void put_u32(std::string& out, std::uint32_t v) {
  char b[4];
  std::memcpy(b, &v, 4);
  out.append(b, 4);
}
void put_f32(std::string& out, double v) {
  const float f = static_cast<float>(v);
  char b[4];
  std::memcpy(b, &f, 4);
  out.append(b, 4);
}
std::uint32_t get_u32(const char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}
float get_f32(const char* p) {
  float v;
  std::memcpy(&v, p, 4);
  return v;
}

/// Merges triangle corners into shared vertices by their exact coordinates.
class CornerMerger {
 public:
  explicit CornerMerger(IndexedMesh& mesh) : mesh_(mesh) {}
  Index add(const Vec3& p) {
    const Key k{p.x(), p.y(), p.z()};
    auto [it, inserted] = index_.try_emplace(k, static_cast<Index>(mesh_.positions.size()));
    if (inserted) mesh_.positions.push_back(p);
    return it->second;
  }

 private:
  struct Key {
    double x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      // -0.0 == 0.0: hash the sum so that equal keys hash alike.
      const auto h = [](double v) { return std::hash<double>{}(v + 0.0); };
      return h(k.x) ^ (h(k.y) * 0x9e3779b97f4a7c15ULL) ^ (h(k.z) * 0xc2b2ae3d27d4eb4fULL);
    }
  };
  IndexedMesh& mesh_;
  std::unordered_map<Key, Index, Hash> index_;
};

IndexedMesh read_stl_binary(const std::string& path, const std::string& data) {
  const std::uint32_t n = get_u32(data.data() + 80);
  IndexedMesh mesh;
  mesh.triangles.reserve(n);
  CornerMerger merge(mesh);
  for (std::uint32_t i = 0; i < n; ++i) {
    const char* rec = data.data() + 84 + 50 * std::size_t(i);
    std::array<Index, 3> t{};
    for (int k = 0; k < 3; ++k) {
      const char* c = rec + 12 + 12 * k;
      const Vec3 p(get_f32(c), get_f32(c + 4), get_f32(c + 8));
      if (!p.allFinite()) throw InputError(path, 0, "triangle " + std::to_string(i) + ": non-finite corner coordinate");
      t[k] = merge.add(p);
    }
    mesh.triangles.push_back(t);
  }
  return mesh;
}

IndexedMesh read_stl_ascii(const std::string& path, const std::string& data) {
  IndexedMesh mesh;
  CornerMerger merge(mesh);
  const std::vector<std::string_view> lines = split_lines(data);
  std::array<Index, 3> t{};
  int corners = -1;  // -1: outside a facet; else corners read in this facet
  int facet_line = 0;
  bool in_solid = false;  // between 'solid' and 'endsolid' (a file may hold several solids)
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const int line = static_cast<int>(k + 1);
    const std::vector<std::string_view> f = split_blanks(lines[k]);
    if (f.empty()) continue;
    if (!in_solid) {
      if (f[0] != "solid") throw InputError(path, line, "expected 'solid', found '" + std::string(f[0]) + "'");
      in_solid = true;
      continue;
    }
    if (f[0] == "facet") {
      if (corners != -1) throw InputError(path, line, "'facet' inside a facet");
      corners = 0;
      facet_line = line;
    } else if (f[0] == "outer" || f[0] == "endloop") {
      if (corners == -1) throw InputError(path, line, "'" + std::string(f[0]) + "' outside a facet");
    } else if (f[0] == "vertex") {
      if (corners == -1) throw InputError(path, line, "'vertex' outside a facet");
      if (corners == 3) throw InputError(path, line, "a facet with more than 3 vertices; only triangles are accepted");
      if (f.size() != 4) throw InputError(path, line, "'vertex' needs 3 coordinates");
      Vec3 p;
      for (int c = 0; c < 3; ++c) p[c] = number_or_throw(path, line, f[c + 1], "vertex coordinate");
      t[corners++] = merge.add(p);
    } else if (f[0] == "endfacet") {
      if (corners != 3)
        throw InputError(
            path, line,
            "a facet with " + std::to_string(std::max(corners, 0)) + " vertices; only triangles are accepted");
      mesh.triangles.push_back(t);
      corners = -1;
    } else if (f[0] == "endsolid") {
      if (corners != -1)
        throw InputError(path, line, "'endsolid' inside the facet of line " + std::to_string(facet_line));
      in_solid = false;
    } else {
      throw InputError(path, line, "unknown ascii STL keyword '" + std::string(f[0]) + "'");
    }
  }
  if (corners != -1) throw InputError(path, facet_line, "unexpected end of file inside a facet");
  if (in_solid) throw InputError(path, static_cast<int>(lines.size()), "unexpected end of file (no 'endsolid')");
  return mesh;
}

}  // namespace

void write_stl(const IndexedMesh& m, const MeshWriteOptions& opt, ChunkedWriter& w) {
  std::string& out = w.buffer();
  auto facet_normal = [&m](const std::array<Index, 3>& t) {
    const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    const Vec3 n = (b - a).cross(c - a);
    return n.norm() > 0 ? Vec3(n.normalized()) : Vec3::Zero();
  };
  if (opt.ascii) {
    auto put = [&](const char* keyword, const Vec3& v) {
      out += keyword;
      for (int k = 0; k < 3; ++k) {
        out += ' ';
        append_number(out, v[k], opt.double_precision);
      }
      out += '\n';
    };
    out += "solid skinmesh\n";
    for (const auto& t : m.triangles) {
      put("facet normal", facet_normal(t));
      out += "outer loop\n";
      for (Index v : t) put("vertex", m.positions[v]);
      out += "endloop\nendfacet\n";
      w.spill();
    }
    out += "endsolid skinmesh\n";
    return;
  }
  std::string header = "binary STL written by skinmesh: " + std::to_string(m.triangles.size()) + " triangles";
  header.resize(80, ' ');
  out += header;
  put_u32(out, static_cast<std::uint32_t>(m.triangles.size()));
  for (const auto& t : m.triangles) {
    const Vec3 n = facet_normal(t);
    for (int k = 0; k < 3; ++k) put_f32(out, n[k]);
    for (Index v : t)
      for (int k = 0; k < 3; ++k) put_f32(out, m.positions[v][k]);
    out.append(2, '\0');  // attribute byte count
    w.spill();
  }
}

IndexedMesh read_stl(const std::string& path, const std::string& data) {
  // Binary files may begin with "solid" too: the size decides.
  if (data.size() >= 84) {
    const std::uint64_t n = get_u32(data.data() + 80);
    if (data.size() == 84 + 50 * n) return read_stl_binary(path, data);
  }
  if (std::string_view(data).substr(0, 5) == "solid") return read_stl_ascii(path, data);
  if (data.size() < 84) throw InputError(path, 0, "not an STL file (shorter than a binary STL header)");
  throw InputError(path, 0,
                   "binary STL of " + std::to_string(data.size()) + " bytes, but its header announces " +
                       std::to_string(get_u32(data.data() + 80)) + " triangles (" +
                       std::to_string(84 + 50 * std::uint64_t(get_u32(data.data() + 80))) + " bytes)");
}

}  // namespace skinmesh::geometry::mesh_io_detail
