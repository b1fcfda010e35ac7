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
#include "geometry/io/mesh_io_internal.h"

namespace skinmesh::geometry {

namespace mesh_io_detail {

namespace {

/// All of `token` as a finite double, or nullopt.
std::optional<double> to_double(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (token.empty() || ec != std::errc() || ptr != token.data() + token.size() || !std::isfinite(v))
    return std::nullopt;
  return v;
}

}  // namespace

// Shared Helpers

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

void append_triangle_lines(std::string& out, const std::vector<std::array<Index, 3>>& triangles) {
  for (const auto& t : triangles) {
    out += '3';
    for (Index v : t) {
      out += ' ';
      append_index(out, v);
    }
    out += '\n';
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

using mesh_io_detail::msms_text;
using mesh_io_detail::obj_text;
using mesh_io_detail::off_text;
using mesh_io_detail::ply_bytes;
using mesh_io_detail::read_msms;
using mesh_io_detail::read_msms_concatenated;
using mesh_io_detail::read_obj;
using mesh_io_detail::read_off;
using mesh_io_detail::read_ply;
using mesh_io_detail::read_stl;
using mesh_io_detail::read_vtk;
using mesh_io_detail::stl_bytes;
using mesh_io_detail::vtk_text;

/// The lower-case copy of `s` (ASCII letters only).
std::string lowercase(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

/// Checks the preconditions of write_mesh() (std::logic_error through
/// SKINMESH_ASSERT_MSG): at most 2^31 - 1 vertices (PLY int indices), normals and
/// atom ids empty or one per vertex, every triangle index in range.
void check_writable(const IndexedMesh& m) {
  const std::size_t n = m.positions.size();
  SKINMESH_ASSERT_MSG(n <= static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()),
                      "too many vertices for PLY int indices");
  SKINMESH_ASSERT_MSG(m.normals.empty() || m.normals.size() == n, "one normal per vertex");
  SKINMESH_ASSERT_MSG(m.atom.empty() || m.atom.size() == n, "one atom id per vertex");
  SKINMESH_ASSERT_MSG(m.rho.empty() || m.rho.size() == n, "one rho per vertex");
  SKINMESH_ASSERT_MSG(m.patch.empty() || m.patch.size() == n, "one patch dimension per vertex");
  for (const auto& t : m.triangles)
    for (Index v : t) SKINMESH_ASSERT_MSG(v < n, "triangle index out of range");
}

}  // namespace

namespace {

/// Writes `bytes` to a fresh temporary file beside `path` and returns its
/// name. On failure the temporary is removed and InputError(path, 0, "cannot
/// write <what> (reason)") is thrown.
std::string write_temporary(const std::string& path, const std::string& bytes, const std::string& what) {
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
  if (std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size() || std::fflush(f) != 0) error = failure();
  if (std::fclose(f) != 0 && error == 0) error = failure();
  if (error != 0) {
    std::remove(tmp.c_str());
    throw InputError(path, 0, "cannot write " + what + " (" + std::strerror(error) + ")");
  }
  return tmp;
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

void write_file_atomically(const std::string& path, const std::string& bytes, const std::string& what) {
  rename_onto(write_temporary(path, bytes, what), path, what);
}

namespace {

/// The whole content of `path`, read in binary mode. Throws InputError(path, 0,
/// "cannot open file (...)" or "cannot read file (...)").
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

}  // namespace

// Mesh I/O Function Definitions

MeshFormat mesh_format_from_extension(const std::string& path) {
  const std::string p = lowercase(path);
  if (p.ends_with(".ply")) return MeshFormat::Ply;
  if (p.ends_with(".off")) return MeshFormat::Off;
  if (p.ends_with(".obj")) return MeshFormat::Obj;
  if (p.ends_with(".stl")) return MeshFormat::Stl;
  if (p.ends_with(".vtk")) return MeshFormat::Vtk;
  if (p.ends_with(".vert") || p.ends_with(".face")) return MeshFormat::Msms;
  throw InputError(path, 0, "unknown mesh format (expected .ply, .off, .obj, .stl, .vtk, or .vert/.face for MSMS)");
}

std::pair<std::string, std::string> msms_paths(const std::string& path) {
  const std::string p = lowercase(path);
  if (!p.ends_with(".vert") && !p.ends_with(".face"))
    throw InputError(path, 0, "an MSMS mesh is named NAME.vert or NAME.face");
  const std::string base = path.substr(0, path.size() - 5);
  return {base + ".vert", base + ".face"};
}

void write_mesh(const std::string& path, const IndexedMesh& mesh, const MeshWriteOptions& opt) {
  const MeshFormat format = mesh_format_from_extension(path);
  check_writable(mesh);
  switch (format) {
    case MeshFormat::Ply:
      write_file_atomically(path, ply_bytes(mesh, opt), "mesh");
      return;
    case MeshFormat::Off:
      write_file_atomically(path, off_text(mesh, opt), "mesh");
      return;
    case MeshFormat::Obj:
      write_file_atomically(path, obj_text(mesh, opt), "mesh");
      return;
    case MeshFormat::Stl:
      write_file_atomically(path, stl_bytes(mesh), "mesh");
      return;
    case MeshFormat::Vtk:
      write_file_atomically(path, vtk_text(mesh, opt), "mesh");
      return;
    case MeshFormat::Msms: {
      const auto [vert_path, face_path] = msms_paths(path);
      const std::string name = vert_path.substr(vert_path.find_last_of('/') + 1);
      const auto [vert, face] = msms_text(mesh, name.substr(0, name.size() - 5));
      // A folder in the way would fail the second rename only: refused first.
      for (const std::string& p : {face_path, vert_path})
        if (std::filesystem::is_directory(p)) throw InputError(p, 0, "cannot write mesh (a folder has this name)");
      // Both files are written to temporaries first, then renamed one right
      // after the other: a failure while writing leaves the old pair (if any)
      // as it was, never a new .face beside an old .vert.
      const std::string face_tmp = write_temporary(face_path, face, "mesh");
      std::string vert_tmp;
      try {
        vert_tmp = write_temporary(vert_path, vert, "mesh");
      } catch (...) {
        std::remove(face_tmp.c_str());
        throw;
      }
      try {
        rename_onto(face_tmp, face_path, "mesh");
      } catch (...) {
        std::remove(vert_tmp.c_str());
        throw;
      }
      rename_onto(vert_tmp, vert_path, "mesh");
      return;
    }
  }
}

double position_rounding(const std::string& path, const IndexedMesh& mesh) {
  switch (mesh_format_from_extension(path)) {
    case MeshFormat::Msms:
      return 1e-3;
    case MeshFormat::Stl: {
      double largest = 0;
      for (const Vec3& p : mesh.positions) largest = std::max(largest, p.cwiseAbs().maxCoeff());
      return 2 * std::ldexp(largest, -24) * std::sqrt(3.0);
    }
    default:
      return 0;
  }
}

IndexedMesh read_mesh(const std::string& path) {
  const MeshFormat format = mesh_format_from_extension(path);
  if (format == MeshFormat::Msms) {
    const auto [vert_path, face_path] = msms_paths(path);
    const std::string vert = read_bytes(vert_path);  // the .vert first: errors name it first
    return read_msms(vert_path, vert, face_path, read_bytes(face_path));
  }
  return read_mesh_from_bytes(read_bytes(path), format, path);
}

IndexedMesh read_mesh_from_bytes(const std::string& data, MeshFormat format, const std::string& name) {
  switch (format) {
    case MeshFormat::Ply:
      return read_ply(name, data);
    case MeshFormat::Off:
      return read_off(name, data);
    case MeshFormat::Obj:
      return read_obj(name, data);
    case MeshFormat::Stl:
      return read_stl(name, data);
    case MeshFormat::Vtk:
      return read_vtk(name, data);
    case MeshFormat::Msms:
      return read_msms_concatenated(name, data);
  }
  return {};
}

}  // namespace skinmesh::geometry
