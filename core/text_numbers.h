// core/text_numbers.h: numbers in text fields, read through std::from_chars
// (correctly rounded, locale-free), shared by the text readers of mesh files
// (geometry/io/mesh_io, skin/skin_mesh_io). Errors name the file and line.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

#include "core/errors.h"

namespace skinmesh {

/// All of `token` (a leading '+' allowed) as an integer, or nullopt.
inline std::optional<std::int64_t> to_int(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  std::int64_t v = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (token.empty() || ec != std::errc() || ptr != token.data() + token.size()) return std::nullopt;
  return v;
}

/// All of `token` (a leading '+' allowed) as a finite double, or nullopt.
inline std::optional<double> to_finite_double(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (token.empty() || ec != std::errc() || ptr != token.data() + token.size() || !std::isfinite(v))
    return std::nullopt;
  return v;
}

/// to_finite_double(token), or throws InputError(path, line, "non-numeric or
/// non-finite <what> '<token>'").
inline double number_or_throw(const std::string& path, int line, std::string_view token, const char* what) {
  if (std::optional<double> v = to_finite_double(token)) return *v;
  throw InputError(path, line, std::string("non-numeric or non-finite ") + what + " '" + std::string(token) + "'");
}

/// to_int(token), or throws InputError(path, line, "non-integer <what> '<token>'").
inline std::int64_t int_or_throw(const std::string& path, int line, std::string_view token, const char* what) {
  if (std::optional<std::int64_t> v = to_int(token)) return *v;
  throw InputError(path, line, std::string("non-integer ") + what + " '" + std::string(token) + "'");
}

}  // namespace skinmesh
