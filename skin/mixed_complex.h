// skin/mixed_complex.h: the mixed complex M_B of a set of weighted points
// (shrink factor s = 1/2), in half-space form, with point location by walking.
// Cheng & Shi 2004 §2.1 and §4.1 "Initialization"; papers/skin/skin_math.md
// §2.3, §3, §9.
// Notes: papers/skin/mixed_complex.md
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <new>
#include <span>
#include <stdexcept>
#include <thread>
#include <type_traits>
#include <vector>

#include "core/assert.h"
#include "core/growable_array.h"
#include "core/types.h"
#include "geometry/kernel/weighted_point.h"
#include "geometry/triangulation/regular_triangulation.h"

namespace skinmesh::skin {

using geometry::WeightedPoint;

// MixedCell Definition

/// One bounding plane of a mixed cell, as seen from that cell: the cell lies
/// in {x : normal·x <= offset}. `normal` is a unit vector (Å⁰), `offset` in Å.
/// The cell on the other side of plane i of cell c is MixedComplex::
/// neighbors(c)[i] (it shares the plane, papers/skin/skin_math.md §2.3). The
/// two cells are a simplex X and a coface Y = X ∪ {k}, k = MixedComplex::
/// extra_vertex(X, Y). Made by MixedComplex::planes() on first use: the
/// plane is computed as X sees it, and Y stores it negated (exactly: negation
/// commutes with rounding, so both sides read the same numbers). The
/// neighbour is not repeated here: 32 bytes a made plane instead of 40.
struct CellPlane {
  Vec3 normal;
  double offset;
};
static_assert(sizeof(CellPlane) == 32, "CellPlane: a unit normal and an offset");

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
  /// This cell's planes: the entries [first_plane, first_plane + num_planes)
  /// of the complex's plane lists (MixedComplex::neighbors(c), planes(c)).
  Index first_plane = 0;
  Index num_planes = 0;
  /// Dimension of X, 0..3 (one byte, beside `bounding`: 88 bytes per cell).
  std::uint8_t dim = 0;
  /// True if a vertex of X is one of the triangulation's bounding points: such
  /// cells lie far from the skin (papers/skin/mixed_complex.md).
  bool bounding = false;
};
static_assert(sizeof(MixedCell) == 88, "MixedCell: dim and bounding share the last word");

/// The simplex of a mixed cell without its geometry, as the complex keeps it
/// for every cell (24 bytes): the vertices, dimension and `bounding` of its
/// MixedCell, and where its plane list starts.
struct CellSimplex {
  std::array<Index, 4> vertices{kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex};
  Index first_plane = 0;
  std::uint8_t dim = 0;
  bool bounding = false;
};
static_assert(sizeof(CellSimplex) == 24, "CellSimplex: 24 bytes a cell");

// MadeStore Definition

/// Values made on first use for a fixed set of keys (the cells of a mixed
/// complex), read without a lock: per key a 4-byte slot, 0 before its values
/// are made, 1 while a thread makes them, else 2 + their handle in blocks of
/// pages that never move (block << kShift | offset; a list of more values than
/// a block holds gets a block of its own). A pointer per key would take 8
/// bytes for every cell of the complex, most never read
/// (papers/decompose/history.md, "Normals and rho from the cell").
/// Preconditions: at most `max_values` values are made between two
/// release() calls (each key's list once), and release() runs while no other
/// thread reads or makes.
template <class T>
class MadeStore {
 public:
  /// Values per block: 160 KiB of them, rounded down to a power of two.
  static constexpr unsigned kShift = std::bit_width((std::size_t{160} << 10) / sizeof(T)) - 1;
  static constexpr std::size_t kBlock = std::size_t{1} << kShift;

