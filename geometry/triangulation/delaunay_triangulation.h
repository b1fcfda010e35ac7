// geometry/triangulation/delaunay_triangulation.h: a fully dynamic 3D Delaunay triangulation
// (insertion, deletion and motion of vertices) with exact predicates and
// symbolic perturbation. papers/geometry/triangulation/delaunay_triangulation.md.
//
// Ideas used (cited in the order they appear in the code):
// * Bounding points, as in RegularTriangulation: the triangulation is one of a
//   big fixed tetrahedron (vertices 0..3), so there is no infinite vertex and
//   every tetrahedron is finite. They are placed from a box given at
//   construction that every point must lie in.
// * power_test_sos() (geometry/kernel/predicates.h) with all weights 0 for every
//   in-sphere decision and the vertex ids as the SoS indices: the result is the
//   Delaunay triangulation of a symbolically perturbed point set (the lifted
//   points are perturbed, the centres are not), which is unique and never has a
//   flat tetrahedron, even for cospherical or coplanar points (Edelsbrunner &
//   Mücke 1990; Devillers & Teillaud, "Perturbations for Delaunay and weighted
//   Delaunay 3D triangulations", CGAL 2011).
// * Remembering stochastic visibility walk (Devillers, Pion & Teillaud,
//   "Walking in a triangulation", IJFCS 2002), with a step limit and an
//   exhaustive scan as fallback.
// * Bowyer-Watson insertion (Bowyer 1981, Watson 1981): the tetrahedra whose
//   circumsphere contains the new point form a connected region, star-shaped
//   from it; it is replaced by the cone from the point over its boundary.
// * Deletion by the Delaunay triangulation of the link (Devillers, "On
//   deletion in Delaunay triangulations", IJCGA 2002; the method of CGAL's
//   Triangulation_3::remove): the link vertices of v plus the 4 bounding points
//   are triangulated with the same perturbation; the tetrahedra of that small
//   triangulation that lie in the hole left by the star of v are exactly the
//   tetrahedra of the new global triangulation there (proof in the note).
//
// Vertex ids: 0..3 are the bounding points; every insert() returns a new id
// (4, 5, ...), never reused. The id is the SoS index: of two points that are
// exactly cospherical with others, the larger id has the larger symbolic
// weight. The triangulation is a function of the current set of pairs
// (id, position) only, not of the history of operations.
//
// Duplicates: inserting (or moving to) a point with exactly the coordinates of a
// live vertex throws InputError naming that vertex (with equal weights, two
// coincident points would make one of them redundant: not a vertex).
//
// Tetrahedron ids: slots of a flat array; a deleted slot is reused by later
// operations (free list). insert(), remove() and move() kill the tetrahedra of
// the conflict region / star and create new ones, which may reuse the killed
// ids; every other tetrahedron keeps its id and its vertices, only its
// neighbour across a facet of the modified region changes. Ids of killed
// tetrahedra must not be used (is_live() tells). Vertex ids stay valid until
// the vertex is removed.
//
// Not thread-safe for concurrent modification; const methods may run
// concurrently with each other.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"
#include "geometry/kernel/weighted_point.h"
#include "geometry/triangulation/cavity.h"
#include "geometry/triangulation/walk.h"

