// geometry/check/mesh_checks.h: check_mesh(), the verifier shared by the tests, the
// benchmarks and the CLI (papers/conventions.md §3 "Tests", like CDT's verifyTopology). It
// reads any IndexedMesh triangle soup, broken ones included, and reports its
// topology (closed, manifold, oriented, components, Euler characteristic,
// genus), its geometry (volume, angles) and its exact self-intersections.
// Implemented in geometry/check/mesh_checks*.cpp, one file per kind of check (the
// list is in geometry/check/mesh_checks_internal.h).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/types.h"
#include "geometry/kernel/angles.h"
#include "geometry/mesh/indexed_mesh.h"

namespace skinmesh::geometry {

// Mesh Check Types ------------------------------------------------------------

/// What check_mesh() does and how much it lists.
struct MeshCheckOptions {
  /// Run the exact self-intersection test (column grid + exact predicates);
  /// the most expensive part. Default: true.
  bool check_self_intersections = true;
  /// Triangles with an angle strictly below this (degrees) are counted in
  /// MeshCheckReport::num_small_angle_triangles. Default 20°: a reporting
  /// threshold only, not a bound from the paper; set it to the bound under test.
  double small_angle_threshold_deg = 20.0;
  /// At most this many examples of each kind of problem are listed in the
  /// report (the counts are always complete). Default: 16.
  std::size_t max_examples = 16;
  /// Threads for the self-intersection test (the simple fans and the column
  /// sweep); the report is the same for every count. Default: 1.
  int threads = 1;
};

/// One connected component of the mesh: triangles joined through shared edges
/// (triangles that only share a vertex are different components).
struct MeshComponent {
  std::size_t vertices = 0;  ///< distinct vertices of its triangles (a pinch vertex counts in each component)
  std::size_t edges = 0;     ///< distinct undirected edges
  std::size_t faces = 0;     ///< triangles
  std::int64_t euler = 0;    ///< Euler characteristic V - E + F
  bool closed = false;       ///< no boundary edge
  /// No non-manifold edge, and at each vertex the component's own triangles
  /// form a single fan (so two spheres touching at a vertex are two manifold
  /// components, while the shared vertex is non-manifold for the mesh).
  bool manifold = false;
  bool oriented = false;  ///< every edge with two triangles is used once in each direction
  /// (2 - euler) / 2 if closed, manifold and oriented; empty otherwise.
  std::optional<std::int64_t> genus;
  /// Signed enclosed volume (Å³), sum of signed tetrahedron volumes: positive for
  /// an outward-oriented closed outer surface. Meaningful for closed components.
  double volume = 0.0;
  double area = 0.0;  ///< total triangle area (Å²)
};

/// The result of check_mesh(). Counts are complete; *_examples list at most
/// MeshCheckOptions::max_examples entries (triangle indices, vertex indices or
/// vertex pairs (i < j) of the input), in increasing order of their first index.
///
/// Which triangles take part in what: triangles with an index out of range are
/// skipped everywhere; triangles with a repeated index are degenerate and skipped
/// in topology, angles and intersections; zero-area triangles (three distinct
/// indices, collinear points) are degenerate, count in topology and angles, and
/// are skipped by the intersection test (it needs a plane); triangles touching a
/// non-finite vertex count in topology only.
struct MeshCheckReport {
  // Counts
  std::size_t num_vertices = 0;               ///< positions.size()
  std::size_t num_triangles = 0;              ///< triangles.size()
  std::size_t num_unreferenced_vertices = 0;  ///< used by no triangle
  std::size_t num_nonfinite_vertices = 0;     ///< a NaN or infinite coordinate
  std::size_t num_edges = 0;                  ///< distinct undirected edges

  // Degenerate triangles
  std::size_t num_out_of_range_triangles = 0;    ///< an index >= num_vertices
  std::size_t num_repeated_index_triangles = 0;  ///< (a, a, b) and the like
  std::size_t num_zero_area_triangles = 0;       ///< distinct indices, exactly collinear points
  std::size_t num_degenerate_triangles = 0;      ///< repeated index + zero area
  std::size_t num_duplicate_triangles = 0;       ///< same vertex set as an earlier triangle
  std::vector<Index> degenerate_triangle_examples;