  /// Slots for `keys` keys, all unmade, and a block table for `max_values` values.
  void init(std::size_t keys, std::size_t max_values) {
    slots_ = std::make_unique<std::atomic<std::uint32_t>[]>(keys);
    for (std::size_t k = 0; k < keys; ++k) slots_[k].store(0, std::memory_order_relaxed);
    // A block of its own holds more than kBlock values. An ordinary block is
    // closed only when the next list does not fit in it: its values and that
    // list's exceed kBlock, and each value is counted so at most twice. So
    // fewer than 3 max_values / kBlock + 1 blocks.
    max_blocks_ = 3 * (max_values / kBlock + 1) + 2;
    if (max_blocks_ > (std::size_t{0xffffffff} - 2) >> kShift)
      throw std::length_error("mixed complex: too many cells for 32-bit handles of the made cells");
    blocks_ = std::make_unique<GrowableArray<std::byte>[]>(max_blocks_);
  }
  /// Key k's values, or nullptr if they are not made (or being made).
  const T* find(Index k) const {
    const std::uint32_t h = slots_[k].load(std::memory_order_acquire);
    if (h < 2) [[unlikely]]
      return nullptr;
    return at(h - 2);
  }
  /// Key k's values, made of n values by fill(T*) if no thread made them
  /// yet; if another thread is making them, waits for it (a few
  /// microseconds). If fill throws, the slot is cleared and the error passed
  /// on (a thread that waited makes them again and meets the error itself).
  template <class Fill>
  const T* make(Index k, std::size_t n, Fill&& fill) {
    std::atomic<std::uint32_t>& slot = slots_[k];
    std::uint32_t seen = 0;
    while (!slot.compare_exchange_strong(seen, 1, std::memory_order_acquire)) {
      while (seen == 1) {
        std::this_thread::yield();
        seen = slot.load(std::memory_order_acquire);
      }
      if (seen != 0) return at(seen - 2);
    }
    try {
      const std::uint32_t h = allocate(k, n);
      T* out = const_cast<T*>(at(h));
      fill(out);
      slot.store(h + 2, std::memory_order_release);
      return out;
    } catch (...) {
      slot.store(0, std::memory_order_release);
      throw;
    }
  }
  /// Every slot unmade again and every block given back to the system.
  void release() {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (const Index k : made_keys_) slots_[k].store(0, std::memory_order_relaxed);
    made_keys_ = GrowableArray<Index>();
    for (std::size_t b = 0; b < num_blocks_; ++b) blocks_[b] = GrowableArray<std::byte>();
    num_blocks_ = used_ = 0;
    bytes_ = 0;
  }
  /// Bytes of the values made since the last release.
  std::size_t bytes() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return bytes_;
  }

 private:
  const T* at(std::uint32_t h) const {
    return std::launder(reinterpret_cast<const T*>(blocks_[h >> kShift].data())) + (h & (kBlock - 1));
  }
  /// Room for n values (the handle of the first); records key k.
  std::uint32_t allocate(Index k, std::size_t n) {
    static_assert(std::is_trivially_destructible_v<T> && alignof(T) <= alignof(std::max_align_t));
    const std::lock_guard<std::mutex> lock(mutex_);
    if (num_blocks_ == 0 || used_ + n > kBlock) {
      SKINMESH_ASSERT_MSG(num_blocks_ < max_blocks_, "MadeStore: more values made than declared");
      const std::size_t size = std::max(kBlock, n);
      GrowableArray<std::byte>& bytes = blocks_[num_blocks_++];
      bytes.reserve(size * sizeof(T));  // exactly this size: the block never moves
      bytes.resize(size * sizeof(T));
      std::uninitialized_default_construct_n(reinterpret_cast<T*>(bytes.data()), size);
      used_ = 0;
    }
    const auto h = static_cast<std::uint32_t>(((num_blocks_ - 1) << kShift) | used_);
    used_ = n > kBlock ? kBlock : used_ + n;  // a list larger than a block fills it
    bytes_ += n * sizeof(T);
    made_keys_.push_back(k);
    return h;
  }

  std::unique_ptr<std::atomic<std::uint32_t>[]> slots_;
  std::unique_ptr<GrowableArray<std::byte>[]> blocks_;
  std::size_t max_blocks_ = 0;
  mutable std::mutex mutex_;  ///< guards the members below and the block table's growth
  std::size_t num_blocks_ = 0;
  std::size_t used_ = 0;  ///< values used in the last block
  std::size_t bytes_ = 0;
  /// The keys made since the last release: 4 bytes per key made, so that
  /// release() costs what was made, not the number of keys.
  GrowableArray<Index> made_keys_;
};

// MixedComplex Definition

/// The mixed complex of the (non-redundant) weighted points of a regular
/// triangulation: one cell per simplex, cells tile the bounding tetrahedron.
/// Construction is O(#simplices) and keeps, per cell, its simplex
/// (CellSimplex) and the cells across its planes; a cell's geometry (focus,
/// axis: MixedCell) and its bounding planes are made on first use and kept
/// until release_made(): the mesher reads a few percent of the cells
/// (papers/decompose/history.md, "Cells and planes made on first use").
/// Evaluation of f, grad f and rho at a point costs one point location (a
/// walk from a nearby cell) plus O(1). Every const method may be called from
/// several threads at once, except release_made().
class MixedComplex {
 public:
  /// Numbers every cell and lists its neighbours from the triangulation, and
  /// settles the foci of flat tetrahedra, on up to `threads` threads (0:
  /// every core); the complex, its numbering included, does not depend on
  /// the count. The shrink factor is fixed at
  /// s = 1/2 (Cheng & Shi §2.1). Throws std::logic_error (a failed
  /// SKINMESH_ASSERT) if the cells or their plane lists need more than 2^32
  /// entries (about 25 million points), std::bad_alloc when memory runs out.
  explicit MixedComplex(const geometry::RegularTriangulation& rt, int threads = 1);