namespace skinmesh::geometry {

// DelaunayTriangulation Definition --------------------------------------------

/// Dynamic Delaunay triangulation of points in a fixed box, plus 4 bounding
/// points (ids 0..3).
///
/// Bounding points: a regular tetrahedron centred at the box centre c with
/// circumradius D = 50 L', L' = half the box diagonal but at least 1 Å
/// (RegularTriangulation's choice). Its inradius D/3 > L', so every point of
/// the box is strictly inside. The tetrahedra with a bounding vertex replace the
/// unbounded part of the Delaunay triangulation of the points; inside the ball
/// B(c, 24.5 L') the Voronoi diagram of points + bounding points equals that of
/// the points alone (papers/geometry/triangulation/delaunay_triangulation.md), so a surface
/// inside the box has the same restricted Delaunay triangulation.
///
/// Layout (RegularTriangulation's convention): tet(t) = {v0, v1, v2, v3} is
/// positively oriented (orient3d(v0, v1, v2, v3) == Positive); neighbor(t, i)
/// is the tetrahedron across the face opposite v_i (kInvalidIndex on the 4
/// outer faces of the bounding tetrahedron); kFaceVertices[i] lists that face
/// so that orient3d(face, v_i) == Positive.
class DelaunayTriangulation {
 public:
  /// Local vertex indices of the face opposite local vertex i, ordered so that
  /// vertex i is on the positive side (as RegularTriangulation::kFaceVertices).
  static constexpr std::array<std::array<int, 3>, 4> kFaceVertices = walk::kFaceVertices;
  /// Number of bounding points (ids 0..3).
  static constexpr Index kNumBounding = 4;

  /// Counters of the operations so far (diagnostics and benchmarks).
  struct Stats {
    std::uint64_t insertions = 0;      ///< successful insert() calls (and the insert half of move())
    std::uint64_t removals = 0;        ///< successful remove() calls (and the remove half of move())
    std::uint64_t walk_steps = 0;      ///< tetrahedra visited by the walks of insert()/move()
    std::uint64_t walk_fallbacks = 0;  ///< walks that hit the step limit (exhaustive scan)
    std::uint64_t conflict_tets = 0;   ///< tetrahedra killed by insertions
    std::uint64_t star_tets = 0;       ///< tetrahedra killed by removals
    std::uint64_t link_vertices = 0;   ///< link vertices triangulated by removals, in total
    std::uint64_t local_tets = 0;      ///< tetrahedra of the link triangulations, in total
    std::uint64_t kinetic_moves = 0;   ///< move() calls that kept the combinatorics (no removal)
  };

  /// An empty triangulation (the bounding tetrahedron only) for points in the
  /// closed box [lo, hi] (Å). Throws InputError("", 0, ...) if a coordinate of
  /// lo or hi is non-finite or outside ±kMaxCoordinate (weighted_point.h), or
  /// lo > hi in some coordinate.
  DelaunayTriangulation(const Vec3& lo, const Vec3& hi);

  // Modification ----------------------------------------------------------------

  /// Inserts the point p (Å) and returns its new vertex id (the largest so
  /// far; ids are never reused). `hint`: a tetrahedron near p where the walk
  /// starts (kInvalidIndex or a dead id: the last tetrahedron created).
  /// Throws InputError if p is non-finite or outside the box, or if p has
  /// exactly the coordinates of a live vertex (the message names it); the
  /// triangulation is then unchanged. Bowyer-Watson with power_test_sos.
  /// Cost: the walk plus O(size of the conflict region).
  Index insert(const Vec3& p, Index hint = kInvalidIndex);

  /// Removes the live non-bounding vertex v: its star is replaced by the
  /// tetrahedra of the Delaunay triangulation of its link (plus the bounding
  /// points) that lie in the hole (Devillers 2002). Throws InputError if v is
  /// not a live vertex or is a bounding point. Cost: O(k log k) in practice for
  /// a link of k vertices (O(k^2) worst case), independent of the global size.
  void remove(Index v);

  /// Moves the live non-bounding vertex v to p (Å), keeping its id. If the
  /// star of v stays positively oriented and locally Delaunay with v at p,
  /// only the position changes (kinetic fast path, O(star)); otherwise
  /// remove(v) then an insertion with the same id. Consequence for SoS: v keeps its place
  /// in the perturbation order (its id), which need not be the latest; the
  /// result is still the unique triangulation of the current (id, position)
  /// pairs. Throws InputError (triangulation unchanged) if v is not a live
  /// non-bounding vertex, p is non-finite or outside the box, or p equals the
  /// position of another live vertex. p equal to v's position: no change.
  void move(Index v, const Vec3& p);

