// dynamic/sample_triangulation.h: a point sample on a level set of the skin
// function, its 3D Delaunay triangulation, the restricted Delaunay
// triangulation read off it, and the refinement that keeps the sample under
// [L] and [U] — the data structure of the dynamic-skin baseline (Cheng, Dey,
// Edelsbrunner & Sullivan, "Dynamic skin triangulation", 2001, as cited by
// Cheng & Shi 2004 [3]).
// Notes: papers/dynamic/dynamic_skin.md
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <queue>
#include <vector>

#include "dynamic/level_set.h"
#include "geometry/mesh/indexed_mesh.h"
#include "geometry/triangulation/delaunay_triangulation.h"
#include "skin/size_conditions.h"
#include "skin/skin_surface.h"
#include "skin/vertex_data.h"

namespace skinmesh::dynamic {

/// Counters of a SampleTriangulation (cumulative).
struct SampleStats {
  std::size_t seeds = 0;                ///< samples added by add_sample(seed = true)
  std::size_t u_insertions = 0;         ///< surface Delaunay centres inserted for [U]
  std::size_t bounding_insertions = 0;  ///< ... for restricted facets with a bounding vertex
  std::size_t manifold_insertions = 0;  ///< ... at vertices whose restricted star is not a disc
  std::size_t l_deletions = 0;          ///< samples deleted for [L] (edge contractions)
  std::size_t ring_samples = 0;         ///< samples added around a sample no restricted facet uses
  std::size_t isolated_deletions = 0;   ///< samples deleted because no restricted facet uses them
  std::size_t failed_insertions = 0;    ///< centre not found, or equal to an existing sample
  std::size_t moves = 0;                ///< samples moved (growth)
  std::size_t rounds = 0;               ///< global rounds of refine()
  std::size_t tets_classified = 0;      ///< Voronoi vertices (circumcentres) evaluated
  std::size_t facets_tested = 0;        ///< restricted facets tested against [U]
  /// Left when refine() stopped (all 0 when it converged).
  std::size_t L_left = 0, U_left = 0, nonmanifold_left = 0;
};

/// Samples (vertices on the level set F_c), their Delaunay triangulation
/// Del(P), and the restricted Delaunay triangulation of P with respect to F_c:
/// the Delaunay facets whose dual Voronoi edge crosses F_c. A facet is taken
/// as restricted when the two Voronoi vertices at the ends of its dual edge
/// (the circumcentres of its two tetrahedra) lie on opposite sides of F_c; the
/// crossing point is the centre of the facet's surface Delaunay ball. Under
/// the closed-ball property every restricted dual edge crosses F_c once, so
/// this is exact there; refine() enforces what it can check (every facet
/// meets [U], every edge [L], every vertex star a disc) and the final mesh is
/// verified independently (verify/skin_mesh_check.h).
///
/// Per-tetrahedron data (circumcentre, f - c there) is kept up to date from
/// DelaunayTriangulation::last_created() after every operation: O(size of the
/// change), no global rebuild, except set_level() (every Voronoi vertex
/// changes side when the level changes).
class SampleTriangulation {
 public:
  /// An empty sample on F_c of `skin` (c <= 0). The Delaunay box is the hull
  /// box of LevelSet. Pre: `skin` outlives this object.
  SampleTriangulation(const skin::SkinSurface& skin, double c, const skin::SizeConstants& size);

  const LevelSet& level_set() const { return level_; }
  const geometry::DelaunayTriangulation& triangulation() const { return dt_; }
  const SampleStats& stats() const { return stats_; }

  /// Changes the level to c (<= 0) and re-evaluates every Voronoi vertex;
  /// the samples are not moved (move them with move_sample() first or after,
  /// inside a batch). O(#tetrahedra).
  void set_level(double c);

  /// Batches: between begin_batch() and end_batch() operations do not
  /// evaluate Voronoi vertices nor queue facets; end_batch() evaluates all and
  /// queues every restricted facet that violates [U]. For moving every sample
  /// at once (a growth step).
  void begin_batch();
  void end_batch();

  /// Adds the sample x (on F_c; its mixed cell and rho) and returns its id,
  /// or kInvalidIndex if a sample has exactly these coordinates. `seed`: a
  /// sample of the initial set (deletable for [L]), not a refinement vertex.
  Index add_sample(const Vec3& x, Index cell, double rho, bool seed);
  /// Deletes sample v (star re-triangulation of Del(P)).
  void remove_sample(Index v);
  /// Moves sample v to x (on the new level set) keeping its id. Returns false
  /// (nothing changed) if another sample has exactly these coordinates.
  bool move_sample(Index v, const Vec3& x, Index cell, double rho);