  Index num_cells() const { return static_cast<Index>(simplices_.size() - 1); }
  /// Cell c with its geometry, made on the first call and kept until
  /// release_made() (the reference stays valid until then).
  const MixedCell& cell(Index c) const;
  /// Cell c with its geometry (cell(c), bit for bit), made and not kept: for
  /// scans over every cell.
  MixedCell cell_value(Index c) const;
  /// The simplex of cell c (its vertices, dimension, `bounding`), without
  /// its geometry: for scans that need no more.
  const CellSimplex& simplex(Index c) const { return simplices_[c]; }
  /// The bounding planes of cell c, in the same order on every call: its
  /// facets first (in the order of its vertices left out), then its cofaces
  /// by increasing cell number. Made on the first call; the span stays valid
  /// until release_made(). Throws std::logic_error (a failed SKINMESH_ASSERT)
  /// for a non-finite plane, std::bad_alloc when memory runs out.
  std::span<const CellPlane> planes(Index c) const;
  /// The cells across the planes of cell c, in the order of planes(c),
  /// without making a plane (for scans over every cell).
  std::span<const Index> neighbors(Index c) const {
    return {neighbors_.data() + simplices_[c].first_plane, num_planes(c)};
  }
  /// The number of planes of cell c.
  Index num_planes(Index c) const { return simplices_[c + 1].first_plane - simplices_[c].first_plane; }
  /// k, the point of the triangulation in Y and not in X, of two neighbouring
  /// cells a and b (either order; one is the simplex X, the other its coface
  /// Y = X ∪ {k}): the `extra` of their plane.
  Index extra_vertex(Index a, Index b) const {
    const CellSimplex &x = simplices_[a], &y = simplices_[b];
    return x.dim < y.dim ? extra_of(x, y) : extra_of(y, x);
  }
  /// The planes of cell c (those of planes(c), bit for bit) written into
  /// `out`, and not kept: for scans over every cell, which would otherwise
  /// keep the planes of every cell they test.
  void planes_into(Index c, std::vector<CellPlane>& out) const;
  /// Gives back the memory of every cell and plane made so far; later calls
  /// of cell() and planes() make them again, bit for bit the same. Its cost
  /// is the number of cells made since the last release, not the number of
  /// cells, so that releasing after each window of a large input costs what
  /// the window made. Pre: no other thread uses the complex, and no reference
  /// from cell() or span from planes() is used afterwards.
  void release_made() const;
  /// Bytes of the cells (88 each) and planes (40 each) made since the
  /// construction or the last release_made().
  std::size_t made_bytes() const;
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
  double violation(Index c, const Vec3& x) const { return violation(planes(c), x); }
  /// The same for the planes of a cell (planes(c) or planes_into()).
  static double violation(std::span<const CellPlane> planes, const Vec3& x);
  /// Mixed cell containing x, found by a visibility walk from `hint` (any cell;
  /// kInvalidIndex starts from the cell of the triangulation point nearest in
  /// power distance found by walking the triangulation). Points on a shared
  /// face may be reported in either cell: f, grad f and rho are continuous
  /// there. Falls back to a scan of all cells if the walk cycles (their
  /// planes made for the scan and not kept).
  /// Pre: x finite and inside the bounding tetrahedron. Throws GeometryError
  /// if no cell contains x within 1e-9 L.
  Index locate(const Vec3& x, Index hint = kInvalidIndex) const;

  /// f_X(x) (Å²) of cell c (valid as the skin function for x in mu_c).
  double f(Index c, const Vec3& x) const;
  /// grad f_X(x) = 2 (P_perp y - P_par y) (Å).
  Vec3 gradient(Index c, const Vec3& x) const;
  /// The skin's unit outward normal at x in cell c: gradient(c, x)
  /// normalized (the value SkinSurface::sample's gradient gives).
  Vec3 unit_normal(Index c, const Vec3& x) const { return gradient(c, x).normalized(); }
  /// Local length scale rho(x) = |x - z_X| (Å), papers/skin/skin_math.md §4.1
  /// (s = 1/2).
  double rho(Index c, const Vec3& x) const { return (x - cell(c).focus).norm(); }
  /// A = P_perp - P_par (half the Hessian of f_X).
  Mat3 quadric_matrix(Index c) const { return quadric_matrix(cell(c)); }
  /// The same for a cell given (cell() or cell_value()).
  static Mat3 quadric_matrix(const MixedCell& m);

