// mesher/summary.h: the result schema of a meshing run — the JSON object
// that `skinmesh mesh --stats` writes and that Python's Mesh.stats holds,
// built in one place so that both report the same fields.
// Notes: papers/mesher/pipeline.md ("The result schema")
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/kernel/weighted_point.h"
#include "mesher/pipeline.h"

namespace skinmesh::mesher {

/// What the caller knows of a run beyond its MeshResult.
struct SummaryContext {
  std::string input;   ///< the molecule file ("" for atoms given directly)
  std::string output;  ///< the mesh file ("" if none is written)
  std::size_t atoms = 0;
  /// The weighted points that were meshed, if the exact skin's area and
  /// volume are wanted beside the mesh's (skin/skin_measures.h); null: not
  /// computed. A failing integration is reported under "analytic" as
  /// {"error": …} with a warning on stderr; the mesh's numbers stay.
  const std::vector<geometry::WeightedPoint>* exact_measures_of = nullptr;
  /// Seconds of the program's own stages, placed before ("read") and after
  /// ("write", "total") the pipeline's in "seconds"; negative: absent.
  double read_seconds = -1, write_seconds = -1, total_seconds = -1;
  /// Peak resident memory of the process (bytes); 0: absent.
  std::size_t peak_memory_bytes = 0;
  /// Peak resident memory of each stage (bytes, sampled), in the order they
  /// ended ("read", the pipeline's stages, "write"); empty: absent.
  std::vector<std::pair<std::string, std::size_t>> stage_peak_memory_bytes;
  /// The per-atom areas of the exact skin and of the mesh (Å², one per atom),
  /// if computed: "surface"."atom_areas" gets their sums, the atoms with area
  /// and the file they were written to; null: absent.
  const std::vector<double>* skin_atom_areas = nullptr;
  const std::vector<double>* mesh_atom_areas = nullptr;
  std::string area_file;
};

/// The summary of a run: input, output, atoms, probe radius, vertices,
/// triangles, "surface" (area Å², enclosed volume Å³ per component and in
/// all, from the mesh; "analytic", the exact skin's, and the relative
/// differences when context.exact_measures_of is given), the check's verdict
/// ("checked", "problems", and when checked "min_angle_deg",
/// "max_angle_deg", "checks_passed"), critical points, the algorithm, the
/// threads, the operation counts of the algorithm that ran, "seconds" per
/// stage (the exact integration's as "analytic"; a decomposed sweep's parts
/// as "sweep_parts": per slab, bands, glue, retried) and the peak memory, of
/// the process and per stage. Keys keep this order.
nlohmann::ordered_json run_summary(const MeshResult& result, const MeshOptions& options, const SummaryContext& context);

}  // namespace skinmesh::mesher
