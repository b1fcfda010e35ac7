// geometry/mesh_io.cpp: PLY, OFF and OBJ writers and readers for IndexedMesh.
// Numbers go through std::to_chars / std::from_chars: shortest text that reads
// back to the same double, and correctly rounded parsing, so text round trips are
// bit-exact.
#include "geometry/mesh_io.h"

#include <unistd.h>  // getpid: unique temporary file names

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <string_view>
#include <type_traits>
#include <vector>

#include "geometry/assert.h"
#include "geometry/errors.h"
#include "geometry/text_split.h"

namespace skinmesh::geometry {

namespace {

// Text Helpers

std::string lowercase(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

using geometry::is_blank;
using geometry::split_blanks;
using geometry::split_lines;

/// All of `token` as a finite double, or nullopt.
std::optional<double> to_double(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (token.empty() || ec != std::errc() || ptr != token.data() + token.size() || !std::isfinite(v))
    return std::nullopt;
  return v;
}

/// All of `token` as an integer, or nullopt.
std::optional<std::int64_t> to_int(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  std::int64_t v = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (token.empty() || ec != std::errc() || ptr != token.data() + token.size()) return std::nullopt;
  return v;
}

double number_or_throw(const std::string& path, int line, std::string_view token, const char* what) {
  if (std::optional<double> v = to_double(token)) return *v;
  throw InputError(path, line, std::string("non-numeric or non-finite ") + what + " '" + std::string(token) + "'");
}

std::int64_t int_or_throw(const std::string& path, int line, std::string_view token, const char* what) {
  if (std::optional<std::int64_t> v = to_int(token)) return *v;
  throw InputError(path, line, std::string("non-integer ") + what + " '" + std::string(token) + "'");
}

// Writing Helpers

/// Shortest decimal text that reads back to `v` (or to float(v)).
void append_number(std::string& out, double v, bool double_precision) {
  std::array<char, 64> buf;
  const std::to_chars_result r = double_precision
                                     ? std::to_chars(buf.data(), buf.data() + buf.size(), v)
                                     : std::to_chars(buf.data(), buf.data() + buf.size(), static_cast<float>(v));
  out.append(buf.data(), r.ptr);
}

void append_index(std::string& out, std::uint64_t i) {
  std::array<char, 24> buf;
  const std::to_chars_result r = std::to_chars(buf.data(), buf.data() + buf.size(), i);
  out.append(buf.data(), r.ptr);
}

/// Appends the little-endian bytes of `v`.
template <class T>
void append_le(std::string& out, T v) {
  static_assert(std::is_trivially_copyable_v<T>);
  std::array<char, sizeof(T)> b;
  std::memcpy(b.data(), &v, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(b.begin(), b.end());
  out.append(b.data(), sizeof(T));
}

void check_writable(const IndexedMesh& m) {
  const std::size_t n = m.positions.size();
  SKINMESH_ASSERT_MSG(n <= static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()),
                      "too many vertices for PLY int indices");
  SKINMESH_ASSERT_MSG(m.normals.empty() || m.normals.size() == n, "one normal per vertex");
  SKINMESH_ASSERT_MSG(m.atom.empty() || m.atom.size() == n, "one atom id per vertex");
  for (const auto& t : m.triangles)
    for (Index v : t) SKINMESH_ASSERT_MSG(v < n, "triangle index out of range");
}

std::string ply_bytes(const IndexedMesh& m, const MeshWriteOptions& opt) {
  const char* real = opt.double_precision ? "double" : "float";
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by skinmesh\n";
  out += "element vertex " + std::to_string(m.positions.size()) + "\n";
  for (const char* p : {"x", "y", "z"}) out += std::string("property ") + real + " " + p + "\n";
  if (!m.normals.empty())
    for (const char* p : {"nx", "ny", "nz"}) out += std::string("property ") + real + " " + p + "\n";
  if (!m.atom.empty()) out += "property int atom\n";
  out += "element face " + std::to_string(m.triangles.size()) + "\n";
  out += "property list uchar int vertex_indices\nend_header\n";
  const std::size_t real_size = opt.double_precision ? 8 : 4;
  out.reserve(out.size() + m.positions.size() * (3 * real_size * (m.normals.empty() ? 1 : 2) + 4) +
              m.triangles.size() * 13);
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
    if (!m.atom.empty()) append_le(out, static_cast<std::int32_t>(m.atom[i]));
  }
  for (const auto& t : m.triangles) {
    append_le(out, static_cast<std::uint8_t>(3));
    for (Index v : t) append_le(out, static_cast<std::int32_t>(v));
  }
  return out;
}

std::string off_text(const IndexedMesh& m, const MeshWriteOptions& opt) {
  std::string out = m.normals.empty() ? "OFF\n" : "NOFF\n";
  out += std::to_string(m.positions.size()) + " " + std::to_string(m.triangles.size()) + " 0\n";
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
    out += '\n';
  }
  for (const auto& t : m.triangles) {
    out += '3';
    for (Index v : t) {
      out += ' ';
      append_index(out, v);
    }
    out += '\n';
  }
  return out;
}

std::string obj_text(const IndexedMesh& m, const MeshWriteOptions& opt) {
  std::string out = "# written by skinmesh\n";
  for (const Vec3& p : m.positions) {
    out += 'v';
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      append_number(out, p[k], opt.double_precision);
    }
    out += '\n';
  }
  for (const Vec3& n : m.normals) {
    out += "vn";
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      append_number(out, n[k], opt.double_precision);
    }
    out += '\n';
  }
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
  }
  return out;
}

