// geometry/io/mesh_io_ply.cpp: the PLY format of mesh_io.h (G. Turk, "The PLY
// Polygon File Format", 1994) — the binary little-endian writer and the reader
// of ascii, binary_little_endian and binary_big_endian files. Declared in
// mesh_io_internal.h.
#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/errors.h"
#include "core/text_split.h"
#include "geometry/io/mesh_io_internal.h"

namespace skinmesh::geometry::mesh_io_detail {

namespace {

// PLY Writing

/// Appends the little-endian bytes of `v`.
template <class T>
void append_le(std::string& out, T v) {
  static_assert(std::is_trivially_copyable_v<T>);
  std::array<char, sizeof(T)> b;
  std::memcpy(b.data(), &v, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(b.begin(), b.end());
  out.append(b.data(), sizeof(T));
}

// PLY Reading

/// The scalar types of the PLY header (both the old and the sized names).
enum class PlyType { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };

/// The PlyType named `s` in a header ("uchar" or "uint8", ...), or nullopt.
std::optional<PlyType> ply_type(std::string_view s) {
  if (s == "char" || s == "int8") return PlyType::Int8;
  if (s == "uchar" || s == "uint8") return PlyType::Uint8;
  if (s == "short" || s == "int16") return PlyType::Int16;
  if (s == "ushort" || s == "uint16") return PlyType::Uint16;
  if (s == "int" || s == "int32") return PlyType::Int32;
  if (s == "uint" || s == "uint32") return PlyType::Uint32;
  if (s == "float" || s == "float32") return PlyType::Float32;
  if (s == "double" || s == "float64") return PlyType::Float64;
  return std::nullopt;
}

/// Bytes of one value of type t in a binary body.
std::size_t ply_type_size(PlyType t) {
  switch (t) {
    case PlyType::Int8:
    case PlyType::Uint8:
      return 1;
    case PlyType::Int16:
    case PlyType::Uint16:
      return 2;
    case PlyType::Int32:
    case PlyType::Uint32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 1;
}

/// True for the integer types (all but float and double).
bool is_integer(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }

/// One `property` line of the header: a scalar or a list.
struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // the value type (list items for a list)
  bool is_list = false;
  PlyType count_type = PlyType::Uint8;  // lists only
};

/// One `element` of the header with its properties, in header order;
/// header_line is its 1-based line (for messages).
struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
  int header_line = 0;
};

/// Reads PLY values from the ascii body, one token at a time.
class PlyAsciiReader {
 public:
  PlyAsciiReader(const std::string& path, std::string_view body, int first_line)
      : path_(path), body_(body), line_(first_line) {}
  double next(PlyType type, const std::string& context) {
    while (pos_ < body_.size() && is_blank(body_[pos_])) {
      if (body_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ >= body_.size()) throw InputError(path_, line_, "unexpected end of file in " + context);
    const std::size_t start = pos_;
    while (pos_ < body_.size() && !is_blank(body_[pos_])) ++pos_;
    const std::string_view token = body_.substr(start, pos_ - start);
    if (is_integer(type)) {
      if (std::optional<std::int64_t> v = to_int(token)) return static_cast<double>(*v);
      throw InputError(path_, line_, "non-integer value '" + std::string(token) + "' in " + context);
    }
    // nan and inf are legal PLY floats; read_ply_body() rejects them where used.
    std::string_view t = token;
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (t.empty() || ptr != t.data() + t.size() || (ec != std::errc() && ec != std::errc::result_out_of_range))
      throw InputError(path_, line_, "non-numeric value '" + std::string(token) + "' in " + context);
    if (ec == std::errc::result_out_of_range) v = std::strtod(std::string(t).c_str(), nullptr);
    return v;
  }
  int line() const { return line_; }

 private:
  const std::string& path_;
  std::string_view body_;
  std::size_t pos_ = 0;
  int line_;
};

/// Reads PLY values from a binary body of either byte order.
class PlyBinaryReader {
 public:
  PlyBinaryReader(const std::string& path, std::string_view body, bool big_endian)
      : path_(path), body_(body), swap_(big_endian != (std::endian::native == std::endian::big)) {}
  double next(PlyType type, const std::string& context) {
    switch (type) {
      case PlyType::Int8:
        return get<std::int8_t>(context);
      case PlyType::Uint8:
        return get<std::uint8_t>(context);
      case PlyType::Int16:
        return get<std::int16_t>(context);
      case PlyType::Uint16:
        return get<std::uint16_t>(context);
      case PlyType::Int32:
        return get<std::int32_t>(context);
      case PlyType::Uint32:
        return get<std::uint32_t>(context);
      case PlyType::Float32:
        return get<float>(context);
      case PlyType::Float64:
        return get<double>(context);
    }
    return 0.0;
  }
  int line() const { return 0; }

