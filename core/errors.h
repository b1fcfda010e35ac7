// core/errors.h: the typed exceptions of the project
// (papers/conventions.md §3 "Errors").
// Bad input throws InputError (file, line, problem); algorithm failures throw
// TopologyError or GeometryError carrying what went wrong.
#pragma once

#include <stdexcept>
#include <string>

namespace skinmesh {

/// Bad input: unreadable file, unknown format, non-numeric or non-finite
/// coordinate, non-positive radius, no atoms. `file` and `line` (1-based, 0 if
/// unknown) locate the problem; what() reads "file:line: problem".
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, int line, const std::string& problem)
      : std::runtime_error(format(file, line, problem)), file_(std::move(file)), line_(line), problem_(problem) {}
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& problem() const { return problem_; }

 private:
  static std::string format(const std::string& f, int line, const std::string& p) {
    std::string s;
    if (!f.empty()) {  // input passed by a caller, not read from a file: the problem alone
      s.append(f);
      if (line > 0) s.append(":").append(std::to_string(line));
      s.append(": ");
    }
    s.append(p);
    return s;
  }
  std::string file_;
  int line_;
  std::string problem_;
};

/// A combinatorial failure of an algorithm (a non-manifold flip, a front that
/// did not close, a Morse count that does not match the expected topology).
class TopologyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A numerical construction that failed (a projection without a root, a walk
/// that did not terminate).
class GeometryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A stage stopped because its caller no longer wants its result
/// (skin::RunContext::cancel): not a failure of the input or the algorithm.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled by the caller") {}
};

}  // namespace skinmesh
