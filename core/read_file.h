// core/read_file.h: a whole file into memory, the first step of every reader
// (mesh files in geometry/io and skin/skin_mesh_io, molecule files in
// skin/molecule_io), so that each parses text or bytes without I/O of its own.
#pragma once

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include "core/errors.h"

namespace skinmesh {

/// The whole content of `path`, read in binary mode. Throws InputError(path, 0,
/// "cannot open file (<reason>)") or InputError(path, 0, "cannot read file
/// (<reason>)").
inline std::string read_file(const std::string& path) {
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

}  // namespace skinmesh
