// geometry/io/mesh_io_vtk.cpp: the legacy VTK format of mesh_io.h (Kitware, "VTK
// File Formats", the simple legacy format that ParaView and VTK read) — the
// ascii POLYDATA writer, with per-vertex normals and scalar attributes and
// per-triangle smallest angle, and the reader of ascii POLYDATA files. Numbers are written as the shortest text that
// reads back to the same double, so a round trip is exact. Declared in mesh_io_internal.h.
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/errors.h"
#include "core/text_split.h"
#include "geometry/io/mesh_io_internal.h"
#include "geometry/kernel/angles.h"

namespace skinmesh::geometry::mesh_io_detail {

namespace {

/// The white-space separated tokens of the file after its three header lines,
/// each with its line number.
class Tokens {
 public:
  Tokens(const std::string& path, const std::vector<std::string_view>& lines, std::size_t first) : path_(path) {
    for (std::size_t k = first; k < lines.size(); ++k)
      for (std::string_view t : split_blanks(lines[k])) tokens_.push_back({t, static_cast<int>(k + 1)});
  }
  bool done() const { return i_ >= tokens_.size(); }
  int line() const { return tokens_.empty() ? 0 : tokens_[i_ < tokens_.size() ? i_ : tokens_.size() - 1].line; }
  std::string_view next(const char* what) {
    if (done()) throw InputError(path_, line(), std::string("unexpected end of file: expected ") + what);
    last_line_ = tokens_[i_].line;
    return tokens_[i_++].text;
  }
  /// The line of the token next() returned last.
  int last_line() const { return last_line_; }
  std::string_view peek() const { return done() ? std::string_view() : tokens_[i_].text; }
  double number(const char* what) {
    const int l = done() ? line() : tokens_[i_].line;
    return number_or_throw(path_, l, next(what), what);
  }
  std::int64_t integer(const char* what) {
    const int l = done() ? line() : tokens_[i_].line;
    return int_or_throw(path_, l, next(what), what);
  }
  std::size_t count(const char* what) {
    const int l = done() ? line() : tokens_[i_].line;
    const std::int64_t n = integer(what);
    if (n < 0) throw InputError(path_, l, std::string("negative ") + what);
    // Every counted item takes at least one token: a larger count is a
    // truncated file (and no allocation is made for it).
    if (static_cast<std::uint64_t>(n) > tokens_.size() - i_)
      throw InputError(path_, l, std::string(what) + " " + std::to_string(n) + " exceeds what the file holds");
    return static_cast<std::size_t>(n);
  }

 private:
  struct Token {
    std::string_view text;
    int line;
  };
  const std::string& path_;
  std::vector<Token> tokens_;
  std::size_t i_ = 0;
  int last_line_ = 0;
};

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  return out;
}

/// True for the legacy VTK data types of integers (upper-case `type`).
bool is_integer_type(std::string_view type) {
  for (std::string_view t : {"BIT", "CHAR", "UNSIGNED_CHAR", "SHORT", "UNSIGNED_SHORT", "INT", "UNSIGNED_INT", "LONG",
                             "UNSIGNED_LONG", "VTKIDTYPE"})
    if (type == t) return true;
  return false;
}

}  // namespace