 private:
  template <class T>
  double get(const std::string& context) {
    if (body_.size() - pos_ < sizeof(T)) throw InputError(path_, 0, "unexpected end of binary data in " + context);
    std::array<char, sizeof(T)> b;
    std::memcpy(b.data(), body_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    if (swap_) std::reverse(b.begin(), b.end());
    T v;
    std::memcpy(&v, b.data(), sizeof(T));
    return static_cast<double>(v);
  }
  const std::string& path_;
  std::string_view body_;
  std::size_t pos_ = 0;
  bool swap_;
};

/// Reads the values of every element of `elements` from `in` (PlyAsciiReader or
/// PlyBinaryReader): vertex x, y, z (and nx, ny, nz when present) into `mesh`,
/// the other scalar vertex properties into `attributes`, faces from their
/// vertex_indices (or vertex_index) list, one entry of `face_lines` per face (its
/// text line, 0 in binary data); other properties and elements are read and
/// dropped. Throws InputError for a missing or second vertex element, a property
/// of the wrong type, a non-finite coordinate or normal, an integer attribute
/// out of the int32 range, a face that is not a triangle, a
/// negative index and truncated data.
template <class Reader>
void read_ply_body(const std::string& path, Reader& in, const std::vector<PlyElement>& elements, IndexedMesh& mesh,
                   std::vector<VertexAttribute>& attributes, std::vector<int>& face_lines) {
  bool have_vertices = false;
  for (const PlyElement& el : elements) {
    const auto find = [&](std::string_view name) -> int {
      for (std::size_t k = 0; k < el.properties.size(); ++k)
        if (el.properties[k].name == name && !el.properties[k].is_list) return static_cast<int>(k);
      return -1;
    };
    // Role of each property: 0-2 position, 3-5 normal, 6 attribute, 7 triangle, -1 skipped.
    std::vector<int> role(el.properties.size(), -1);
    std::vector<std::size_t> attribute_of(el.properties.size(), 0);  // role 6: index into `attributes`
    bool with_normals = false;
    if (el.name == "vertex") {
      if (have_vertices) throw InputError(path, el.header_line, "second PLY vertex element");
      have_vertices = true;
      const int x = find("x"), y = find("y"), z = find("z");
      if (x < 0 || y < 0 || z < 0) throw InputError(path, el.header_line, "PLY vertex element lacks scalar x, y or z");
      role[static_cast<std::size_t>(x)] = 0;
      role[static_cast<std::size_t>(y)] = 1;
      role[static_cast<std::size_t>(z)] = 2;
      const int nx = find("nx"), ny = find("ny"), nz = find("nz");
      with_normals = nx >= 0 && ny >= 0 && nz >= 0;
      if (with_normals) {
        role[static_cast<std::size_t>(nx)] = 3;
        role[static_cast<std::size_t>(ny)] = 4;
        role[static_cast<std::size_t>(nz)] = 5;
      }
      for (std::size_t k = 0; k < el.properties.size(); ++k) {
        const PlyProperty& p = el.properties[k];
        if (role[k] >= 0 || p.is_list || find(p.name) != static_cast<int>(k)) continue;  // first of a name only
        role[k] = 6;
        attribute_of[k] = attributes.size();
        attributes.push_back({p.name, is_integer(p.type), std::vector<double>(el.count, 0.0)});
      }
      mesh.positions.assign(el.count, Vec3::Zero());
      if (with_normals) mesh.normals.assign(el.count, Vec3::Zero());
    } else if (el.name == "face") {
      int list = -1;
      for (std::size_t k = 0; k < el.properties.size(); ++k)
        if (el.properties[k].is_list &&
            (el.properties[k].name == "vertex_indices" || el.properties[k].name == "vertex_index")) {
          list = static_cast<int>(k);
          break;
        }
      if (list < 0) throw InputError(path, el.header_line, "PLY face element lacks a list property vertex_indices");
      if (!is_integer(el.properties[static_cast<std::size_t>(list)].type))
        throw InputError(path, el.header_line, "PLY vertex_indices must have an integer type");
      role[static_cast<std::size_t>(list)] = 7;
      mesh.triangles.reserve(el.count);
    }
    // A record without properties holds no data: nothing to read, however
    // many records the header claims (a count the size check before the body
    // cannot bound, so the loop below must not run it).
    if (el.properties.empty()) continue;
    const std::string element_name = "element '" + el.name + "' ";
    for (std::size_t i = 0; i < el.count; ++i) {
      const std::string context = element_name + std::to_string(i);
      std::array<Index, 3> tri{};
      for (std::size_t k = 0; k < el.properties.size(); ++k) {
        const PlyProperty& p = el.properties[k];
        if (!p.is_list) {
          const double v = in.next(p.type, context);
          if (role[k] >= 0 && role[k] <= 5 && !std::isfinite(v))
            throw InputError(path, in.line(), "non-finite " + p.name + " in " + context);
          switch (role[k]) {
            case 0:
            case 1:
            case 2:
              mesh.positions[i][role[k]] = v;
              break;
            case 3:
            case 4:
            case 5:
              mesh.normals[i][role[k] - 3] = v;
              break;
            case 6: {
              VertexAttribute& a = attributes[attribute_of[k]];
              if (a.integer &&
                  (v < std::numeric_limits<std::int32_t>::min() || v > std::numeric_limits<std::int32_t>::max()))
                throw InputError(path, in.line(), p.name + " out of the int32 range in " + context);
              a.values[i] = v;
              break;
            }
            default:
              break;
          }
          continue;
        }
        const double count = in.next(p.count_type, context);
        if (count < 0) throw InputError(path, in.line(), "negative list length in " + context);
        const auto n = static_cast<std::size_t>(count);
        if (role[k] == 7 && n != 3)
          throw InputError(
              path, in.line(),
              "face " + std::to_string(i) + " has " + std::to_string(n) + " vertices; only triangles are accepted");
        for (std::size_t j = 0; j < n; ++j) {
          const double v = in.next(p.type, context);
          if (role[k] == 7) {
            if (v < 0 || v > static_cast<double>(std::numeric_limits<Index>::max() - 1)) {
              // Printed from the double: an index near 2^63 has no long long value.
              char text[64];
              std::snprintf(text, sizeof text, "%.0f", v);
              throw InputError(path, in.line(),
                               "face " + std::to_string(i) + ": vertex index " + text + " out of range");
            }
            tri[j] = static_cast<Index>(v);
          }
        }
      }
      if (el.name == "face") {
        mesh.triangles.push_back(tri);
        face_lines.push_back(in.line());
      }
    }
  }
  if (!have_vertices) throw InputError(path, 0, "PLY file has no vertex element");
}

}  // namespace

void write_ply(const IndexedMesh& m, const std::vector<VertexAttribute>& attributes, const MeshWriteOptions& opt,
               ChunkedWriter& w) {
  const char* real = opt.double_precision ? "double" : "float";
  std::string& out = w.buffer();
  out += opt.ascii ? "ply\nformat ascii 1.0\n" : "ply\nformat binary_little_endian 1.0\n";
  out += "comment written by skinmesh\n";
  out += "element vertex " + std::to_string(m.positions.size()) + "\n";
  for (const char* p : {"x", "y", "z"}) out += std::string("property ") + real + " " + p + "\n";
  if (!m.normals.empty())
    for (const char* p : {"nx", "ny", "nz"}) out += std::string("property ") + real + " " + p + "\n";
  for (const VertexAttribute& a : attributes)
    out += std::string("property ") + (a.integer ? "int" : real) + " " + a.name + "\n";
  out += "element face " + std::to_string(m.triangles.size()) + "\n";
  out += "property list uchar int vertex_indices\nend_header\n";
  if (opt.ascii) {
    // One line per element, the numbers separated by single spaces.
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        if (k > 0) out += ' ';
        append_number(out, m.positions[i][k], opt.double_precision);
      }
      if (!m.normals.empty())
        for (int k = 0; k < 3; ++k) {
          out += ' ';
          append_number(out, m.normals[i][k], opt.double_precision);
        }
      for (const VertexAttribute& a : attributes) {
        out += ' ';
        if (a.integer)
          out += std::to_string(static_cast<std::int32_t>(a.values[i]));
        else
          append_number(out, a.values[i], opt.double_precision);
      }
      out += '\n';
      w.spill();
    }
    append_triangle_lines(w, m.triangles);
    return;
  }
  auto put_real = [&](double v) {
    if (opt.double_precision)
      append_le(out, v);
    else
      append_le(out, static_cast<float>(v));
  };
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) put_real(m.positions[i][k]);
    if (!m.normals.empty())
      for (int k = 0; k < 3; ++k) put_real(m.normals[i][k]);
    for (const VertexAttribute& a : attributes) {
      if (a.integer)
        append_le(out, static_cast<std::int32_t>(a.values[i]));
      else
        put_real(a.values[i]);
    }
    w.spill();
  }
  for (const auto& t : m.triangles) {
    append_le(out, static_cast<std::uint8_t>(3));
    for (Index v : t) append_le(out, static_cast<std::int32_t>(v));
    w.spill();
  }
}

