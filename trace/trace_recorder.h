// trace/trace_recorder.h: the recorder behind `skinmesh trace` — runs the
// sweep pipeline (mesher/pipeline.h) or the dynamic-skin baseline
// (dynamic/dynamic_skin.h) with observers on every operation and returns the
// history a student needs to watch the algorithm: the critical points and the
// Morse–Smale arcs (§3), the partial mesh after every operation of the sweep
// (creation, creep, contact, wings, hold, bridge, small hole, seal; §4.1) or
// every k-th one, the local refinement's flips, contractions and insertions
// (§4.3), the angle improvement, and the final mesh with its per-triangle
// quality (min angle, [L] and [U] ratios, §2.2). The document's format is
// trace/FORMAT.md; the viewer page that shows it is trace/viewer/.
// Notes: papers/trace/README.md
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/kernel/weighted_point.h"
#include "mesher/pipeline.h"

namespace skinmesh::trace {

/// Options of a recording.
struct TraceOptions {
  /// Options of the pipeline, its algorithm included (the recorder sets its
  /// observers: the sweep's, the refinement's, the stages' and the baseline's).
  /// mesh.progress also hears the first run that counts the operations, as
  /// stages named "count <stage>".
  mesher::MeshOptions mesh;
  /// Record at most about this many steps: consecutive operations are merged
  /// k to a step beyond it (creations, bridges and seals always end a step).
  /// The numbers of operations are counted by a first run without recording.
  std::size_t max_steps = 2000;
  /// Operations per recorded step (0: chosen from max_steps).
  long every = 0;
  /// Upper bound (bytes, roughly) of what the dynamic algorithm's growth
  /// steps may add to the document: every growth step moves every sample, so
  /// only some are recorded.
  std::size_t growth_budget_bytes = 25u << 20;
  /// Shown in the page: its title, the input's file name, the probe radius
  /// (Å; negative: weighted points given directly).
  std::string title, input;
  double probe = -1;
};

/// What a recording measured, for the command line's report.
struct TraceSummary {
  std::size_t steps = 0, operations = 0, face_records = 0, vertices = 0;
  std::size_t triangles = 0;  ///< of the final mesh
  double min_angle_deg = 0;   ///< of the final mesh
  bool checked = false, ok = true;
  std::vector<std::string> problems;  ///< the check's, if it failed
};

/// Runs the algorithm on `points` (centres Å, weights Å²) and returns the
/// trace document (trace/FORMAT.md). Throws what mesher::mesh_skin()
/// throws, and std::invalid_argument for fewer than 10 steps. A mesh that fails its check is recorded all the same; the
/// document's "check" says so, and so does `summary`.
nlohmann::json record_trace(const std::vector<geometry::WeightedPoint>& points, const TraceOptions& options,
                            TraceSummary* summary = nullptr);

/// The placeholder the viewer template holds exactly once, inside
/// <script id="skinmesh-trace" type="application/json">.
inline constexpr const char* kTracePlaceholder = "__SKINMESH_TRACE_JSON__";

/// The page: `viewer_template` (the built trace/viewer page) with the
/// placeholder replaced by the document, every "<" written "\u003c" (so that
/// no string in it can end the script element or open a comment). Throws std::runtime_error if
/// the template does not hold the placeholder exactly once.
std::string fill_viewer_template(const std::string& viewer_template, const nlohmann::json& document);

}  // namespace skinmesh::trace