  // Topology
  std::size_t num_boundary_edges = 0;     ///< edges with exactly one triangle
  std::size_t num_nonmanifold_edges = 0;  ///< edges with more than two triangles
  std::size_t num_misoriented_edges = 0;  ///< two triangles using the edge in the same direction
  /// Vertices whose triangles do not form a single fan (a path or a cycle of
  /// triangles through shared edges), e.g. two cones touching at their tips
  /// (several components meet there). A vertex of a non-manifold edge is also
  /// non-manifold.
  std::size_t num_nonmanifold_vertices = 0;
  bool closed = false;           ///< num_boundary_edges == 0
  bool edge_manifold = false;    ///< num_nonmanifold_edges == 0
  bool vertex_manifold = false;  ///< num_nonmanifold_vertices == 0
  bool oriented = false;         ///< num_misoriented_edges == 0
  std::vector<std::array<Index, 2>> boundary_edge_examples;
  std::vector<std::array<Index, 2>> nonmanifold_edge_examples;
  std::vector<std::array<Index, 2>> misoriented_edge_examples;
  std::vector<Index> nonmanifold_vertex_examples;
  /// Edge-connected components, in the order of their lowest triangle index.
  std::vector<MeshComponent> components;
  /// Number of components when sharing a vertex suffices to connect (the
  /// referenced vertices grouped by the triangles' edges); <= components.size().
  std::size_t num_vertex_components = 0;

  // Self-intersections
  bool self_intersections_checked = false;  ///< MeshCheckOptions::check_self_intersections
  /// Pairs of triangles that intersect beyond what their shared vertices imply:
  /// pairs with no common vertex that touch at all; pairs with one common vertex
  /// that meet elsewhere; pairs with a common edge that overlap (coplanar, on the
  /// same side). Duplicates are counted in num_duplicate_triangles instead. Exact.
  std::size_t num_self_intersections = 0;
  std::vector<std::array<Index, 2>> self_intersection_examples;  ///< triangle pairs (i < j)
  std::size_t num_pairs_tested = 0;                              ///< candidate pairs given to the exact test

  // Angles (degrees), over triangles with three distinct in-range finite vertices
  double min_angle_deg = 0.0;  ///< 0 when there is no such triangle
  double max_angle_deg = 0.0;
  Index worst_triangle = kInvalidIndex;  ///< the triangle with the smallest angle
  /// Every angle counted once: 18 bins of 10°, bin i = [10 i, 10 (i + 1)) degrees,
  /// 180° in the last bin. Sum = 3 x (number of triangles measured).
  std::vector<std::size_t> angle_histogram = std::vector<std::size_t>(18, 0);
  double small_angle_threshold_deg = 0.0;  ///< copied from the options
  std::size_t num_small_angle_triangles = 0;

  /// Human-readable list of what is wrong, one line each; empty if ok().
  std::vector<std::string> problems;

  /// True if the mesh is a valid closed surface: no out-of-range, degenerate or
  /// duplicate triangle, no non-finite vertex, closed, edge- and vertex-manifold,
  /// oriented and (if checked) free of self-intersections. Unreferenced vertices
  /// and small angles do not count; an empty mesh is ok().
  bool ok() const;

  /// The report as one JSON object: keys = the field names above, plus "ok"
  /// (ok()) and "angle_histogram_bin_deg" (10); a missing genus, an invalid
  /// worst_triangle and non-finite numbers are null. Strings are escaped.
  std::string to_json() const;
};

// Mesh Check Public Functions --------------------------------------------------

/// Verify a triangle soup. Every combinatorial decision is exact (index
/// comparisons, orient2d/orient3d of geometry/kernel/predicates); volumes, areas and
/// angles are double-precision estimates. O(n log n) for meshes whose triangles
/// have comparable sizes (a grid of (x, y) columns about the mean triangle
/// extent, swept along z; pairs around a simple fan settled from the
/// connectivity); many huge overlapping triangles degrade towards O(n^2).
/// Throws nothing but std::bad_alloc.
MeshCheckReport check_mesh(const IndexedMesh& mesh, const MeshCheckOptions& options = {});

}  // namespace skinmesh::geometry
