// core/stage_clock.h: the stopwatch and progress reports of a pipeline's
// stages, shared by both algorithms (mesher/pipeline) and by the stages that
// time their own parts (dynamic/dynamic_skin).
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace skinmesh {

/// Wall-clock seconds per stage, in the order the stages ended, and progress
/// reports to an optional callback. A stage runs from the end of the previous
/// one (or the clock's construction) to its own end(). The library prints
/// nothing: the callback decides what a report shows.
class StageClock {
 public:
  /// Called with a stage name and the fraction of it done (0..1).
  using Progress = std::function<void(const std::string& stage, double fraction)>;

  explicit StageClock(Progress progress = {}) : progress_(std::move(progress)), last_(Clock::now()) {}

  /// Reports that `stage` starts (fraction 0).
  void begin(const char* stage) const { report(stage, 0.0); }
  /// Reports `fraction` (0..1) of `stage` done; nothing without a callback.
  void report(const std::string& stage, double fraction) const {
    if (progress_) progress_(stage, fraction);
  }
  /// Ends `stage`: records its seconds since the previous end and reports 1.
  void end(const char* stage) {
    const Clock::time_point now = Clock::now();
    seconds_.emplace_back(stage, std::chrono::duration<double>(now - last_).count());
    last_ = now;
    report(stage, 1.0);
  }
  /// The stages ended so far and their seconds, in order.
  const std::vector<std::pair<std::string, double>>& seconds() const { return seconds_; }

 private:
  using Clock = std::chrono::steady_clock;
  Progress progress_;
  Clock::time_point last_;
  std::vector<std::pair<std::string, double>> seconds_;
};

}  // namespace skinmesh
