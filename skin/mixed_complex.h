// skin/mixed_complex.h: the mixed complex M_B of a set of weighted points
// (shrink factor s = 1/2), in half-space form, with point location by walking.
// Cheng & Shi 2004 §2.1 and §4.1 "Initialization"; papers/skin/skin_math.md
// §2.3, §3, §9.
// Notes: papers/skin/mixed_complex.md
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/types.h"
#include "geometry/kernel/weighted_point.h"
#include "geometry/triangulation/regular_triangulation.h"

namespace skinmesh::skin {

using geometry::WeightedPoint;

// MixedCell Definition

/// One bounding plane of a mixed cell, as seen from that cell: the cell lies
/// in {x : normal·x <= offset}. `normal` is a unit vector (Å⁰), `offset` in Å.
/// `neighbor` is the cell on the other side of the plane (it shares the
/// plane, papers/skin/skin_math.md §2.3). The two cells are a simplex X and a
/// coface Y = X ∪ {k}; `extra` is k, the point of the triangulation in Y and
/// not in X, on both sides. A value made on the fly by MixedComplex::planes():
/// the complex stores each plane once, for X, and Y sees it negated (exactly:
/// negation commutes with rounding, so every test reads the same numbers as
/// with a copy per side).
struct CellPlane {
  Vec3 normal;
  double offset;
  Index neighbor;
  Index extra;
};

/// The mixed cell mu_X of a simplex X of the regular triangulation and the
/// quadric patch f_X it carries (papers/skin/skin_math.md §3.2 with s = 1/2):
///   f_X(x) = |P_perp y|² - |P_par y|² + w_X / 2,   y = x - z_X,
/// where P_par projects onto the direction space of aff X. `dim` is 0 (vertex:
/// sphere patch), 1 (edge: hyperboloid about the edge line), 2 (triangle:
/// hyperboloid about the normal line through z_X) or 3 (tetrahedron: cavity
/// sphere). `vertices[0..dim]` are point indices of the triangulation (sorted).
struct MixedCell {
  std::array<Index, 4> vertices{kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex};
  /// Focus (orthocentre) z_X (Å) and focus weight w_X (Å²),
  /// papers/skin/skin_math.md §2.2.
  Vec3 focus = Vec3::Zero();
  double focus_weight = 0.0;
  /// Edge direction (dim 1) or triangle normal (dim 2), unit; zero otherwise.
  Vec3 axis = Vec3::Zero();
  /// This cell's planes: the plane uses [first_plane, first_plane + num_planes)
  /// of the complex (MixedComplex::planes(c)).
  Index first_plane = 0;
  Index num_planes = 0;
  /// Dimension of X, 0..3 (one byte, beside `bounding`: 88 bytes per cell).
  std::uint8_t dim = 0;
  /// True if a vertex of X is one of the triangulation's bounding points: such
  /// cells lie far from the skin (papers/skin/mixed_complex.md).
  bool bounding = false;
};
static_assert(sizeof(MixedCell) == 88, "MixedCell: dim and bounding share the last word");

// MixedComplex Definition

/// The mixed complex of the (non-redundant) weighted points of a regular
/// triangulation: one cell per simplex, cells tile the bounding tetrahedron.
/// Construction is O(#simplices); evaluation of f, grad f and rho at a point
/// costs one point location (a walk from a nearby cell) plus O(1).
class MixedComplex {
 public:
  /// Builds every cell (foci, axes, bounding planes) from the triangulation,
  /// on up to `threads` threads (0: every core); the complex, its numbering
  /// included, does not depend on the count. The shrink factor is fixed at
  /// s = 1/2 (Cheng & Shi §2.1). Throws std::logic_error (a failed
  /// SKINMESH_ASSERT) if the complex needs more than 2^31 planes (about 25
  /// million points).
  explicit MixedComplex(const geometry::RegularTriangulation& rt, int threads = 1);

  Index num_cells() const { return static_cast<Index>(cells_.size()); }
  const MixedCell& cell(Index c) const { return cells_[c]; }
  class PlaneRange;
  /// The bounding planes of cell c (a forward range of CellPlane values, in
  /// the same order on every call).
  PlaneRange planes(Index c) const;
  const geometry::RegularTriangulation& triangulation() const { return *rt_; }
  /// Number of cells of dimension d (0..3) that do not touch a bounding point.
  Index num_cells_of_dim(int d) const;
  /// Vertex cell of triangulation point v, or kInvalidIndex if v is redundant.
  Index vertex_cell(Index v) const { return vertex_cell_[v]; }
  /// Length scale L of the input (bounding-box diagonal of the non-bounding
  /// points plus their radii, Å): the unit for tolerances
  /// (papers/skin/skin_math.md §9).
  double length_scale() const { return length_scale_; }

  /// Largest signed distance (Å) by which x lies outside the planes of cell c
  /// (<= 0 inside).
  double violation(Index c, const Vec3& x) const;
  /// Mixed cell containing x, found by a visibility walk from `hint` (any cell;
  /// kInvalidIndex starts from the cell of the triangulation point nearest in
  /// power distance found by walking the triangulation). Points on a shared
  /// face may be reported in either cell: f, grad f and rho are continuous
  /// there. Falls back to a scan of all cells if the walk cycles.
  /// Pre: x finite and inside the bounding tetrahedron. Throws GeometryError
  /// if no cell contains x within 1e-9 L.
  Index locate(const Vec3& x, Index hint = kInvalidIndex) const;

