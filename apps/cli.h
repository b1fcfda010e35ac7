// apps/cli.h: command-line argument parsing for skinmesh (options are parsed
// once, here; the library takes typed structs, STYLE.md §3).
#pragma once

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/errors.h"

namespace skinmesh::cli {

/// A malformed command line (unknown option, missing value, bad number).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Options that take a value; every other option is a flag.
inline const std::set<std::string>& value_options() {
  static const std::set<std::string> s = {"--probe", "--format", "--direction", "-o",       "--stats",
                                          "--C",     "--Q",      "--min-angle", "--dump-at",
                                          "--max-steps", "--dump-partial"};
  return s;
}
/// Flags (options without a value).
inline const std::set<std::string>& flag_options() {
  static const std::set<std::string> s = {"--keep-water", "--no-hydrogens", "--quiet", "--json",
                                          "--help",       "-h",             "--no-check", "--force",
                                          "--no-self-intersections",        "--no-rdt",
                                          "--paranoid",   "--trace"};
  return s;
}

/// Parses a finite number; throws UsageError naming the option.
inline double parse_number(const std::string& s, const std::string& what) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE || !std::isfinite(v))
    throw UsageError(what + " expects a number, got '" + s + "'");
  return v;
}

/// Parses "a,b,c" into numbers.
inline std::vector<double> parse_numbers(const std::string& s, const std::string& what) {
  std::vector<double> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = s.find(',', start);
    out.push_back(parse_number(s.substr(start, comma - start), what));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

/// Positional arguments, flags and valued options of one command.
class Args {
 public:
  Args(int argc, char** argv) {
    for (int i = 0; i < argc; ++i) {
      std::string a = argv[i];
      if (a.size() > 1 && a[0] == '-' && !(a.size() > 1 && (std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.'))) {
        std::string val;
        bool has_val = false;
        if (const auto eq = a.find('='); eq != std::string::npos && a.rfind("--", 0) == 0) {
          val = a.substr(eq + 1);
          a = a.substr(0, eq);
          has_val = true;
        }
        if (value_options().count(a)) {
          if (!has_val) {
            if (i + 1 >= argc) throw UsageError("option " + a + " needs a value");
            val = argv[++i];
          }
          values_[a] = val;
        } else if (flag_options().count(a)) {
          if (has_val) throw UsageError("option " + a + " takes no value");
          flags_.insert(a == "-h" ? "--help" : a);
        } else {
          throw UsageError("unknown option '" + a + "'");
        }
      } else {
        positional_.push_back(a);
      }
    }
  }
  bool flag(const std::string& name) const { return flags_.count(name) > 0; }
  std::optional<std::string> value(const std::string& name) const {
    auto it = values_.find(name);
    if (it == values_.end()) return std::nullopt;
    return it->second;
  }
  double number(const std::string& name, double fallback) const {
    auto v = value(name);
    return v ? parse_number(*v, name) : fallback;
  }
  const std::string& positional(std::size_t i) const { return positional_.at(i); }
  /// Throws UsageError unless there are exactly n positional arguments.
  void expect_positional(std::size_t n, const std::string& usage) const {
    if (positional_.size() != n)
      throw UsageError("expected " + std::to_string(n) + " argument" + (n == 1 ? "" : "s") + ": " + usage);
  }

 private:
  std::vector<std::string> positional_;
  std::set<std::string> flags_;
  std::map<std::string, std::string> values_;
};

/// Writes text to a file through a temporary file and a rename (no partial
/// file on failure). Throws InputError(path, 0, ...) if it cannot write.
inline void write_text_file(const std::string& path, const std::string& text) {
  if (path == "-") {
    std::fwrite(text.data(), 1, text.size(), stdout);
    return;
  }
  const std::string tmp = path + ".tmp";
  {
    std::ofstream os(tmp, std::ios::binary);
    if (!os) throw InputError(path, 0, "cannot write file");
    os << text;
    if (!os.flush()) {
      std::remove(tmp.c_str());
      throw InputError(path, 0, "cannot write file");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw InputError(path, 0, "cannot write file");
  }
}

}  // namespace skinmesh::cli
