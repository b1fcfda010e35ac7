// geometry/triangulation/regular_triangulation.h: the regular (weighted Delaunay)
// triangulation R_B of a set of weighted points, built incrementally.
// papers/skin/skin_math.md §2.1 (definitions, redundant points) and §9
// (degeneracies).
//
// Ideas used (cited in the order they appear in the code):
// * Bounding points (below): the triangulation is one of a big tetrahedron, so
//   there is no infinite vertex and every tetrahedron is finite.
// * BRIO, "biased randomised insertion order" (Amenta, Choi & Rote, SoCG 2003):
//   rounds of geometrically growing size, each sorted along a 3D Hilbert curve
//   (Hilbert index by Skilling, "Programming the Hilbert curve", AIP 2004).
// * Remembering stochastic visibility walk for point location (Devillers, Pion
//   & Teillaud, "Walking in a triangulation", IJFCS 2002), from the tetrahedron
//   created by the previous insertion; a bounded number of steps, then an
//   exhaustive scan, so it terminates on any input.
// * Bowyer-Watson insertion (Bowyer 1981, Watson 1981) for weighted points
//   (Edelsbrunner & Shah, "Incremental topological flipping works for regular
//   triangulations", Algorithmica 1996, for the regular-triangulation facts):
//   the conflict region (tetrahedra whose orthosphere is in conflict with the
//   new point, found by a graph search over neighbours) is a
//   star-shaped ball whose boundary facets all see the new point; it is
//   replaced by the cone from the new point over its boundary.
// * power_test_sos() (geometry/kernel/predicates.h) for every conflict decision:
//   Simulation of Simplicity on the weights only, so that the result is the
//   regular triangulation of symbolically perturbed weights, which never has a
//   flat tetrahedron, even for coplanar or cospherical input.
//
// Redundant points (papers/skin/skin_math.md §2.1): a point whose lifted point
// lies above the lower hull is not a vertex. An input is redundant either
// because it is not in conflict with the tetrahedron that contains it when it is
// inserted (it is then never inserted), or because a later insertion hides it
// (all its tetrahedra are in conflict and it lies inside the cavity). Duplicate
// centres: the larger weight wins; equal weights: the larger index wins (SoS,
// see power_test_sos()).
//
// What this class does NOT do: no point removal, no insertion after
// construction, no dimensions other than 3 (lower-dimensional inputs are made
// 3-dimensional by the bounding points), no multithreading.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/assert.h"
#include "core/types.h"
#include "geometry/kernel/weighted_point.h"
#include "geometry/triangulation/cavity.h"
#include "geometry/triangulation/walk.h"

namespace skinmesh::geometry {

namespace detail {
/// Bits per axis of the Hilbert keys used for the insertion order.
inline constexpr int kHilbertBits = 16;
inline constexpr std::uint32_t kHilbertMask = (1u << kHilbertBits) - 1;
/// Position of the grid cell (x, y, z) (each < 2^16) along the 3D Hilbert
/// curve of order 16: consecutive keys are face-adjacent cells. Skilling,
/// "Programming the Hilbert curve", AIP Conf. Proc. 707 (2004).
std::uint64_t hilbert_key(std::uint32_t x, std::uint32_t y, std::uint32_t z);
}  // namespace detail

// RegularTriangulation Definition ---------------------------------------------

/// Regular triangulation of n >= 1 input weighted points plus 4 bounding points.
///
/// Bounding points: indices n..n+3 are the vertices of a regular tetrahedron
/// centred at the centre c of the inputs' bounding box, with circumradius
/// D = 50 L', L' = max_i (|z_i - c| + sqrt(max(w_i, 0))) but at least 1 Å, and
/// weight 0. Why: (1) every input becomes 3-dimensional (1, 2 or 3 atoms,
/// planar molecules), (2) there is no infinite vertex: every tetrahedron is
/// finite and every input face has two tetrahedra, (3) they provably do not
/// change the skin of the inputs for s = 1/2 as long as D > ~7 L' (proof:
/// papers/geometry/triangulation/regular_triangulation.md, by the lead); D = 50 L' leaves a
/// wide margin. The bounding points are always vertices (they are the extreme
/// points of the convex hull). Caveats: the tetrahedra without a bounding vertex
/// are not always exactly the regular triangulation of the inputs alone (a very
/// flat tetrahedron on the inputs' hull, whose orthosphere reaches a bounding
/// point, is replaced by tetrahedra with a bounding vertex); and an input with a
/// very negative weight (below -(D^2 - |z - c|^2), about -2500 L'^2; L' ignores
/// negative weights) is redundant against the bounding points alone.
///
/// Layout (geogram style, flat index arrays): tet(t) = {v0, v1, v2, v3} is
/// positively oriented (orient3d(v0, v1, v2, v3) == Positive); neighbor(t, i)
/// is the tetrahedron across the face opposite v_i, kInvalidIndex on the 4
/// outer faces of the bounding tetrahedron. The face opposite local vertex i is
/// kFaceVertices[i], ordered so that orient3d(face, v_i) == Positive (the face
/// normal (b - a) x (c - a) points into the tetrahedron):
///
///            v3                 face 0 = (v1, v3, v2)
///           /|\                 face 1 = (v0, v2, v3)
///          / | \                face 2 = (v0, v3, v1)
///        v0--|--v2              face 3 = (v0, v1, v2)
///          \ | /
///           \|/      (v0, v1, v2 counter-clockwise seen from v3)
///            v1
///
/// Construction is deterministic for a given input and seed. Indices never
/// change after construction and there are no deleted tetrahedra.
class RegularTriangulation {
 public:
  /// Local vertex indices of the face opposite local vertex i, ordered so that
  /// vertex i is on the positive side (see the class comment).
  static constexpr std::array<std::array<int, 3>, 4> kFaceVertices = walk::kFaceVertices;

