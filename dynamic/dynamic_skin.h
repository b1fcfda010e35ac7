// dynamic/dynamic_skin.h: the dynamic-skin baseline — the algorithm of
// H.-L. Cheng, T. K. Dey, H. Edelsbrunner and J. Sullivan, "Dynamic skin
// triangulation" (Discrete Comput. Geom. 25, 2001), which Cheng & Shi 2004
// compare their sweep with in Table 1 — rewritten from what is known of it on
// the project's own kernel: a sample on the skin, its 3D Delaunay
// triangulation, the restricted Delaunay triangulation as the mesh, [L]/[U]
// kept by vertex deletion and insertion while the skin grows from small
// spheres to its final shape. A static variant (no growth) samples and
// refines the final skin directly.
// Notes: papers/dynamic/dynamic_skin.md
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/stage_clock.h"
#include "dynamic/sample_triangulation.h"
#include "geometry/kernel/predicates.h"
#include "geometry/kernel/weighted_point.h"
#include "geometry/mesh/indexed_mesh.h"
#include "skin/size_conditions.h"
#include "skin/skin_surface.h"
#include "skin/vertex_data.h"

namespace skinmesh::dynamic {

/// Options of the baseline.
struct DynamicOptions {
  /// Grow the skin from small spheres (the dynamic algorithm, default); false:
  /// the static variant, which samples the final skin and refines it.
  bool growth = true;
  /// Spacing of the template sample of a sphere patch, as a fraction of the
  /// sphere's radius (= rho on it): 0.2 puts triangles of circumradius about
  /// 0.115 rho, inside [U] (0.132 rho) and [L] (edges > 0.097 rho).
  double seed_spacing = 0.2;
  /// Growth: largest motion of a sample in one step, as a fraction of
  /// max(rho, rho_floor) at the sample.
  double max_step_motion = 1.0;
  /// Growth: rho floor as a fraction of the smallest final atom sphere radius
  /// sqrt(w/2); during growth [U] uses max(rho, floor), so that the sample
  /// stays bounded near the critical points of the growth, where rho -> 0
  /// (papers/dynamic/dynamic_skin.md "Events"). The final skin is refined
  /// with the true rho.
  double rho_floor_fraction = 0.25;
  /// Global rounds of SampleTriangulation::refine() per growth step and at
  /// the end.
  int growth_rounds = 8;
  int final_rounds = 60;
  /// Called with the sample and its restricted Delaunay triangulation
  /// (SampleTriangulation::extract) after the refinement of every growth step
  /// ("growth") and after the final refinement ("refine"); empty: not
  /// called. For recorders (trace/trace_recorder.h); positions are in the
  /// local frame (mesher::MeshResult::frame_centre). The run is the same with
  /// or without an observer.
  std::function<void(const char* stage, const SampleTriangulation&)> observer;
};

/// What the baseline did.
struct DynamicStats {
  SampleStats samples;
  std::size_t steps = 0;                       ///< growth steps (levels visited before the final one)
  std::size_t births = 0;                      ///< sphere patches seeded during growth (static: at the start)
  std::size_t lost_samples = 0;                ///< samples deleted because the level set left them (a void closed)
  double start_level = 0;                      ///< first level c of the growth (Å²; weights shifted by 2c)
  std::size_t peak_samples = 0;                ///< largest sample size seen
  std::size_t peak_tets = 0;                   ///< largest number of Delaunay tetrahedra seen
  std::uint64_t kinetic_moves = 0, moves = 0;  ///< sample moves, and those that kept Del(P)
  bool converged = false;                      ///< the final refinement met every condition it checks
  /// Operation counts of the 3D Delaunay triangulation (where the time goes).
  geometry::DelaunayTriangulation::Stats delaunay;
  /// Predicate calls of the whole run on the calling thread, and how many
  /// needed exact arithmetic or symbolic perturbation (geometry/kernel/predicates.h).
  geometry::PredicateStats predicates;
};

/// Throws std::invalid_argument if an option is out of range (seed spacing,
/// step motion or rho floor fraction outside (0, 1]).
void validate(const DynamicOptions& options);

/// The dynamic-skin baseline on `skin` (centres Å, weights Å², shrink factor
/// 1/2; the caller has refused singular skins, skin::require_non_singular):
/// the restricted Delaunay triangulation of a sample kept under [L] and [U]
/// of `size` (Cheng & Shi §2.2) while the skin grows (options.growth) or on
/// the final skin alone (the static variant). Returns the mesh in the skin's
/// frame (Å; triangles counter-clockwise seen from outside; per vertex the
/// unit outward normal), its vertex data in `vertex_data` (atom, rho and
/// mixed-cell dimension per vertex) and fills `stats`
/// except stats.predicates, which the caller measures. Ends the stages
/// "growth" (not for the static variant), "refine" (the final level) and
/// "output" on `clock`. Throws GeometryError if a sample cannot be placed.
geometry::IndexedMesh mesh_dynamic(const skin::SkinSurface& skin, const skin::SizeConstants& size,
                                   const DynamicOptions& options, StageClock& clock, DynamicStats& stats,
                                   skin::SkinVertexData& vertex_data);

}  // namespace skinmesh::dynamic