void write_vtk(const IndexedMesh& m, const std::vector<VertexAttribute>& attributes, const MeshWriteOptions& opt,
               ChunkedWriter& w) {
  const bool dp = opt.double_precision;
  const char* type = dp ? "double" : "float";
  std::string& out = w.buffer();
  out += "# vtk DataFile Version 3.0\nskinmesh: a triangulated skin surface\nASCII\nDATASET POLYDATA\n";
  out += "POINTS " + std::to_string(m.positions.size()) + " " + type + "\n";
  for (const Vec3& p : m.positions) {
    for (int k = 0; k < 3; ++k) {
      if (k > 0) out += ' ';
      append_number(out, p[k], dp);
    }
    out += '\n';
    w.spill();
  }
  out += "POLYGONS " + std::to_string(m.triangles.size()) + " " + std::to_string(4 * m.triangles.size()) + "\n";
  append_triangle_lines(w, m.triangles);
  if (!m.normals.empty() || !attributes.empty()) {
    out += "POINT_DATA " + std::to_string(m.positions.size()) + "\n";
    if (!m.normals.empty()) {
      out += std::string("NORMALS normals ") + type + "\n";
      for (const Vec3& n : m.normals) {
        for (int k = 0; k < 3; ++k) {
          if (k > 0) out += ' ';
          append_number(out, n[k], dp);
        }
        out += '\n';
        w.spill();
      }
    }
    for (const VertexAttribute& a : attributes) {
      out += "SCALARS " + a.name + " " + (a.integer ? "int" : type) + " 1\nLOOKUP_TABLE default\n";
      for (double v : a.values) {
        if (a.integer)
          out += std::to_string(static_cast<std::int32_t>(v));
        else
          append_number(out, v, dp);
        out += '\n';
        w.spill();
      }
    }
  }
  if (!m.triangles.empty()) {
    out += "CELL_DATA " + std::to_string(m.triangles.size()) + "\nSCALARS min_angle double 1\nLOOKUP_TABLE default\n";
    for (const auto& t : m.triangles) {
      append_number(out, min_angle(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]) * 180 / kPi, dp);
      out += '\n';
      w.spill();
    }
  }
}