  /// Default seed of the randomised parts (BRIO shuffle, stochastic walk).
  static constexpr std::uint64_t kDefaultSeed = 0x5EED5EED2004ULL;

  /// Counters of the construction (for benchmarks and diagnostics).
  struct BuildStats {
    std::uint64_t walk_steps = 0;       ///< tetrahedra visited by point location
    std::uint64_t walk_fallbacks = 0;   ///< walks that hit the step limit (exhaustive scan)
    std::uint64_t conflict_tets = 0;    ///< tetrahedra removed by insertions, in total
    std::uint64_t hidden_vertices = 0;  ///< vertices made redundant by a later insertion
  };

  /// Builds the regular triangulation of `points` plus 4 bounding points.
  /// `points[i]`: centre (Å) and weight (Å², the squared radius; any sign).
  /// `seed` makes the randomised insertion order and walk reproducible; the
  /// triangulation itself does not depend on it (it is unique under SoS).
  /// Throws InputError("", 0, ...) if points is empty or has a non-finite
  /// coordinate or weight (a bug of the caller: readers reject such input).
  /// Pre: admissible magnitudes of geometry/kernel/predicates.h. Cost: expected
  /// O(n log n) for well-distributed input.
  explicit RegularTriangulation(std::span<const WeightedPoint> points, std::uint64_t seed = kDefaultSeed);

  // Points --------------------------------------------------------------------

  /// Number n of input points.
  Index num_input_points() const { return n_input_; }
  /// Number of points including the 4 bounding points: n + 4.
  Index num_points() const { return static_cast<Index>(points_.size()); }
  /// Point v (input if v < n, bounding point if n <= v < n + 4). Pre: v < num_points().
  const WeightedPoint& point(Index v) const;
  /// All n + 4 points, inputs first.
  std::span<const WeightedPoint> points() const { return points_; }
  /// True iff v is one of the 4 bounding points (v >= n).
  bool is_bounding(Index v) const { return v >= n_input_; }
  /// True iff point v is a vertex of the triangulation (false for redundant
  /// inputs). Pre: v < num_points().
  bool is_vertex(Index v) const;
  /// The redundant inputs (not vertices), in increasing index order.
  std::vector<Index> redundant_points() const;
  /// Centre c (Å) of the bounding tetrahedron (the inputs' bounding-box centre).
  const Vec3& bounding_centre() const { return bounding_centre_; }
  /// Circumradius D = 50 L' (Å) of the bounding tetrahedron.
  double bounding_radius() const { return bounding_radius_; }

  // Tetrahedra ----------------------------------------------------------------

  /// Number of tetrahedra (all finite, all alive).
  Index num_tets() const { return static_cast<Index>(cells_.size()); }
  /// Vertices of tetrahedron t, positively oriented. Pre: t < num_tets().
  const std::array<Index, 4>& tet(Index t) const;
  /// Tetrahedron across the face of t opposite its local vertex i (0..3), or
  /// kInvalidIndex on the boundary of the bounding tetrahedron.
  Index neighbor(Index t, int i) const;
  /// Some tetrahedron incident to vertex v, kInvalidIndex if v is redundant.
  Index vertex_tet(Index v) const;
  /// Local index (0..3) of vertex v in tetrahedron t, or -1.
  int local_index(Index t, Index v) const;

