// geometry/io/mesh_io.cpp: the public functions of mesh_io.h — the format by
// extension, write_mesh() and read_mesh() dispatching to one writer and one
// reader per format (mesh_io_ply.cpp, mesh_io_off.cpp, mesh_io_obj.cpp) — and
// what the formats share: atomic writing of the finished file, reading a whole
// file, and the number and index helpers of mesh_io_internal.h.
#include "geometry/io/mesh_io.h"

#include <unistd.h>  // getpid: unique temporary file names

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

#include "core/assert.h"
#include "core/errors.h"
#include "core/read_file.h"
#include "core/text_split.h"
#include "geometry/io/mesh_io_internal.h"

namespace skinmesh::geometry {

namespace mesh_io_detail {

// Shared Helpers

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

void append_triangle_lines(ChunkedWriter& w, const std::vector<std::array<Index, 3>>& triangles) {
  std::string& out = w.buffer();
  for (const auto& t : triangles) {
    out += '3';
    for (Index v : t) {
      out += ' ';
      append_index(out, v);
    }
    out += '\n';
    w.spill();
  }
}

void check_indices(const std::string& path, const IndexedMesh& m, const std::vector<int>& lines) {
  const std::size_t n = m.positions.size();
  for (std::size_t i = 0; i < m.triangles.size(); ++i)
    for (Index v : m.triangles[i])
      if (v >= n)
        throw InputError(path, i < lines.size() ? lines[i] : 0,
                         "face " + std::to_string(i) + ": vertex index " + std::to_string(v) + " out of range (" +
                             std::to_string(n) + " vertices)");
}

}  // namespace mesh_io_detail

namespace {

using mesh_io_detail::read_obj;
using mesh_io_detail::read_off;
using mesh_io_detail::read_ply;
using mesh_io_detail::read_stl;
using mesh_io_detail::read_vtk;
using mesh_io_detail::read_vtk_xml;
using mesh_io_detail::write_obj;
using mesh_io_detail::write_off;
using mesh_io_detail::write_ply;
using mesh_io_detail::write_stl;
using mesh_io_detail::write_vtk;
using mesh_io_detail::write_vtk_xml;

}  // namespace

void check_writable(const IndexedMesh& m, const std::vector<VertexAttribute>& attributes) {
  const std::size_t n = m.positions.size();
  SKINMESH_ASSERT_MSG(n <= static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()),
                      "too many vertices for PLY int indices");
  SKINMESH_ASSERT_MSG(m.normals.empty() || m.normals.size() == n, "one normal per vertex");
  for (const VertexAttribute& a : attributes) {
    SKINMESH_ASSERT_MSG(a.values.size() == n, "one attribute value per vertex");
    SKINMESH_ASSERT_MSG(
        !a.name.empty() && std::all_of(a.name.begin(), a.name.end(),
                                       [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }),
        "an attribute name is one word");
    if (a.integer)
      for (double v : a.values)
        SKINMESH_ASSERT_MSG(v == std::floor(v) && v >= std::numeric_limits<std::int32_t>::min() &&
                                v <= std::numeric_limits<std::int32_t>::max(),
                            "integer attribute values in the int32 range");
  }
  for (const auto& t : m.triangles)
    for (Index v : t) SKINMESH_ASSERT_MSG(v < n, "triangle index out of range");
}

namespace {

/// Writes the bytes `produce` makes to a fresh temporary file beside `path`,
/// chunk by chunk, and returns its name. On failure the temporary is removed
/// and InputError(path, 0, "cannot write <what> (reason)") is thrown; an
/// exception from `produce` removes it too and is passed on.
std::string write_temporary(const std::string& path, const FileProducer& produce, const std::string& what) {
  static std::atomic<unsigned> counter{0};
  std::string tmp;
  std::FILE* f = nullptr;
  for (int attempt = 0; attempt < 100 && f == nullptr; ++attempt) {
    tmp = path + ".tmp." + std::to_string(static_cast<long>(::getpid())) + "." + std::to_string(counter.fetch_add(1));
    f = std::fopen(tmp.c_str(), "wbx");  // "x": fail rather than reuse an existing file
    if (f == nullptr && errno != EEXIST) break;
  }
  if (f == nullptr) throw InputError(path, 0, "cannot write " + what + " (" + std::strerror(errno) + ")");
  int error = 0;  // errno of the first failing step (EIO if the step left none)
  const auto failure = [] { return errno != 0 ? errno : EIO; };
  errno = 0;
  ChunkedWriter out([&](std::string_view chunk) {
    if (error == 0 && std::fwrite(chunk.data(), 1, chunk.size(), f) != chunk.size()) error = failure();
  });
  try {
    produce(out);
    out.flush();
  } catch (...) {
    std::fclose(f);
    std::remove(tmp.c_str());
    throw;
  }
  if (error == 0 && std::fflush(f) != 0) error = failure();
  if (std::fclose(f) != 0 && error == 0) error = failure();
  if (error != 0) {
    std::remove(tmp.c_str());
    throw InputError(path, 0, "cannot write " + what + " (" + std::strerror(error) + ")");
  }
  return tmp;
}

/// A producer of the bytes of `bytes`.
FileProducer bytes_producer(const std::string& bytes) {
  return [&bytes](ChunkedWriter& out) { out.write(bytes); };
}

/// Renames the temporary `tmp` onto `path`; on failure removes it and throws
/// InputError(path, 0, "cannot write <what> (reason)").
void rename_onto(const std::string& tmp, const std::string& path, const std::string& what) {
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int error = errno != 0 ? errno : EIO;
    std::remove(tmp.c_str());
    throw InputError(path, 0, "cannot write " + what + " (" + std::strerror(error) + ")");
  }
}

}  // namespace