IndexedMesh read_ply(const std::string& path, const std::string& data, std::vector<VertexAttribute>& attributes) {
  // Header: lines up to "end_header".
  std::vector<PlyElement> elements;
  enum class Encoding { Ascii, BinaryLittle, BinaryBig };
  std::optional<Encoding> encoding;
  std::size_t pos = 0;
  int line = 0;
  bool ended = false;
  while (pos < data.size() && !ended) {
    std::size_t end = data.find('\n', pos);
    if (end == std::string::npos) end = data.size();
    std::string_view text(data.data() + pos, end - pos);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    pos = end + 1;
    ++line;
    const std::vector<std::string_view> f = split_blanks(text);
    if (line == 1) {
      if (f.size() != 1 || f[0] != "ply") throw InputError(path, 1, "not a PLY file (first line must be 'ply')");
      continue;
    }
    if (f.empty() || f[0] == "comment" || f[0] == "obj_info") continue;
    if (f[0] == "format") {
      if (f.size() != 3 || f[2] != "1.0") throw InputError(path, line, "unsupported PLY format line");
      if (f[1] == "ascii")
        encoding = Encoding::Ascii;
      else if (f[1] == "binary_little_endian")
        encoding = Encoding::BinaryLittle;
      else if (f[1] == "binary_big_endian")
        encoding = Encoding::BinaryBig;
      else
        throw InputError(path, line, "unknown PLY format '" + std::string(f[1]) + "'");
    } else if (f[0] == "element") {
      if (f.size() != 3) throw InputError(path, line, "malformed PLY element line");
      const std::int64_t count = int_or_throw(path, line, f[2], "element count");
      if (count < 0) throw InputError(path, line, "negative PLY element count");
      elements.push_back({std::string(f[1]), static_cast<std::size_t>(count), {}, line});
    } else if (f[0] == "property") {
      if (elements.empty()) throw InputError(path, line, "PLY property before any element");
      PlyProperty p;
      if (f.size() == 5 && f[1] == "list") {
        const std::optional<PlyType> ct = ply_type(f[2]), it = ply_type(f[3]);
        if (!ct || !it) throw InputError(path, line, "unknown PLY property type");
        if (!is_integer(*ct)) throw InputError(path, line, "PLY list count must have an integer type");
        p = {std::string(f[4]), *it, true, *ct};
      } else if (f.size() == 3) {
        const std::optional<PlyType> t = ply_type(f[1]);
        if (!t) throw InputError(path, line, "unknown PLY property type '" + std::string(f[1]) + "'");
        p = {std::string(f[2]), *t, false, PlyType::Uint8};
      } else {
        throw InputError(path, line, "malformed PLY property line");
      }
      elements.back().properties.push_back(std::move(p));
    } else if (f[0] == "end_header") {
      ended = true;
    } else {
      throw InputError(path, line, "unknown PLY header line '" + std::string(text) + "'");
    }
  }
  if (!ended) throw InputError(path, line, "PLY header without end_header");
  if (!encoding) throw InputError(path, line, "PLY header without format line");
  // A header may claim more records than the file can hold (a hostile file):
  // a binary record takes at least the bytes of its scalars and list counts,
  // an ascii record at least one character. Refuse before allocating anything;
  // a file merely cut short is reported where it ends, by the body readers.
  {
    const std::size_t body_size = data.size() - std::min(pos, data.size());
    std::size_t budget = body_size;
    for (const PlyElement& el : elements) {
      std::size_t min_record = 0;
      for (const PlyProperty& p : el.properties)
        min_record += *encoding == Encoding::Ascii ? 0 : ply_type_size(p.is_list ? p.count_type : p.type);
      if (*encoding == Encoding::Ascii && !el.properties.empty()) min_record = 1;
      if (min_record == 0) continue;
      if (el.count > budget / min_record)
        throw InputError(path, el.header_line,
                         "PLY element '" + el.name + "' claims " + std::to_string(el.count) +
                             " records, more than the " + std::to_string(body_size) +
                             " bytes after the header can hold");
      budget -= el.count * min_record;
    }
  }

  IndexedMesh mesh;
  std::vector<int> face_lines;
  const std::string_view body = std::string_view(data).substr(std::min(pos, data.size()));
  if (*encoding == Encoding::Ascii) {
    PlyAsciiReader in(path, body, line + 1);
    read_ply_body(path, in, elements, mesh, attributes, face_lines);
  } else {
    PlyBinaryReader in(path, body, *encoding == Encoding::BinaryBig);
    read_ply_body(path, in, elements, mesh, attributes, face_lines);
  }
  check_indices(path, mesh, face_lines);
  return mesh;
}

}  // namespace skinmesh::geometry::mesh_io_detail
