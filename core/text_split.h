// core/text_split.h: splitting text into lines and blank-separated fields, and
// ASCII case folding,
// shared by the readers (geometry/io/mesh_io, skin/molecule_io). Views point into
// the caller's text, which must outlive them.
#pragma once

#include <cctype>
#include <string>
#include <string_view>
#include <vector>

namespace skinmesh {

/// The lower-case copy of `s` (ASCII letters only).
inline std::string lowercase(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

/// The upper-case copy of `s` (ASCII letters only).
inline std::string uppercase(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

/// True for ASCII white space (space, tab, CR, LF, FF, VT).
inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

/// s without leading and trailing white space.
inline std::string_view trim(std::string_view s) {
  while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
  return s;
}

/// The white-space separated fields of s.
inline std::vector<std::string_view> split_blanks(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && is_blank(s[i])) ++i;
    const std::size_t start = i;
    while (i < s.size() && !is_blank(s[i])) ++i;
    if (i > start) out.push_back(s.substr(start, i - start));
  }
  return out;
}

/// The white-space separated fields of `line` before its first '#' (a
/// comment to the end of the line, as in OBJ, OFF and XYZR files).
inline std::vector<std::string_view> fields_before_comment(std::string_view line) {
  if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
  return split_blanks(line);
}

/// The lines of `text` without their "\n" or "\r\n"; entry k is line k + 1.
inline std::vector<std::string_view> split_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    start = end + 1;
  }
  return lines;
}

}  // namespace skinmesh