void write_file_atomically(const std::string& path, const FileProducer& produce, const std::string& what) {
  rename_onto(write_temporary(path, produce, what), path, what);
}

void write_file_atomically(const std::string& path, const std::string& bytes, const std::string& what) {
  write_file_atomically(path, bytes_producer(bytes), what);
}

void write_files_atomically(const std::vector<std::pair<std::string, FileProducer>>& files, const std::string& what) {
  // A folder in the way would fail a later rename only: refused first.
  for (const auto& [path, produce] : files)
    if (std::filesystem::is_directory(path))
      throw InputError(path, 0, "cannot write " + what + " (a folder has this name)");
  std::vector<std::string> temporaries;
  const auto remove_temporaries = [&temporaries](std::size_t from) {
    for (std::size_t k = from; k < temporaries.size(); ++k) std::remove(temporaries[k].c_str());
  };
  try {
    for (const auto& [path, produce] : files) temporaries.push_back(write_temporary(path, produce, what));
  } catch (...) {
    remove_temporaries(0);
    throw;
  }
  for (std::size_t k = 0; k < files.size(); ++k) {
    try {
      rename_onto(temporaries[k], files[k].first, what);
    } catch (...) {
      remove_temporaries(k + 1);
      throw;
    }
  }
}

void write_files_atomically(const std::vector<std::pair<std::string, std::string>>& files, const std::string& what) {
  std::vector<std::pair<std::string, FileProducer>> producers;
  for (const auto& [path, bytes] : files) producers.emplace_back(path, bytes_producer(bytes));
  write_files_atomically(producers, what);
}

// Mesh I/O Function Definitions

std::optional<MeshFormat> mesh_format_of(const std::string& path) {
  const std::string p = lowercase(path);
  if (p.ends_with(".ply")) return MeshFormat::Ply;
  if (p.ends_with(".off")) return MeshFormat::Off;
  if (p.ends_with(".obj")) return MeshFormat::Obj;
  if (p.ends_with(".stl")) return MeshFormat::Stl;
  if (p.ends_with(".vtk")) return MeshFormat::Vtk;
  if (p.ends_with(".vtp")) return MeshFormat::Vtp;
  if (p.ends_with(".vtu")) return MeshFormat::Vtu;
  return std::nullopt;
}

MeshFormat mesh_format_from_extension(const std::string& path) {
  if (const std::optional<MeshFormat> format = mesh_format_of(path)) return *format;
  throw InputError(path, 0, "unknown mesh format (expected .ply, .off, .obj, .stl, .vtk, .vtp or .vtu)");
}

void write_mesh(const std::string& path, const IndexedMesh& mesh, const MeshWriteOptions& opt,
                const std::vector<VertexAttribute>& attributes) {
  const MeshFormat format = mesh_format_from_extension(path);
  check_writable(mesh, attributes);
  switch (format) {
    case MeshFormat::Ply:
      write_file_atomically(
          path, [&](ChunkedWriter& out) { write_ply(mesh, attributes, opt, out); }, "mesh");
      return;
    case MeshFormat::Off:
      write_file_atomically(
          path, [&](ChunkedWriter& out) { write_off(mesh, opt, out); }, "mesh");
      return;
    case MeshFormat::Obj:
      write_file_atomically(
          path, [&](ChunkedWriter& out) { write_obj(mesh, opt, out); }, "mesh");
      return;
    case MeshFormat::Stl:
      write_file_atomically(
          path, [&](ChunkedWriter& out) { write_stl(mesh, opt, out); }, "mesh");
      return;
    case MeshFormat::Vtk:
      write_file_atomically(
          path, [&](ChunkedWriter& out) { write_vtk(mesh, attributes, opt, out); }, "mesh");
      return;
    case MeshFormat::Vtp:
    case MeshFormat::Vtu:
      write_file_atomically(
          path, [&](ChunkedWriter& out) { write_vtk_xml(mesh, attributes, opt, format == MeshFormat::Vtu, out); },
          "mesh");
      return;
  }
}