IndexedMesh read_vtk(const std::string& path, const std::string& data, std::vector<VertexAttribute>& attributes) {
  const std::vector<std::string_view> lines = split_lines(data);
  if (lines.empty() || !trim(lines[0]).starts_with("# vtk DataFile Version"))
    throw InputError(path, 1, "not a legacy VTK file (the first line must be '# vtk DataFile Version x.x')");
  if (lines.size() < 3) throw InputError(path, static_cast<int>(lines.size()), "unexpected end of the VTK header");
  const std::string format = upper(trim(lines[2]));
  if (format == "BINARY") throw InputError(path, 3, "binary VTK is not supported (write it as ASCII)");
  if (format != "ASCII")
    throw InputError(path, 3, "expected ASCII or BINARY, found '" + std::string(trim(lines[2])) + "'");
  Tokens tok(path, lines, 3);
  if (upper(tok.next("DATASET")) != "DATASET") throw InputError(path, tok.last_line(), "expected DATASET");
  const std::string kind = upper(tok.next("the dataset type"));
  if (kind != "POLYDATA")
    throw InputError(path, tok.last_line(), "dataset " + kind + " is not supported (only POLYDATA with triangles)");
  IndexedMesh mesh;
  bool have_points = false;
  std::size_t n_points = 0;
  // Sections: POINTS, VERTICES / LINES (skipped), POLYGONS, POINT_DATA, CELL_DATA.
  enum class Data { None, Point, Cell } data_kind = Data::None;
  std::size_t data_count = 0;
  while (!tok.done()) {
    const int line = tok.line();
    const std::string key = upper(tok.next("a section"));
    if (key == "POINTS") {
      if (have_points) throw InputError(path, line, "a second POINTS section");
      n_points = tok.count("point count");
      tok.next("the point type");
      mesh.positions.resize(n_points);
      for (Vec3& p : mesh.positions)
        for (int k = 0; k < 3; ++k) p[k] = tok.number("point coordinate");
      have_points = true;
    } else if (key == "POLYGONS" || key == "VERTICES" || key == "LINES" || key == "TRIANGLE_STRIPS") {
      if (key == "TRIANGLE_STRIPS") throw InputError(path, line, "TRIANGLE_STRIPS are not supported");
      const std::size_t n = tok.count("cell count");
      tok.integer("cell list size");
      if (key == "POLYGONS") mesh.triangles.reserve(n);
      for (std::size_t i = 0; i < n; ++i) {
        const int cl = tok.line();
        const std::int64_t size = tok.integer("cell size");
        if (key == "POLYGONS" && size != 3)
          throw InputError(path, cl,
                           "polygon " + std::to_string(i) + " has " + std::to_string(size) +
                               " vertices; only triangles are accepted");
        if (size < 0 || static_cast<std::uint64_t>(size) > 1u << 20) throw InputError(path, cl, "bad cell size");
        std::array<Index, 3> t{};
        for (std::int64_t k = 0; k < size; ++k) {
          const std::int64_t v = tok.integer("vertex index");
          if (!have_points || v < 0 || static_cast<std::uint64_t>(v) >= n_points)
            throw InputError(path, cl,
                             "cell " + std::to_string(i) + ": vertex index " + std::to_string(v) + " out of range (" +
                                 std::to_string(n_points) + " points)");
          if (key == "POLYGONS") t[k] = static_cast<Index>(v);
        }
        if (key == "POLYGONS") mesh.triangles.push_back(t);
      }
    } else if (key == "POINT_DATA" || key == "CELL_DATA") {
      data_kind = key == "POINT_DATA" ? Data::Point : Data::Cell;
      data_count = tok.count("data count");
      if (data_kind == Data::Point && data_count != n_points)
        throw InputError(path, line,
                         "POINT_DATA " + std::to_string(data_count) + " for " + std::to_string(n_points) + " points");
    } else if (key == "NORMALS" || key == "SCALARS") {
      if (data_kind == Data::None) throw InputError(path, line, key + " outside POINT_DATA or CELL_DATA");
      const std::string name(tok.next("the attribute name"));
      const bool integer_type = is_integer_type(upper(tok.next("the attribute type")));
      std::int64_t components = 3;
      if (key == "SCALARS") {
        components = 1;
        if (upper(tok.peek()) != "LOOKUP_TABLE") components = tok.integer("number of components");
        if (components < 1 || components > 4)
          throw InputError(path, line, "SCALARS with " + std::to_string(components) + " components");
        if (upper(tok.next("LOOKUP_TABLE")) != "LOOKUP_TABLE")
          throw InputError(path, tok.last_line(), "expected LOOKUP_TABLE");
        tok.next("the lookup table name");
      }
      const bool point = data_kind == Data::Point;
      const bool normals = point && key == "NORMALS", scalar = point && key == "SCALARS" && components == 1;
      if (normals) mesh.normals.resize(data_count);
      VertexAttribute* attribute = nullptr;
      if (scalar) {
        // A second array of the same name replaces the first.
        std::erase_if(attributes, [&](const VertexAttribute& a) { return a.name == name; });
        attribute = &attributes.emplace_back(VertexAttribute{name, integer_type, std::vector<double>(data_count)});
      }
      for (std::size_t i = 0; i < data_count; ++i)
        for (std::int64_t k = 0; k < components; ++k) {
          const int vl = tok.line();
          const double v = tok.number("attribute value");
          if (normals) mesh.normals[i][k] = v;
          if (attribute != nullptr) {
            if (integer_type && (v != std::floor(v) || std::fabs(v) > 2147483647.0))
              throw InputError(path, vl, "non-integer or out-of-range value in SCALARS " + name);
            attribute->values[i] = v;
          }
        }
    } else if (key == "FIELD" || key == "COLOR_SCALARS" || key == "VECTORS" || key == "TEXTURE_COORDINATES" ||
               key == "TENSORS" || key == "LOOKUP_TABLE") {
      throw InputError(path, line, key + " data is not supported by this reader");
    } else {
      throw InputError(path, line, "unknown VTK section '" + key + "'");
    }
  }
  if (!have_points) throw InputError(path, tok.line(), "no POINTS section");
  // Attributes given before POINTS (sized by their own count) must match it.
  const auto sized = [&](std::size_t n, const char* what) {
    if (n != 0 && n != n_points)
      throw InputError(
          path, 0,
          std::string(what) + " for " + std::to_string(n) + " points, but POINTS has " + std::to_string(n_points));
  };
  sized(mesh.normals.size(), "NORMALS");
  for (const VertexAttribute& a : attributes) sized(a.values.size(), ("SCALARS " + a.name).c_str());
  check_indices(path, mesh, {});
  return mesh;
}

}  // namespace skinmesh::geometry::mesh_io_detail
