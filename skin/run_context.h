// skin/run_context.h: what every stage of one meshing run must agree on — the
// size constants C and Q, the threads, where progress goes, and whether a
// stage may give back the cells the mixed complex made — held once and handed
// to each stage beside its own tuning options, which hold none of it.
// Notes: papers/mesher/pipeline.md ("The run context")
#pragma once

#include <atomic>
#include <functional>
#include <string>

#include "skin/size_conditions.h"

namespace skinmesh::skin {

/// The settings shared by the stages of one run (the sweep, the refinement,
/// the angle improvement, the check, the Morse–Smale complex, the
/// decomposition). A stage's options say how it works; the context says
/// what all stages of the run agree on, so that no stage can disagree: the
/// pipeline (mesher::mesh_skin) builds it once from MeshOptions. A
/// default-constructed context is the paper's constants on the calling
/// thread, without progress reports, leaving the complex's made cells alone.
struct RunContext {
  /// C and Q of [L] and [U] (Cheng & Shi §2.2): the sweep's tangent-disc
  /// window, the refinement's and the angle improvement's targets, and the
  /// check's thresholds all derive from them.
  SizeConstants size;
  /// Threads a stage may use; 0: every core of the machine (each stage reads
  /// it through core/parallel.h's thread_count()). No output depends on it:
  /// the stages split independent work only.
  int threads = 1;
  /// Called with a stage name and the fraction of it done (0..1), from the
  /// calling thread; empty: no reports. The library itself prints nothing.
  std::function<void(const std::string& stage, double fraction)> progress;
  /// The stage may give back the mixed complex's made cells and planes
  /// (MixedComplex::release_made()) while it runs: the caller owns the skin
  /// and no other thread reads it. Each stage makes again what it reads, bit
  /// for bit the same, so the output does not depend on it.
  bool release_made_cells = false;
  /// Set by the caller once it no longer wants the stage's result (a slab
  /// swept ahead that no round will ask for: decompose/slab_pool.h). The
  /// sweep reads it between departures and then throws Cancelled
  /// (core/errors.h); nullptr: never.
  const std::atomic<bool>* cancel = nullptr;

  /// This context with `t` threads (a part of the run that gives its threads
  /// to parts beside it).
  RunContext with_threads(int t) const {
    RunContext c = *this;
    c.threads = t;
    return c;
  }
  /// This context without progress reports (a part of the run whose progress
  /// the caller reports itself).
  RunContext quiet() const {
    RunContext c = *this;
    c.progress = nullptr;
    return c;
  }
};

}  // namespace skinmesh::skin