double PositionStorage::stored(double x) const {
  if (!std::isfinite(x)) return x;
  switch (kind) {
    case Kind::Exact:
      return x;
    case Kind::Float32:
      return static_cast<double>(static_cast<float>(x));
    case Kind::Float32Text: {
      // The text append_number() writes, read back as the nearest double.
      std::array<char, 64> buf;
      const std::to_chars_result r = std::to_chars(buf.data(), buf.data() + buf.size(), static_cast<float>(x));
      double back = x;
      std::from_chars(buf.data(), r.ptr, back);
      return back;
    }
    case Kind::Decimals: {
      // Through the text itself: the decimal a correctly rounding printf
      // writes, read back as the nearest double (what every reader does).
      std::array<char, 400> buf;  // a fixed-format double needs at most 309 + 1 + 17 digits
      const std::to_chars_result r =
          std::to_chars(buf.data(), buf.data() + buf.size(), x, std::chars_format::fixed, decimals);
      double back = x;
      std::from_chars(buf.data(), r.ptr, back);
      return back;
    }
  }
  return x;
}

double PositionStorage::max_error(const IndexedMesh& mesh) const {
  if (kind == Kind::Exact) return 0;
  double largest = 0;
  for (const Vec3& p : mesh.positions)
    if (p.allFinite()) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  if (kind == Kind::Float32) return std::ldexp(largest, -24) * std::sqrt(3.0);      // half a float32 ulp per axis
  if (kind == Kind::Float32Text) return std::ldexp(largest, -23) * std::sqrt(3.0);  // the float's, then the text's
  // Half a unit of the last decimal, then the decimal read as the nearest
  // double (half a double ulp, which matters only at many decimals).
  return (0.5 * std::pow(10.0, -decimals) + std::ldexp(largest, -53)) * std::sqrt(3.0);
}

std::string PositionStorage::describe() const {
  switch (kind) {
    case Kind::Exact:
      return "exact doubles";
    case Kind::Float32:
      return "float32";
    case Kind::Float32Text:
      return "float32 text";
    case Kind::Decimals:
      return std::to_string(decimals) + " decimals";
  }
  return "";
}

PositionStorage position_storage(MeshFormat format, const MeshWriteOptions& opt) {
  const bool binary = (format == MeshFormat::Ply || format == MeshFormat::Stl) && !opt.ascii;
  if (binary && (format == MeshFormat::Stl || !opt.double_precision)) return {PositionStorage::Kind::Float32, 0};
  if (!opt.double_precision) return {PositionStorage::Kind::Float32Text, 0};
  return {};
}

bool float32_coordinates(const IndexedMesh& mesh) {
  const PositionStorage value{PositionStorage::Kind::Float32, 0}, text{PositionStorage::Kind::Float32Text, 0};
  for (const Vec3& p : mesh.positions)
    for (int k = 0; k < 3; ++k)
      if (value.stored(p[k]) != p[k] && text.stored(p[k]) != p[k]) return false;
  return !mesh.positions.empty();
}

double position_rounding(MeshFormat format, const IndexedMesh& mesh) {
  // Binary STL holds floats only; an ASCII STL may hold exact doubles.
  if (format != MeshFormat::Stl || !float32_coordinates(mesh)) return 0;
  return 2 * PositionStorage{PositionStorage::Kind::Float32Text, 0}.max_error(mesh);
}

IndexedMesh read_mesh(const std::string& path, std::vector<VertexAttribute>* attributes) {
  const MeshFormat format = mesh_format_from_extension(path);
  return read_mesh_from_bytes(read_file(path), format, path, attributes);
}

IndexedMesh read_mesh_from_bytes(const std::string& data, MeshFormat format, const std::string& name,
                                 std::vector<VertexAttribute>* attributes) {
  std::vector<VertexAttribute> ignored;
  std::vector<VertexAttribute>& out = attributes != nullptr ? *attributes : ignored;
  out.clear();
  switch (format) {
    case MeshFormat::Ply:
      return read_ply(name, data, out);
    case MeshFormat::Off:
      return read_off(name, data);
    case MeshFormat::Obj:
      return read_obj(name, data);
    case MeshFormat::Stl:
      return read_stl(name, data);
    case MeshFormat::Vtk:
      return read_vtk(name, data, out);
    case MeshFormat::Vtp:
    case MeshFormat::Vtu:
      return read_vtk_xml(name, data, out);
  }
  return {};
}

}  // namespace skinmesh::geometry
