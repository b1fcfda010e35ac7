// verify/skin_mesh_check.h: the verifier of a mesh against the analytic skin,
// shared by `skinmesh check`, `skinmesh mesh`, the tests and the benchmarks.
// It composes geometry::check_mesh (closed, manifold, oriented, components,
// exact self-intersections, angles) with the skin-specific checks: vertex
// distance to the skin, outward orientation, [L], [U] (Cheng & Shi §2.2),
// restricted Delaunay (§2.2, §4.3) and the expected topology (skin/dual_complex).
// Notes: papers/verify/skin_mesh_check.md
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "geometry/check/mesh_checks.h"
#include "geometry/mesh/indexed_mesh.h"
#include "skin/dual_complex.h"
#include "skin/run_context.h"
#include "skin/shells.h"
#include "skin/skin_surface.h"

namespace skinmesh::verify {

/// What the skin check verifies and with which thresholds.
struct SkinCheckOptions {
  /// Largest admissible |f(v)| / |grad f(v)| at a vertex (Å) for a skin of
  /// length scale L <= 100 Å; above, it grows with L (tolerance =
  /// max_vertex_distance · max(1, L / 100 Å), about 1e-11 L: scale-free, and
  /// still ~1e5 units in the last place of a coordinate of size L).
  double max_vertex_distance = 1e-9;
  /// Smallest admissible angle (degrees); the [L]+[U] bound is 21.55°.
  double min_angle_deg = 21.5;
  bool check_self_intersections = true;
  bool check_restricted_delaunay = true;
  /// Count the edges violating [L] and the triangles violating [U] (default).
  /// The check of a mesh as a lossy file stores it (mesher/pipeline.h,
  /// MeshOptions::stored_positions) turns this and the restricted Delaunay
  /// test off: those are strict inequalities that refinement meets with
  /// arbitrarily small margins, so any rounding may tip one without damage a
  /// reader can see, and they hold for the positions before rounding.
  bool check_size_conditions = true;
  /// Expected Euler characteristic of each skin component (any order), if the
  /// caller knows it (from the Morse–Smale complex); empty: only the number of
  /// components and the total are compared, plus the multiset when the total
  /// genus is 0 or there is a single component.
  std::vector<std::int64_t> expected_component_euler;
  /// The topology of the skin from its dual complex K0
  /// (skin::dual_complex_topology of the same skin), if the caller has
  /// already computed it (the pipeline has); empty: computed here. It is a
  /// deterministic function of the skin, so the report is the same either way.
  std::optional<skin::SkinTopology> expected_topology;
  /// The shells the mesh holds of the skin's (skin/shells.h), when it holds
  /// some only (`skinmesh check --cavities ...`) and expected_component_euler
  /// is empty: the topology test then counts the mesh's bodies (components
  /// enclosing a positive volume) and cavities against K0's, and each
  /// component's genus against the skin's total (papers/skin/shells.md).
  skin::ShellSelection shells;
  /// The mixed cell holding each vertex of the mesh, if the caller knows it
  /// (the mesher does), one per vertex: each vertex's point location starts
  /// there. Empty: from the cell of a neighbouring vertex. A wrong cell costs
  /// only a longer walk; a vertex on a face shared by two cells may be read
  /// in either (f, grad f and rho are continuous there, equal up to rounding).
  std::span<const Index> vertex_cells;
};

/// Result of check_skin_mesh().
struct SkinCheckReport {
  geometry::MeshCheckReport mesh;
  skin::SkinTopology expected;
  std::vector<std::int64_t> component_euler;           ///< measured, sorted
  std::vector<std::int64_t> expected_component_euler;  ///< sorted; empty if unknown
  bool topology_matches = false;
  double max_vertex_distance = 0;  ///< max |f| / |grad f| over vertices (Å)
  Index worst_vertex = kInvalidIndex;
  std::size_t num_far_vertices = 0;      ///< above vertex_distance_tolerance
  double vertex_distance_tolerance = 0;  ///< the tolerance applied (Å), see SkinCheckOptions
  std::size_t num_inward_triangles = 0;  ///< normal disagrees with the skin normal
  std::size_t num_L_violations = 0;      ///< edges violating [L]
  std::size_t num_U_violations = 0;      ///< triangles violating [U]
  bool restricted_delaunay_checked = false;
  bool size_conditions_checked = false;  ///< [L] and [U] counted (SkinCheckOptions::check_size_conditions)
  /// Triangles whose surface Delaunay ball holds another vertex strictly inside
  /// (relative tolerance 1e-9), or whose dual line misses the skin.
  std::size_t num_rdt_violations = 0;
  std::vector<Index> rdt_violation_examples;
  double min_angle_required_deg = 0;
  std::vector<std::string> problems;

  /// True if every check passed.
  bool ok() const { return problems.empty(); }
  /// The report as JSON (the mesh report nested under "mesh").
  std::string to_json() const;
};

/// Verifies `mesh` against the skin. Pre: the mesh's vertices are meant to lie
/// on `skin`. [L] and [U] are those of run.size. With run.threads of 2 or
/// more (0: every core of the machine), the mesh-only checks of
/// geometry::check_mesh (closed, manifold, orientation, exact
/// self-intersections, angles) run on a thread of their own beside the skin
/// checks, and both split their loops (samples of the skin at the vertices,
/// restricted Delaunay balls, the self-intersection sweep) over the threads;
/// 1 runs everything on the calling thread. The report is the same for every
/// count. Throws nothing but std::bad_alloc and GeometryError from point
/// location of vertices outside the bounding tetrahedron.
SkinCheckReport check_skin_mesh(const skin::SkinSurface& skin, const geometry::IndexedMesh& mesh,
                                const SkinCheckOptions& options = {}, const skin::RunContext& run = {});

}  // namespace skinmesh::verify