  // Queries ---------------------------------------------------------------------

  /// A live tetrahedron whose closed hull contains p (Å), by a visibility walk
  /// with exact orient3d from `hint` (kInvalidIndex or dead: the last
  /// tetrahedron created); the faces are tried in a pseudo-random order seeded
  /// by the start tetrahedron, so the answer is deterministic. After 1000 + 4 *
  /// capacity steps, an exhaustive scan decides. If p lies on a shared face,
  /// edge or vertex any of its tetrahedra may be returned. Returns
  /// kInvalidIndex iff p is outside the closed bounding tetrahedron (never for
  /// p in the box). Pre: p finite.
  Index locate(const Vec3& p, Index hint = kInvalidIndex) const;

  /// power_test_sos() (weights 0, SoS indices = ids) of vertex v against the
  /// live tetrahedron t: Positive iff v is strictly inside the (perturbed)
  /// circumsphere of t. Pre: v a live vertex, not a vertex of t. Never Zero.
  Sign conflict(Index t, Index v) const;

  /// Exhaustive validity check, O(#tets): every live tetrahedron has 4
  /// distinct live vertices and is positively oriented (exact orient3d);
  /// neighbour relations are symmetric and share exactly the facet; exactly 4
  /// outer faces, each with 3 bounding vertices; every live vertex's
  /// vertex_tet() is live and contains it, no dead vertex is used; the counts
  /// match; local Delaunay: for every interior facet the opposite vertex is not
  /// in conflict (power_test_sos Negative), which with the rest implies the
  /// global empty-sphere property. On failure returns false and, if `why` is
  /// not null, stores the first problem found.
  bool is_valid(std::string* why = nullptr) const;

  // Vertices --------------------------------------------------------------------

  /// Number of live vertices, the 4 bounding points excluded.
  Index num_vertices() const { return num_live_vertices_; }
  /// One past the largest vertex id ever used (bounding points included).
  Index vertex_capacity() const { return static_cast<Index>(mesh_.points.size()); }
  /// True iff v is a live vertex (bounding points are always live).
  bool is_vertex(Index v) const;
  /// True iff v is one of the 4 bounding points (v < 4).
  static bool is_bounding(Index v) { return v < kNumBounding; }
  /// Position (Å) of vertex v (for a removed vertex: its last position).
  /// Pre: v < vertex_capacity().
  const Vec3& point(Index v) const;
  /// A live tetrahedron incident to vertex v, kInvalidIndex if v is not live.
  Index vertex_tet(Index v) const;
  /// Replaces the content of `out` with the live tetrahedra incident to the
  /// live vertex v (its star), in breadth-first order from vertex_tet(v).
  /// Cost O(star size) (a hash set for stars larger than 64).
  void incident_tets(Index v, std::vector<Index>& out) const;

  // Tetrahedra ------------------------------------------------------------------

  /// Number of live tetrahedra.
  Index num_tets() const { return mesh_.live_cells; }
  /// One past the largest tetrahedron id in use or on the free list.
  Index tet_capacity() const { return static_cast<Index>(mesh_.cells.size()); }
  /// True iff t < tet_capacity() and t is a live tetrahedron.
  bool is_live(Index t) const;
  /// Vertices of the live tetrahedron t, positively oriented.
  const std::array<Index, 4>& tet(Index t) const;
  /// Tetrahedron across the face of t opposite its local vertex i (0..3), or
  /// kInvalidIndex on the boundary of the bounding tetrahedron. Pre: t live.
  Index neighbor(Index t, int i) const;
  /// Local index (0..3) of vertex v in tetrahedron t, or -1.
  int local_index(Index t, Index v) const;
  /// Circumcentre (Å) of the live tetrahedron t, in floating point (an
  /// estimate, for Voronoi vertices: the decisions use the predicates). Far
  /// away for a nearly flat tetrahedron; finite because t is never flat.
  Vec3 circumcentre(Index t) const;
  /// Calls f(t) for every live tetrahedron t in increasing id order. f must not
  /// modify the triangulation.
  template <class F>
  void for_each_tet(F&& f) const {
    const Index n = tet_capacity();
    for (Index t = 0; t < n; ++t)
      if (mesh_.cells[t].v[0] != kInvalidIndex) f(t);
  }

