// apps/output.h: what the command-line program writes besides meshes — text
// files written atomically (no partial file on failure) and a progress line on
// stderr for long runs.
#pragma once

#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include "core/errors.h"
#include "geometry/io/mesh_io.h"

namespace skinmesh::app {

/// Writes `text` to `path` ("-": standard output) atomically (no partial file
/// on failure; geometry::write_file_atomically). Throws InputError(path, 0,
/// "cannot write file (reason)") if it cannot write.
inline void write_text_file(const std::string& path, const std::string& text) {
  if (path == "-") {
    std::fwrite(text.data(), 1, text.size(), stdout);
    std::fflush(stdout);
    return;
  }
  geometry::write_file_atomically(path, text);
}

/// Throws InputError(path, 0, "cannot write file (...)") unless the folder of
/// `path` exists and is writable: checked before a long run, so that it does
/// not end in a write error. "-" (standard output) always passes.
inline void require_writable(const std::string& path) {
  if (path == "-") return;
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  const std::string dir = parent.empty() ? std::string(".") : parent.string();
  if (::access(dir.c_str(), W_OK) != 0)
    throw InputError(path, 0, std::string("cannot write file (") + std::strerror(errno) + ")");
}

/// A one-line progress display on stderr ("skinmesh: sweep  42%"), redrawn in
/// place at most ten times a second. It shows only when enabled, when stderr
/// is a terminal, and once the run has lasted a second, so short runs, logs
/// and pipes stay clean.
class ProgressReporter {
 public:
  explicit ProgressReporter(bool enabled) : enabled_(enabled && isatty(fileno(stderr))) {}
  /// Reports that `stage` is `fraction` (0..1) done.
  void report(const std::string& stage, double fraction) {
    if (!enabled_) return;
    const auto now = Clock::now();
    if (now - start_ < std::chrono::seconds(1)) return;
    if (stage == last_stage_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_stage_ = stage, last_draw_ = now;
    std::fprintf(stderr, "\rskinmesh: %-7s %3d%%", stage.c_str(), static_cast<int>(100 * fraction + 0.5));
    std::fflush(stderr);
    drawn_ = true;
  }
  /// Clears the progress line, if one was drawn.
  void finish() {
    if (drawn_) std::fprintf(stderr, "\r\033[K");
    drawn_ = false;
  }
  ~ProgressReporter() { finish(); }

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_;
  bool drawn_ = false;
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_draw_{};
  std::string last_stage_;
};

}  // namespace skinmesh::app
