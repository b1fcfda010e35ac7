// core/binary_io.h: raw values in and out of binary streams, for the files
// one process writes and another process of the same build reads (the cut
// and region files of a decomposition carried out over several processes:
// decompose/region_files.h). Values keep their bytes: a double read back is
// the double written, so a mesh made from files is the mesh made in memory.
// Native byte order; the files say which with a marker their readers test.
#pragma once

#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <type_traits>
#include <vector>

#include "core/errors.h"

namespace skinmesh {

/// Writes the bytes of `value` (trivially copyable).
template <class T>
void put_raw(std::ostream& os, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>, "put_raw: T must be trivially copyable");
  os.write(reinterpret_cast<const char*>(&value), sizeof(T));
}

/// Reads the bytes of a T that put_raw() wrote. Throws InputError naming
/// `file` if the stream ends first.
template <class T>
T get_raw(std::istream& is, const std::string& file) {
  static_assert(std::is_trivially_copyable_v<T>, "get_raw: T must be trivially copyable");
  T value;
  if (!is.read(reinterpret_cast<char*>(&value), sizeof(T)))
    throw InputError(file, 0, "the file ends early (truncated, or not written by this program)");
  return value;
}

/// Reads `n` bytes into `data`; InputError naming `file` if the stream ends first.
inline void get_bytes(std::istream& is, void* data, std::size_t n, const std::string& file) {
  if (n > 0 && !is.read(static_cast<char*>(data), static_cast<std::streamsize>(n)))
    throw InputError(file, 0, "the file ends early (truncated, or not written by this program)");
}

/// A count read from a file, refused above `limit` (a damaged file must not
/// make the reader allocate without bound).
inline std::uint64_t get_count(std::istream& is, const std::string& file,
                               std::uint64_t limit = std::uint64_t{1} << 40) {
  const auto n = get_raw<std::uint64_t>(is, file);
  if (n > limit) throw InputError(file, 0, "a count of " + std::to_string(n) + " is out of range (a damaged file)");
  return n;
}

/// A string: its length, then its bytes.
inline void put_string(std::ostream& os, const std::string& s) {
  put_raw<std::uint64_t>(os, s.size());
  os.write(s.data(), static_cast<std::streamsize>(s.size()));
}
inline std::string get_string(std::istream& is, const std::string& file) {
  std::string s(get_count(is, file, std::uint64_t{1} << 30), '\0');
  get_bytes(is, s.data(), s.size(), file);
  return s;
}

/// A vector of trivially copyable values, or of Eigen's fixed vectors (whose
/// bytes are their value): its size, then its elements' bytes.
template <class T>
void put_vector(std::ostream& os, const std::vector<T>& v) {
  put_raw<std::uint64_t>(os, v.size());
  os.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
}
template <class T>
std::vector<T> get_vector(std::istream& is, const std::string& file) {
  std::vector<T> v(get_count(is, file, (std::uint64_t{1} << 40) / sizeof(T)));
  get_bytes(is, v.data(), v.size() * sizeof(T), file);
  return v;
}

}  // namespace skinmesh