/// Writes `bytes` to a fresh temporary file beside `path`, then renames it onto
/// `path`. On any failure the temporary file is removed and InputError thrown.
void write_atomically(const std::string& path, const std::string& bytes) {
  static std::atomic<unsigned> counter{0};
  std::string tmp;
  std::FILE* f = nullptr;
  for (int attempt = 0; attempt < 100 && f == nullptr; ++attempt) {
    tmp = path + ".tmp." + std::to_string(static_cast<long>(::getpid())) + "." +
          std::to_string(counter.fetch_add(1));
    f = std::fopen(tmp.c_str(), "wbx");  // "x": fail rather than reuse an existing file
    if (f == nullptr && errno != EEXIST) break;
  }
  if (f == nullptr)
    throw InputError(path, 0, std::string("cannot write mesh (") + std::strerror(errno) + ")");
  int error = 0;  // errno of the first failing step (EIO if the step left none)
  const auto failure = [] { return errno != 0 ? errno : EIO; };
  errno = 0;
  if (std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size() || std::fflush(f) != 0) error = failure();
  if (std::fclose(f) != 0 && error == 0) error = failure();
  if (error == 0 && std::rename(tmp.c_str(), path.c_str()) != 0) error = failure();
  if (error != 0) {
    std::remove(tmp.c_str());
    throw InputError(path, 0, std::string("cannot write mesh (") + std::strerror(error) + ")");
  }
}

std::string read_bytes(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw InputError(path, 0, std::string("cannot open file (") + std::strerror(errno) + ")");
  std::string data;
  std::array<char, 1 << 16> buf;
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), f)) > 0) data.append(buf.data(), n);
  const bool failed = std::ferror(f) != 0;
  const int saved_errno = errno;
  std::fclose(f);
  if (failed) throw InputError(path, 0, std::string("cannot read file (") + std::strerror(saved_errno) + ")");
  return data;
}

/// Checks that every triangle index is < positions.size(); `lines[i]` (if given)
/// is the source line of triangle i.
void check_indices(const std::string& path, const IndexedMesh& m, const std::vector<int>& lines) {
  const std::size_t n = m.positions.size();
  for (std::size_t i = 0; i < m.triangles.size(); ++i)
    for (Index v : m.triangles[i])
      if (v >= n)
        throw InputError(path, i < lines.size() ? lines[i] : 0,
                         "face " + std::to_string(i) + ": vertex index " + std::to_string(v) +
                             " out of range (" + std::to_string(n) + " vertices)");
}

// PLY Reading

enum class PlyType { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };

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