  /// Number of focus moves made by the construction to put the foci of flat
  /// tetrahedra in the order of their Voronoi edges (papers/skin/mixed_complex.md,
  /// "Flat tetrahedra"); 0 for inputs without cocircular slivers.
  std::size_t num_reordered_foci() const { return num_reordered_foci_; }

 private:
  /// Moves the focus of every flat tetrahedron (all facet normals within
  /// ~1.4e-6 rad of one line) along that line into the slab its four Voronoi
  /// edges allow, into moved_foci_. Tetrahedron t of the triangulation is
  /// cell first_tet_cell + t.
  void order_flat_foci(Index first_tet_cell);
  /// k of a simplex X and its coface Y = X ∪ {k}: the first place where their
  /// sorted vertices differ.
  static Index extra_of(const CellSimplex& X, const CellSimplex& Y) {
    for (int i = 0; i < Y.dim; ++i)
      if (Y.vertices[i] != X.vertices[i]) return Y.vertices[i];
    return Y.vertices[Y.dim];
  }
  /// Makes the planes of cell c (or waits for the thread making them) and
  /// returns them.
  const CellPlane* make_planes(Index c) const;
  /// Makes cell c (or waits for the thread making it) and returns it.
  const MixedCell* make_cell(Index c) const;
  /// Cell c's geometry from its simplex (the focus of a flat tetrahedron
  /// from moved_foci_).
  void fill_cell(Index c, MixedCell& m) const;
  /// The focus of cell c (that of cell(c), bit for bit): the made cell's if
  /// there is one, else computed and not kept.
  Vec3 focus_of_cell(Index c) const;
  struct MovedFocus;
  /// The moved focus of tetrahedron cell c, or nullptr.
  const MovedFocus* moved_focus(Index c) const;
  /// Writes the planes of cell c into out[0 .. num_planes).
  void fill_planes(Index c, CellPlane* out) const;

  /// A tetrahedron cell's focus and focus weight moved by order_flat_foci().
  struct MovedFocus {
    Index cell;
    Vec3 focus;
    double weight;
  };

  const geometry::RegularTriangulation* rt_;
  std::vector<CellSimplex> simplices_;  ///< per cell, and one more: the end of the last plane list
  std::vector<MovedFocus> moved_foci_;  ///< by increasing cell
  std::vector<Index> neighbors_;        ///< per cell, the cells across its planes (first_plane, num_planes)
  /// Per cell, its planes once made: 4 bytes per cell, and 40 per plane only
  /// for the cells read. The blocks are pages mapped on their own:
  /// release_made() gives them back to the system, where freed heap blocks of
  /// malloc would stay resident (papers/decompose/history.md, "The made
  /// cells between the stages").
  mutable MadeStore<CellPlane> made_planes_;
  /// Per cell, its geometry once made: 4 bytes per cell, and 88 only for the
  /// cells read.
  mutable MadeStore<MixedCell> made_cells_;
  std::vector<Index> vertex_cell_;
  double length_scale_ = 1.0;
  std::size_t max_walk_steps_ = 64;  ///< bound of locate()'s walk, from the cell count
  std::size_t num_reordered_foci_ = 0;
};

inline std::span<const CellPlane> MixedComplex::planes(Index c) const {
  const CellPlane* p = made_planes_.find(c);
  if (p == nullptr) [[unlikely]]
    p = make_planes(c);
  return {p, num_planes(c)};
}

inline const MixedCell& MixedComplex::cell(Index c) const {
  const MixedCell* p = made_cells_.find(c);
  if (p == nullptr) [[unlikely]]
    p = make_cell(c);
  return *p;
}

/// Focus z_X and focus weight w_X of the simplex with the given vertices
/// (1 to 4 weighted points), papers/skin/skin_math.md §2.2: the point of aff X
/// with equal power distance w_X to every vertex. Computed in coordinates
/// relative to the first vertex. Pre: the points are affinely independent.
void focus_of(std::span<const WeightedPoint> pts, Vec3& z, double& w);

}  // namespace skinmesh::skin
