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

#include "dynamic/sample_triangulation.h"
#include "geometry/mesh/indexed_mesh.h"
#include "geometry/kernel/predicates.h"
#include "geometry/kernel/weighted_point.h"
#include "skin/size_conditions.h"
#include "verify/skin_mesh_check.h"
#include "skin/dual_complex.h"
#include "skin/molecule.h"

namespace skinmesh::dynamic {

/// Options of the baseline.
struct DynamicOptions {
  /// Probe radius (Å) for the Molecule overload: w = 2 (r + probe)².
  double probe_radius = 1.4;
  /// C and Q of [L] and [U], shared with the check (Cheng & Shi §2.2).
  skin::SizeConstants size;
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
  /// Verify the final mesh (verify/skin_mesh_check.h); the verdict is in
  /// DynamicResult::check.
  bool check = true;
  verify::SkinCheckOptions checks;
  /// Called with a stage name ("skin", "growth", "refine", "check") and the
  /// fraction done (0..1); empty: no reports. The library prints nothing.
  std::function<void(const std::string& stage, double fraction)> progress;
  /// Called with the sample and its restricted Delaunay triangulation
  /// (SampleTriangulation::extract) after the refinement of every growth step
  /// ("growth") and after the final refinement ("refine"); empty: not
  /// called. For recorders (trace/trace_recorder.h); positions are in the
  /// local frame (DynamicResult::frame_centre). The run is the same with or
  /// without an observer.
  std::function<void(const char* stage, const SampleTriangulation&)> observer;
};

/// What the baseline did.
struct DynamicStats {
  SampleStats samples;
  std::size_t steps = 0;         ///< growth steps (levels visited before the final one)
  std::size_t births = 0;        ///< sphere patches seeded during growth (static: at the start)
  std::size_t lost_samples = 0;  ///< samples deleted because the level set left them (a void closed)
  double start_level = 0;        ///< first level c of the growth (Å²; weights shifted by 2c)
  std::size_t peak_samples = 0;  ///< largest sample size seen
  std::size_t peak_tets = 0;     ///< largest number of Delaunay tetrahedra seen
  std::uint64_t kinetic_moves = 0, moves = 0;  ///< sample moves, and those that kept Del(P)
  bool converged = false;        ///< the final refinement met every condition it checks
  /// Operation counts of the 3D Delaunay triangulation (where the time goes).
  geometry::DelaunayTriangulation::Stats delaunay;
  /// Predicate calls of the whole run on the calling thread, and how many
  /// needed exact arithmetic or symbolic perturbation (geometry/kernel/predicates.h).
  geometry::PredicateStats predicates;
};

/// Result of mesh_skin_dynamic().
struct DynamicResult {
  /// The mesh (Å; triangles counter-clockwise seen from outside; per vertex
  /// unit outward normal and atom index).
  geometry::IndexedMesh mesh;
  skin::SkinTopology expected_topology;
  DynamicStats stats;
  bool checked = false;
  verify::SkinCheckReport check;
  /// Wall-clock seconds per stage: "skin", "growth" (absent for the static
  /// variant), "refine" (the final level), "output", "check".
  std::vector<std::pair<std::string, double>> seconds;
  Vec3 frame_centre = Vec3::Zero();
  bool ok() const { return !checked || check.ok(); }
};

/// Meshes the skin of `points` (centres Å, weights Å², shrink factor 1/2) with
/// the dynamic-skin baseline. Throws InputError for an empty input or a
/// singular skin (skin::require_non_singular, as mesh_skin does),
/// std::invalid_argument for options out of range. A mesh that
/// fails its check is returned with the report (ok() false).
DynamicResult mesh_skin_dynamic(const std::vector<geometry::WeightedPoint>& points,
                                const DynamicOptions& options = {});

/// mesh_skin_dynamic() of a molecule's atoms with options.probe_radius.
DynamicResult mesh_skin_dynamic(const skin::Molecule& molecule, const DynamicOptions& options = {});

}  // namespace skinmesh::dynamic
