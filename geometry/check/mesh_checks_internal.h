// geometry/check/mesh_checks_internal.h: the private header of check_mesh() — the
// triangle classes every step reads and the steps check_mesh() runs in order,
// each defined in its own file:
//   mesh_checks.cpp               check_mesh(): triangle classes, the steps, the problem list
//   mesh_checks_topology.cpp      check_topology(): edges, components, Euler characteristics
//   mesh_checks_geometry.cpp      measure_components() (volume, area), measure_angles()
//   mesh_checks_intersections.cpp find_self_intersections(): column grid, simple fans, exact test
//   mesh_checks_json.cpp          MeshCheckReport::to_json()
// Only geometry/check/mesh_checks*.cpp include this header (and the tests of
// tests/geometry/mesh_checks_broad_phase_test.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/check/mesh_checks.h"
#include "geometry/mesh/indexed_mesh.h"

namespace skinmesh::geometry::mesh_checks_detail {

/// Angle histogram of MeshCheckReport: kHistogramBins bins of kHistogramBinDeg degrees.
inline constexpr int kHistogramBins = 18;
inline constexpr double kHistogramBinDeg = 10.0;

/// The class of one input triangle, which decides the steps it takes part in
/// (see MeshCheckReport): kOutOfRange (an index >= number of vertices: skipped
/// everywhere), kRepeated (a repeated index: skipped in topology, angles and
/// intersections), kNonFinite (a non-finite vertex: topology only), kZeroArea
/// (distinct indices, exactly collinear points: topology and angles), kGood.
enum class TriangleKind : std::uint8_t { kOutOfRange, kRepeated, kZeroArea, kNonFinite, kGood };

/// What every step needs to know about the input, computed once by check_mesh():
/// the class of each triangle and, per vertex, whether its coordinates are
/// finite and whether an in-range triangle references it.
struct TriangleClasses {
  std::vector<TriangleKind> kind;   ///< one per triangle
  std::vector<bool> vertex_finite;  ///< one per vertex
  std::vector<bool> referenced;     ///< one per vertex
  /// True if triangle t takes part in the topology (its indices are in range and distinct).
  bool in_topology(std::size_t t) const {
    return kind[t] != TriangleKind::kOutOfRange && kind[t] != TriangleKind::kRepeated;
  }
};

/// Vertex -> triangle incidence in compressed (CSR) form, over the triangles in
/// the topology (TriangleClasses::in_topology): the triangles of vertex v are
/// incident[start[v] .. start[v + 1]), in increasing order.
struct VertexIncidence {
  std::vector<Index> start;  ///< number of vertices + 1 offsets
  std::vector<Index> incident;
};

/// The VertexIncidence of `mesh`, counting only triangles in the topology.
VertexIncidence build_incidence(const IndexedMesh& mesh, const TriangleClasses& classes);

/// Appends `item` to an examples list of the report unless it already holds
/// `max_examples` entries (the counts are kept separately, always complete).
template <class List, class Item>
void add_example(List& list, const Item& item, std::size_t max_examples) {
  if (list.size() < max_examples) list.push_back(item);
}

/// The combinatorial checks: duplicate triangles, boundary / non-manifold /
/// misoriented edges (closed, edge_manifold, oriented), edge-connected
/// components with V, E, F, Euler characteristic and genus, non-manifold
/// vertices (vertex_manifold) and vertex-connected components. Fills those
/// fields of `r`, leaving each component's volume and area at 0. Returns the
/// component of every triangle (an index into r.components; kInvalidIndex for
/// triangles outside the topology). Exact: index comparisons only. `incidence`
/// = build_incidence(mesh, classes), kept by the caller for
/// simple_fan_vertices().
std::vector<Index> check_topology(const IndexedMesh& mesh, const TriangleClasses& classes,
                                  const VertexIncidence& incidence, std::size_t max_examples, MeshCheckReport& r);

/// Signed volume and area of every component of r.components (from
/// check_topology(), `component` = its triangle -> component map), over the
/// triangles with finite vertices, relative to the centre of the bounding box of
/// the referenced finite vertices (to limit cancellation). Double precision.
void measure_components(const IndexedMesh& mesh, const TriangleClasses& classes, const std::vector<Index>& component,
                        MeshCheckReport& r);

/// Angle statistics of `r` (min_angle_deg, max_angle_deg, worst_triangle,
/// angle_histogram, num_small_angle_triangles below `threshold_deg`) over the
/// good and zero-area triangles. Double precision (corner_angle()).
void measure_angles(const IndexedMesh& mesh, const TriangleClasses& classes, double threshold_deg, MeshCheckReport& r);

/// The exact self-intersection test over the good triangles: sets
/// self_intersections_checked, num_self_intersections, num_pairs_tested and the
/// first `max_examples` pairs (i < j, sorted) of `r`. Column-grid broad phase,
/// then mesh_triangles_intersect() (geometry/kernel/triangle_intersection.h) on each
/// candidate pair that is not the same triangle twice and not settled by
/// `fan_ok` (simple_fan_vertices(), one flag per vertex: the caller computes
/// it first, so that the vertex incidence is freed before the broad phase's
/// boxes are made, the peak of the check's memory). Runs on up to `threads`
/// threads (core/parallel.h); the report is the same for every thread count.
void find_self_intersections(const IndexedMesh& mesh, const TriangleClasses& classes,
                             const std::vector<std::uint8_t>& fan_ok, std::size_t max_examples, int threads,
                             MeshCheckReport& r);

/// Per vertex, 1 if the good triangles around it form a simple fan: one closed
/// cycle of consistently oriented triangles that a coordinate projection maps
/// one-to-one onto a disc around the vertex (orient2d of one strict sign,
/// winding number 1). Two good triangles sharing such a vertex (or an edge with
/// such an end) meet only in what they share. Exact. 0 for other vertices.
/// `incidence` = build_incidence(mesh, classes). On up to `threads` threads.
std::vector<std::uint8_t> simple_fan_vertices(const IndexedMesh& mesh, const TriangleClasses& classes,
                                              const VertexIncidence& incidence, int threads = 1);

/// The broad phase of find_self_intersections(), for tests: every pair (i < j)
/// of `boxes` (lo x, y, z, hi x, y, z) whose closed boxes overlap, sorted;
/// the same list for every number of `threads`, every `entries_per_block`
/// (the size of the blocks of columns swept on the threads) and every
/// `boxes_per_band` (the boxes stored at a time); 0: the checks' own.
std::vector<std::array<Index, 2>> box_overlap_pairs(const std::vector<std::array<double, 6>>& boxes, int threads = 1,
                                                    std::size_t entries_per_block = 0, std::size_t boxes_per_band = 0);

}  // namespace skinmesh::geometry::mesh_checks_detail