bool is_integer(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;   // the value type (list items for a list)
  bool is_list = false;
  PlyType count_type = PlyType::Uint8;  // lists only
};

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
      case PlyType::Int8: return get<std::int8_t>(context);
      case PlyType::Uint8: return get<std::uint8_t>(context);
      case PlyType::Int16: return get<std::int16_t>(context);
      case PlyType::Uint16: return get<std::uint16_t>(context);
      case PlyType::Int32: return get<std::int32_t>(context);
      case PlyType::Uint32: return get<std::uint32_t>(context);
      case PlyType::Float32: return get<float>(context);
      case PlyType::Float64: return get<double>(context);
    }
    return 0.0;
  }
  int line() const { return 0; }

 private:
  template <class T>
  double get(const std::string& context) {
    if (body_.size() - pos_ < sizeof(T))
      throw InputError(path_, 0, "unexpected end of binary data in " + context);
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

template <class Reader>
void read_ply_body(const std::string& path, Reader& in, const std::vector<PlyElement>& elements,
                   IndexedMesh& mesh, std::vector<int>& face_lines) {
  bool have_vertices = false;
  for (const PlyElement& el : elements) {
    const auto find = [&](std::string_view name) -> int {
      for (std::size_t k = 0; k < el.properties.size(); ++k)
        if (el.properties[k].name == name && !el.properties[k].is_list) return static_cast<int>(k);
      return -1;
    };
    // Role of each property: 0-2 position, 3-5 normal, 6 atom, 7 triangle, -1 skipped.
    std::vector<int> role(el.properties.size(), -1);
    bool with_normals = false, with_atom = false;
    if (el.name == "vertex") {
      if (have_vertices) throw InputError(path, el.header_line, "second PLY vertex element");
      have_vertices = true;
      const int x = find("x"), y = find("y"), z = find("z");
      if (x < 0 || y < 0 || z < 0)
        throw InputError(path, el.header_line, "PLY vertex element lacks scalar x, y or z");
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
      const int atom = find("atom");
      with_atom = atom >= 0;
      if (with_atom) {
        if (!is_integer(el.properties[static_cast<std::size_t>(atom)].type))
          throw InputError(path, el.header_line, "PLY vertex property 'atom' must have an integer type");
        role[static_cast<std::size_t>(atom)] = 6;
      }
      mesh.positions.assign(el.count, Vec3::Zero());
      if (with_normals) mesh.normals.assign(el.count, Vec3::Zero());
      if (with_atom) mesh.atom.assign(el.count, -1);
    } else if (el.name == "face") {
      int list = -1;
      for (std::size_t k = 0; k < el.properties.size(); ++k)
        if (el.properties[k].is_list &&
            (el.properties[k].name == "vertex_indices" || el.properties[k].name == "vertex_index")) {
          list = static_cast<int>(k);
          break;
        }
      if (list < 0)
        throw InputError(path, el.header_line, "PLY face element lacks a list property vertex_indices");
      if (!is_integer(el.properties[static_cast<std::size_t>(list)].type))
        throw InputError(path, el.header_line, "PLY vertex_indices must have an integer type");
      role[static_cast<std::size_t>(list)] = 7;
      mesh.triangles.reserve(el.count);
    }
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
            case 0: case 1: case 2: mesh.positions[i][role[k]] = v; break;
            case 3: case 4: case 5: mesh.normals[i][role[k] - 3] = v; break;
            case 6:
              if (v < std::numeric_limits<std::int32_t>::min() || v > std::numeric_limits<std::int32_t>::max())
                throw InputError(path, in.line(), "atom id out of range in " + context);
              mesh.atom[i] = static_cast<std::int32_t>(v);
              break;
            default: break;
          }
          continue;
        }
        const double count = in.next(p.count_type, context);
        if (count < 0) throw InputError(path, in.line(), "negative list length in " + context);
        const auto n = static_cast<std::size_t>(count);
        if (role[k] == 7 && n != 3)
          throw InputError(path, in.line(), "face " + std::to_string(i) + " has " + std::to_string(n) +
                                                " vertices; only triangles are accepted");
        for (std::size_t j = 0; j < n; ++j) {
          const double v = in.next(p.type, context);
          if (role[k] == 7) {
            if (v < 0 || v > static_cast<double>(std::numeric_limits<Index>::max() - 1))
              throw InputError(path, in.line(), "face " + std::to_string(i) + ": vertex index " +
                                                    std::to_string(static_cast<long long>(v)) + " out of range");
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

IndexedMesh read_ply(const std::string& path, const std::string& data) {
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
      if (f[1] == "ascii") encoding = Encoding::Ascii;
      else if (f[1] == "binary_little_endian") encoding = Encoding::BinaryLittle;
      else if (f[1] == "binary_big_endian") encoding = Encoding::BinaryBig;
      else throw InputError(path, line, "unknown PLY format '" + std::string(f[1]) + "'");
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

  IndexedMesh mesh;
  std::vector<int> face_lines;
  const std::string_view body = std::string_view(data).substr(std::min(pos, data.size()));
  if (*encoding == Encoding::Ascii) {
    PlyAsciiReader in(path, body, line + 1);
    read_ply_body(path, in, elements, mesh, face_lines);
  } else {
    PlyBinaryReader in(path, body, *encoding == Encoding::BinaryBig);
    read_ply_body(path, in, elements, mesh, face_lines);
  }
  check_indices(path, mesh, face_lines);
  return mesh;
}

// OFF Reading

IndexedMesh read_off(const std::string& path, const std::string& data) {
  // Records: non-empty lines with comments removed, with their line numbers.
  struct Record {
    int line;
    std::vector<std::string_view> fields;
  };
  std::vector<Record> records;
  const std::vector<std::string_view> lines = split_lines(data);
  for (std::size_t k = 0; k < lines.size(); ++k) {
    std::string_view l = lines[k];
    if (const std::size_t hash = l.find('#'); hash != std::string_view::npos) l = l.substr(0, hash);
    std::vector<std::string_view> f = split_blanks(l);
    if (!f.empty()) records.push_back({static_cast<int>(k + 1), std::move(f)});
  }
  if (records.empty()) throw InputError(path, 0, "empty OFF file");

  // Header keyword [ST][C][N]OFF, counts on the same line or the next.
  const Record& head = records[0];
  std::string_view key = head.fields[0];
  bool normals = false, colours = false;
  if (key.starts_with("ST")) key.remove_prefix(2);
  if (key.starts_with("C")) { colours = true; key.remove_prefix(1); }
  if (key.starts_with("N")) { normals = true; key.remove_prefix(1); }
  if (key != "OFF")
    throw InputError(path, head.line, "not an OFF file (header '" + std::string(head.fields[0]) +
                                          "'; expected OFF, NOFF, COFF, STOFF)");
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
  if (records.size() - r < static_cast<std::size_t>(nv + nf))
    throw InputError(path, records.back().line,
                     "unexpected end of file: expected " + std::to_string(nv) + " vertices and " +
                         std::to_string(nf) + " faces");

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
      throw InputError(path, rec.line, "face " + std::to_string(i) + " has " + std::to_string(n) +
                                           " vertices; only triangles are accepted");
    if (rec.fields.size() < 4) throw InputError(path, rec.line, "face " + std::to_string(i) + " lists fewer than 3 indices");
    std::array<Index, 3> t{};
    for (std::size_t k = 0; k < 3; ++k) {
      const std::int64_t v = int_or_throw(path, rec.line, rec.fields[k + 1], "vertex index");
      if (v < 0 || v >= nv)
        throw InputError(path, rec.line, "face " + std::to_string(i) + ": vertex index " + std::to_string(v) +
                                             " out of range (" + std::to_string(nv) + " vertices)");
      t[k] = static_cast<Index>(v);
    }
    mesh.triangles.push_back(t);
  }
  return mesh;
}

// OBJ Reading

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
      throw InputError(path, line, std::string(what) + " " + std::string(token) + " out of range (" +
                                       std::to_string(n) + " defined so far)");
    return r;
  };
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const int line = static_cast<int>(k + 1);
    std::string_view l = lines[k];
    if (const std::size_t hash = l.find('#'); hash != std::string_view::npos) l = l.substr(0, hash);
    const std::vector<std::string_view> f = split_blanks(l);
    if (f.empty()) continue;
    if (f[0] == "v" || f[0] == "vn") {
      if (f.size() < 4) throw InputError(path, line, "'" + std::string(f[0]) + "' needs 3 numbers");
      const Vec3 p(number_or_throw(path, line, f[1], "coordinate"), number_or_throw(path, line, f[2], "coordinate"),
                   number_or_throw(path, line, f[3], "coordinate"));
      (f[0] == "v" ? mesh.positions : vn).push_back(p);
    } else if (f[0] == "f") {
      if (f.size() != 4)
        throw InputError(path, line, "face " + std::to_string(mesh.triangles.size()) + " has " +
                                         std::to_string(f.size() - 1) + " vertices; only triangles are accepted");
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
    if (consistent && std::all_of(set.begin(), set.end(), [](bool b) { return b; }))
      mesh.normals = std::move(normals);
  }
  check_indices(path, mesh, face_lines);
  return mesh;
}

}  // namespace