  // Queries -------------------------------------------------------------------

  /// A tetrahedron whose closed hull contains p (Å), found by a stochastic
  /// visibility walk from `hint` (any tetrahedron; kInvalidIndex: start at
  /// tetrahedron 0). If p lies on a shared face, edge or vertex any of the
  /// tetrahedra containing it may be returned. Returns kInvalidIndex iff p is
  /// outside the closed bounding tetrahedron. Exact (orient3d). Deterministic.
  Index locate(const Vec3& p, Index hint = kInvalidIndex) const;

  /// power_test_sos() of point v against tetrahedron t: Positive iff v is in
  /// (symbolically perturbed) conflict with t, i.e. t's orthosphere is not
  /// empty of v. For a valid triangulation, Negative for every v, vertex or
  /// redundant, that is not a vertex of t. Pre: v not a vertex of t.
  Sign conflict(Index t, Index v) const;

  /// Counters of the construction.
  const BuildStats& build_stats() const { return stats_; }

 private:
  // RegularTriangulation Private Methods
  void insert(Index v);
  Index walk(std::span<const WeightedPoint> pts, const Vec3& p, Index start, std::uint64_t& rng, std::uint64_t* steps,
             std::uint64_t* fallbacks) const;
  Index locate_by_scan(std::span<const WeightedPoint> pts, const Vec3& p) const;
  bool contains(std::span<const WeightedPoint> pts, Index t, const Vec3& p) const;
  Sign work_conflict(Index t, Index v) const;  // construction numbering
  Index new_tet();
  void compact();
  std::vector<Index> insertion_order(std::uint64_t seed) const;

  // RegularTriangulation Private Members
  Index n_input_ = 0;
  std::vector<WeightedPoint> points_;
  Vec3 bounding_centre_ = Vec3::Zero();
  double bounding_radius_ = 0.0;
  // Tetrahedron t: vertices and neighbours side by side (one cache line per
  // two tetrahedra); a deleted one (during construction only) has v[0] invalid.
  struct alignas(32) Cell {
    std::array<Index, 4> v;
    std::array<Index, 4> n;
  };
  std::vector<Cell> cells_;
  std::vector<Index> vertex_tet_;
  /// What became of an input point.
  enum class PointState : std::uint8_t {
    NotInserted,  ///< not inserted yet (construction only)
    Vertex,       ///< a vertex of the triangulation
    Redundant,    ///< never inserted: its lifted point lies above the lower hull
    Hidden,       ///< inserted, then hidden by a later point
  };
  std::vector<PointState> vertex_state_;
  BuildStats stats_;

  // Construction scratch (empty after construction). During construction the
  // vertex numbers in cells_, vertex_tet_ and vertex_state_ are positions in
  // the insertion order: work_points_[k] is the point, work_ids_[k] its index.
  std::vector<WeightedPoint> work_points_;
  std::vector<Index> work_ids_;
  std::vector<Index> free_tets_;
  std::vector<std::uint32_t> tet_mark_;
  std::vector<std::uint32_t> vertex_mark_;
  std::vector<Index> stack_, conflict_, cavity_vertices_;
  std::vector<cavity::Facet> boundary_;
  std::vector<cavity::EdgeSlot> edge_table_;
  std::uint32_t generation_ = 0;
  Index last_tet_ = 0;
  std::uint64_t walk_rng_ = 0;
};

// The accessors are inline: the mixed complex's construction and the walks
// call them a few times per step.
inline const WeightedPoint& RegularTriangulation::point(Index v) const {
  SKINMESH_DEBUG_ASSERT(v < points_.size());
  return points_[v];
}

inline const std::array<Index, 4>& RegularTriangulation::tet(Index t) const {
  SKINMESH_DEBUG_ASSERT(t < cells_.size());
  return cells_[t].v;
}

inline Index RegularTriangulation::neighbor(Index t, int i) const {
  SKINMESH_DEBUG_ASSERT(t < cells_.size() && i >= 0 && i < 4);
  return cells_[t].n[i];
}

inline int RegularTriangulation::local_index(Index t, Index v) const {
  const std::array<Index, 4>& tv = tet(t);
  for (int i = 0; i < 4; ++i)
    if (tv[i] == v) return i;
  return -1;
}

}  // namespace skinmesh::geometry