  /// Makes every live sample deletable for [L], as a seed (the refinement
  /// then protects only the vertices it inserts from now on).
  void mark_all_as_seeds();
  /// [U] uses max(rho, floor) (Å) instead of rho (0: the true rho, default).
  /// Facets that a lower floor makes violate [U] are found by refine()'s scan.
  void set_rho_floor(double floor) { rho_floor_ = floor; }

  /// Live sample ids, increasing.
  std::vector<Index> samples() const;
  const Vec3& position(Index v) const { return dt_.point(v); }
  double rho(Index v) const { return rho_[v]; }
  Index cell(Index v) const { return cell_[v]; }

  /// Refines until every restricted facet meets [U] and has no bounding
  /// vertex, every restricted edge meets [L] and every sample's restricted
  /// star is one disc — or `max_rounds` global rounds have passed. [U]:
  /// insert the facet's surface Delaunay centre (the largest violation
  /// first); [L]: delete an endpoint that is a seed (a refinement vertex is
  /// never deleted: inserted at the centre of an empty ball, it is at least
  /// that ball's radius from every other sample, so an edge between two of
  /// them cannot violate [L], papers/refine/local_refinement.md
  /// "Termination"); a non-disc star: insert the centre of its largest
  /// restricted facet; a sample with no restricted facet gets a ring of six
  /// samples around it in its tangent plane (once; a seed still without
  /// facets is then deleted). Returns
  /// true if it converged; the counts left are in stats().
  bool refine(int max_rounds);

  /// The restricted Delaunay triangulation as a mesh: the facets between a
  /// tetrahedron whose circumcentre is inside F_c and one outside, oriented
  /// towards the outside one (outward), vertices compacted (samples in id
  /// order), with unit normals grad f / |grad f|. `vertex_ids` (if not null)
  /// receives the sample id of each mesh vertex; `data` (if not null) the
  /// atom, rho and mixed-cell dimension of each vertex's patch.
  geometry::IndexedMesh extract(std::vector<Index>* vertex_ids = nullptr, skin::SkinVertexData* data = nullptr) const;

 private:
  struct Facet {
    double ratio;  // circumradius / (C Q min rho); +inf with a bounding vertex
    Index tet;
    int face;
    std::uint32_t birth;
    bool operator<(const Facet& o) const { return ratio < o.ratio; }
  };
  struct RoundReport {
    std::vector<std::array<Index, 2>> l_edges;
    std::vector<Index> bad_vertices, isolated;
    std::vector<Facet> u_facets;
    std::size_t u = 0;
  };

  /// Calls fn(t, face, {a, b, c}) once for every restricted facet, from its
  /// inside tetrahedron t (circumcentre inside F_c); (a, b, c) is ordered
  /// counter-clockwise seen from outside.
  template <class Fn>
  void for_each_restricted_facet(Fn&& fn) const {
    dt_.for_each_tet([&](Index t) {
      if (!(value_[t] < 0)) return;
      for (int f = 0; f < 4; ++f) {
        if (!restricted(t, f)) continue;
        const auto& v = dt_.tet(t);
        const auto& fv = geometry::DelaunayTriangulation::kFaceVertices[f];
        // (v[fv0], v[fv1], v[fv2]) has its normal into t (inside): reverse it.
        fn(t, f, std::array<Index, 3>{v[fv[0]], v[fv[2]], v[fv[1]]});
      }
    });
  }
  void ensure_capacity();
  void classify(Index t);
  void after_operation();
  void queue_if_bad(Index t, int face);
  bool restricted(Index t, int face) const;
  double facet_ratio(Index t, int face) const;
  bool insert_centre(Index t, int face);
  std::size_t add_ring(Index v);
  void process_queue();
  RoundReport scan() const;

  const skin::SkinSurface* skin_;
  LevelSet level_;
  skin::SizeConstants size_;
  geometry::DelaunayTriangulation dt_;
  // Per sample (by Delaunay vertex id).
  std::vector<double> rho_;
  std::vector<Index> cell_;
  std::vector<std::uint8_t> seed_, ringed_;
  // Per tetrahedron (by id): circumcentre, f - c there, and a stamp that
  // changes whenever the slot is reused.
  std::vector<Vec3> cc_;
  std::vector<double> value_;
  std::vector<std::uint32_t> birth_;
  std::vector<std::uint32_t> op_mark_;
  std::uint32_t births_ = 0, op_ = 0;
  bool batch_ = false;
  double rho_floor_ = 0;
  std::priority_queue<Facet> queue_;
  SampleStats stats_;
};

}  // namespace skinmesh::dynamic