// Mesh I/O Function Definitions

MeshFormat mesh_format_from_extension(const std::string& path) {
  const std::string p = lowercase(path);
  if (p.ends_with(".ply")) return MeshFormat::Ply;
  if (p.ends_with(".off")) return MeshFormat::Off;
  if (p.ends_with(".obj")) return MeshFormat::Obj;
  throw InputError(path, 0, "unknown mesh format (expected .ply, .off or .obj)");
}

void write_mesh(const std::string& path, const IndexedMesh& mesh, const MeshWriteOptions& opt) {
  const MeshFormat format = mesh_format_from_extension(path);
  check_writable(mesh);
  switch (format) {
    case MeshFormat::Ply:
      write_atomically(path, ply_bytes(mesh, opt));
      return;
    case MeshFormat::Off:
      write_atomically(path, off_text(mesh, opt));
      return;
    case MeshFormat::Obj:
      write_atomically(path, obj_text(mesh, opt));
      return;
  }
}

IndexedMesh read_mesh(const std::string& path) {
  const MeshFormat format = mesh_format_from_extension(path);
  const std::string data = read_bytes(path);
  switch (format) {
    case MeshFormat::Ply:
      return read_ply(path, data);
    case MeshFormat::Off:
      return read_off(path, data);
    case MeshFormat::Obj:
      return read_obj(path, data);
  }
  return {};
}

}  // namespace skinmesh::geometry