  // Box -------------------------------------------------------------------------
  /// Centre c and circumradius D = 50 L' (Å) of the bounding tetrahedron.
  const Vec3& bounding_centre() const { return centre_; }
  double bounding_radius() const { return radius_; }

  /// Counters of the operations so far.
  const Stats& stats() const { return stats_; }

  /// The tetrahedra created by the last successful insert(), remove() or
  /// move() (a move logs those of its removal and of its re-insertion, or,
  /// on its fast path, the star whose vertex moved), in creation order. An id
  /// may be listed twice, or be dead again (a move's re-insertion can kill
  /// what its removal created): filter with is_live(). Every live
  /// tetrahedron not listed existed before the operation with the same
  /// vertices at the same positions. Empty before the first operation and after a move() to the
  /// vertex's own position. This is how a client keeps per-tetrahedron data
  /// (circumcentres, restricted facets) up to date in O(size of the change).
  const std::vector<Index>& last_created() const { return mesh_.created; }

 private:
  // A tetrahedron: vertices and neighbours; dead iff v[0] == kInvalidIndex.
  struct Cell {
    std::array<Index, 4> v;
    std::array<Index, 4> n;
  };
  // A tetrahedralisation of the bounding tetrahedron with its own vertex
  // numbering: the global triangulation (sos[v] == v) and the link
  // triangulation of a removal (sos = the global ids) are both Meshes.
  struct Mesh {
    std::vector<WeightedPoint> points;  // by vertex, weight 0
    std::vector<Index> sos;             // SoS index of each vertex
    std::vector<Index> vertex_tet;      // kInvalidIndex: not a live vertex
    std::vector<Cell> cells;
    std::vector<Index> free_cells;
    std::vector<Index> created;  // cells made since the last clear (last_created())
    Index live_cells = 0;
    Index last_cell = 0;
    // Scratch of insert_vertex().
    std::vector<std::uint32_t> cell_mark;
    std::uint32_t generation = 0;
    std::vector<Index> stack, conflict;
    std::vector<cavity::Facet> cavity_facets;
    std::vector<cavity::EdgeSlot> edge_table;

    void reset(const std::array<Vec3, 4>& corners);
    Index add_vertex(const Vec3& p, Index sos_index);
    Index new_cell();
    void kill_cell(Index t);
    bool live(Index t) const { return t < cells.size() && cells[t].v[0] != kInvalidIndex; }
    Sign conflict_with(Index t, Index v) const;
    bool contains(Index t, const Vec3& p) const;
    Index scan(const Vec3& p) const;
    Index walk(const Vec3& p, Index start, std::uint64_t& rng, std::uint64_t* steps, std::uint64_t* fallbacks) const;
    std::uint32_t next_generation();
    void insert_vertex(Index v, Index start, std::uint64_t* conflict_count);
  };

  void check_point(const Vec3& p, const char* what) const;
  Index locate_checked(const Vec3& p, Index hint, Index ignore);
  void remove_vertex(Index v);

  Vec3 lo_, hi_, centre_;
  double radius_ = 0.0;
  std::array<Vec3, 4> corners_;
  Mesh mesh_;  // the triangulation
  Mesh link_;  // scratch: the link triangulation of a removal
  Index num_live_vertices_ = 0;
  std::uint64_t rng_ = 0x9E3779B97F4A7C15ULL;
  Stats stats_;
  // Removal scratch.
  std::vector<Index> star_, local_of_, local_stamp_, hole_, global_of_local_;
  std::vector<std::uint8_t> boundary_mask_;
  std::vector<Index> boundary_outside_;
  std::uint32_t removal_stamp_ = 0;
};

}  // namespace skinmesh::geometry