  /// f_X(x) (Å²) of cell c (valid as the skin function for x in mu_c).
  double f(Index c, const Vec3& x) const;
  /// grad f_X(x) = 2 (P_perp y - P_par y) (Å).
  Vec3 gradient(Index c, const Vec3& x) const;
  /// Local length scale rho(x) = |x - z_X| (Å), papers/skin/skin_math.md §4.1
  /// (s = 1/2).
  double rho(Index c, const Vec3& x) const { return (x - cells_[c].focus).norm(); }
  /// A = P_perp - P_par (half the Hessian of f_X).
  Mat3 quadric_matrix(Index c) const;

  /// Number of focus moves made by the construction to put the foci of flat
  /// tetrahedra in the order of their Voronoi edges (papers/skin/mixed_complex.md,
  /// "Flat tetrahedra"); 0 for inputs without cocircular slivers.
  std::size_t num_reordered_foci() const { return num_reordered_foci_; }

 private:
  /// Moves the focus of every flat tetrahedron (all facet normals within
  /// ~1.4e-6 rad of one line) along that line into the slab its four Voronoi
  /// edges allow. Tetrahedron t of the triangulation is cell first_tet_cell + t.
  void order_flat_foci(Index first_tet_cell);

  /// A plane shared by a simplex X and a coface Y = X ∪ {k}, as seen from X.
  struct SharedPlane {
    Vec3 normal;
    double offset;
  };
  /// One plane of a cell: the shared plane's number times two, plus one if
  /// the cell is the coface (it sees the plane negated); and the cell on the
  /// other side.
  struct PlaneUse {
    std::uint32_t plane_side;
    Index neighbor;
  };
  friend class PlaneRange;
  /// v as seen from a plane's side: v for the simplex, -v for the coface (an
  /// exact negation: the sign bit flipped, no branch).
  static double on_side(double v, std::uint32_t plane_side) {
    return std::bit_cast<double>(std::bit_cast<std::uint64_t>(v) ^ (std::uint64_t(plane_side & 1u) << 63));
  }

  const geometry::RegularTriangulation* rt_;
  std::vector<MixedCell> cells_;
  std::vector<SharedPlane> shared_planes_;  ///< one per facet/coface pair (X, Y)
  std::vector<PlaneUse> plane_uses_;        ///< per cell, its planes (first_plane, num_planes)
  std::vector<Index> vertex_cell_;
  double length_scale_ = 1.0;
  std::size_t max_walk_steps_ = 64;  ///< bound of locate()'s walk, from the cell count
  std::size_t num_reordered_foci_ = 0;
};

/// The planes of one cell as CellPlane values (MixedComplex::planes()).
class MixedComplex::PlaneRange {
 public:
  class iterator {
   public:
    using value_type = CellPlane;
    using difference_type = std::ptrdiff_t;
    iterator() = default;
    iterator(const MixedComplex* mc, Index cell, const PlaneUse* u) : mc_(mc), cell_(cell), u_(u) {}
    CellPlane operator*() const {
      const SharedPlane& p = mc_->shared_planes_[u_->plane_side >> 1];
      const std::uint32_t side = u_->plane_side;
      return {Vec3(on_side(p.normal.x(), side), on_side(p.normal.y(), side), on_side(p.normal.z(), side)),
              on_side(p.offset, side), u_->neighbor, extra(side)};
    }
    iterator& operator++() {
      ++u_;
      return *this;
    }
    iterator operator++(int) {
      iterator t = *this;
      ++u_;
      return t;
    }
    bool operator==(const iterator& o) const { return u_ == o.u_; }

   private:
    /// k, the vertex of Y = X ∪ {k} not in X: the first place where the
    /// sorted vertices of Y and X differ (made here, not stored: 4 bytes per
    /// plane saved).
    Index extra(std::uint32_t side) const {
      const MixedCell& X = mc_->cells_[(side & 1u) ? u_->neighbor : cell_];
      const MixedCell& Y = mc_->cells_[(side & 1u) ? cell_ : u_->neighbor];
      for (int i = 0; i < Y.dim; ++i)
        if (Y.vertices[i] != X.vertices[i]) return Y.vertices[i];
      return Y.vertices[Y.dim];
    }
    const MixedComplex* mc_ = nullptr;
    Index cell_ = kInvalidIndex;
    const PlaneUse* u_ = nullptr;
  };
  PlaneRange(const MixedComplex* mc, Index cell, const PlaneUse* b, const PlaneUse* e)
      : mc_(mc), cell_(cell), b_(b), e_(e) {}
  iterator begin() const { return {mc_, cell_, b_}; }
  iterator end() const { return {mc_, cell_, e_}; }
  std::size_t size() const { return static_cast<std::size_t>(e_ - b_); }

 private:
  const MixedComplex* mc_;
  Index cell_;
  const PlaneUse *b_, *e_;
};

inline MixedComplex::PlaneRange MixedComplex::planes(Index c) const {
  const MixedCell& m = cells_[c];
  const PlaneUse* b = plane_uses_.data() + m.first_plane;
  return {this, c, b, b + m.num_planes};
}

/// Focus z_X and focus weight w_X of the simplex with the given vertices
/// (1 to 4 weighted points), papers/skin/skin_math.md §2.2: the point of aff X
/// with equal power distance w_X to every vertex. Computed in coordinates
/// relative to the first vertex. Pre: the points are affinely independent.
void focus_of(std::span<const WeightedPoint> pts, Vec3& z, double& w);

}  // namespace skinmesh::skin
