// geometry/triangulation/point_grid.h: uniform grids over points for fixed-radius neighbour
// queries: PointGrid, a hash grid that grows point by point (critical-point
// lookup, front proximity), LeveledPointGrid and LeveledIndexGrid, hash grids
// per band of the points' scales whose points can also be removed (the
// sweep's front and protecting spheres; its vertices, by id only),
// FlatPointGrid, a grid over a fixed point set stored in flat arrays (the
// verifier's restricted-Delaunay test), and SizedItemGrid, items with a size
// (a detour's balls, a cut's edges) in one grid per octave of size.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "core/assert.h"
#include "core/growable_array.h"
#include "core/types.h"
#include "geometry/triangulation/key_index.h"

namespace skinmesh::geometry {

namespace detail {

/// The occupied cells of a uniform grid of cubic cells of side `cell_size`
/// (Å), numbered densely 0, 1, 2, ... in the order they were first added (a
/// KeyIndex of the cells' integer coordinates). The grids below keep their
/// per-cell data in arrays indexed by that number.
class CellIndex {
 public:
  static constexpr std::uint32_t kNone = KeyIndex::kNone;
  using Cell = std::array<std::int64_t, 3>;

  /// Pre: cell_size > 0.
  explicit CellIndex(double cell_size) : h_(cell_size) {}

  /// The cell holding p.
  Cell cell_of(const Vec3& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x() / h_)), static_cast<std::int64_t>(std::floor(p.y() / h_)),
            static_cast<std::int64_t>(std::floor(p.z() / h_))};
  }
  /// The number of cell c, or kNone if it was never added.
  std::uint32_t find(const Cell& c) const { return keys_.find(key(c)); }
  /// The number of cell c, adding it (as number size()) if it is new.
  std::uint32_t find_or_add(const Cell& c) { return keys_.find_or_add(key(c)).first; }
  /// Calls fn(number) for every added cell meeting the box [q - r, q + r]³, in
  /// (x, y, z) order of the cells.
  template <class Fn>
  void for_each_cell_near(const Vec3& q, double r, Fn&& fn) const {
    const Cell lo = cell_of(q - Vec3::Constant(r)), hi = cell_of(q + Vec3::Constant(r));
    for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
      for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k) {
          const std::uint32_t c = find({i, j, k});
          if (c != kNone) fn(c);
        }
  }
  double cell_size() const { return h_; }
  /// Number of cells added.
  std::uint32_t size() const { return keys_.size(); }

 private:
  static std::uint64_t key(const Cell& c) {
    // 21 bits per axis, 63 in all (cells beyond ±2^20 wrap, which only costs speed).
    const std::uint64_t m = (1u << 21) - 1;
    return (static_cast<std::uint64_t>(c[0]) & m) | ((static_cast<std::uint64_t>(c[1]) & m) << 21) |
           ((static_cast<std::uint64_t>(c[2]) & m) << 42);
  }
  double h_;
  KeyIndex keys_;
};

}  // namespace detail

/// Uniform grid of cubic cells of side `cell_size` (Å) hashing point indices.
/// Points can be added after construction; removal is not supported (callers
/// filter stale entries, or use LeveledPointGrid). Queries visit the cells
/// overlapping the query box in (x, y, z) order, and, within a cell, the
/// points in insertion order.
///
/// Layout: detail::CellIndex numbers the occupied cells; each cell keeps the
/// first and last of its points; the points live in one flat array, each
/// linked to the next point of its cell. No allocation per cell, one probe
/// sequence per visited cell: the queries of the sweep and the refinement
/// are many and small, and a node per cell cost more than the points it
/// held ([measured] papers/bench/profile.md, "After").
class PointGrid {
 public:
  /// Pre: cell_size > 0.
  explicit PointGrid(double cell_size) : index_(cell_size) {}

  /// Adds point `id` at position p.
  void insert(Index id, const Vec3& p) {
    const std::uint32_t c = index_.find_or_add(index_.cell_of(p));
    if (c == ends_.size()) ends_.push_back({kNone, kNone});
    const auto e = static_cast<std::uint32_t>(entries_.size());
    entries_.push_back({p, id, kNone});
    if (ends_[c].head == kNone) {
      ends_[c].head = e;
    } else {
      entries_[ends_[c].tail].next = e;
    }
    ends_[c].tail = e;
  }

  /// Calls fn(id, position) for every point within distance r (Å) of q.
  template <class Fn>
  void for_each_near(const Vec3& q, double r, Fn&& fn) const {
    const double r2 = r * r;
    index_.for_each_cell_near(q, r, [&](std::uint32_t c) {
      for (std::uint32_t e = ends_[c].head; e != kNone; e = entries_[e].next)
        if ((entries_[e].p - q).squaredNorm() <= r2) fn(entries_[e].id, entries_[e].p);
    });
  }

  double cell_size() const { return index_.cell_size(); }

 private:
  static constexpr std::uint32_t kNone = detail::CellIndex::kNone;
  struct Entry {
    Vec3 p;
    Index id;
    std::uint32_t next;  ///< the next point of the same cell, or kNone
  };
  struct Ends {
    std::uint32_t head, tail;
  };
  detail::CellIndex index_;
  std::vector<Ends> ends_;  ///< per cell number: its first and last point
  std::vector<Entry> entries_;
};

/// Points that each carry a scale (Å), in one hash grid per band of
/// `octaves` octaves of scales: a point of scale s lives at level
/// k = floor(floor(log2 s) / octaves), in cells of side
/// cell_per_scale · 2^((k+1) octaves), so that a cell is as large as the
/// scales of its level and not as the largest scale of the whole set. A query names the
/// range of scales its points can have (for the sweep: the local length scale
/// rho is 1-Lipschitz, so the points within r of a skin point q have
/// rho(q) - r <= rho <= rho(q) + r) and visits only those levels; in each it
/// reads the cells meeting its box, or the level's occupied cells when they
/// are fewer. Costs thus follow the local scale: one region of large rho does
/// not make the queries elsewhere read many points. Each cell keeps its points
/// in a contiguous block of entries (see kCopies below); removal moves the
/// cell's last point into the hole. The blocks
/// share one pool, their capacities powers of two: a full block moves to one
/// twice its size and leaves its place to the next block of its size, and an
/// emptied one is given back, so the grid needs no allocation of its own per
/// cell (a std::vector per cell cost 24 bytes plus an allocation's header and
/// rounding, on the sweep's vertex grid about as much as the points: papers/
/// decompose/history.md, "The sweep's grids in one pool"). An erasable grid finds a
/// point's place by its id in pages of 1024 ids, a page allocated on its first
/// point and freed with its last: the sweep's front moves through the vertex
/// ids, so the table holds the front's pages, not one entry per vertex. A query
/// reads a cell's entries sequentially (with copies: filters them with a
/// distance bound padded by the single-precision rounding) and decides each
/// with the exact test on the caller's double-precision positions, so it
/// reports exactly the points of its scale range that a scan reports. The visiting
/// order is deterministic but not the insertion order: callers choose among
/// the points by their own rule (nearest, ties to the lower id).
///
/// kCopies: each entry holds a single-precision copy of its point and its id
/// (16 bytes; the filter above reads the copies in order), or only the id (4
/// bytes; a query reads every point of a cell from the caller's positions).
/// LeveledPointGrid (the sweep's free front and protecting spheres, few points
/// read often) and LeveledIndexGrid (the sweep's vertices, every vertex of the
/// mesh kept to the end of the sweep).
template <bool kCopies>
class BasicLeveledPointGrid {
 public:
  /// Levels are clamped to [kMinLevel, kMaxLevel]: scales from about 1e-12
  /// to 4e6 Å get their own level, smaller or larger ones share the end levels.
  static constexpr int kMinLevel = -40, kMaxLevel = 22;

  /// Pre: cell_per_scale > 0. With erasable = false the grid keeps no table
  /// from ids to places and erase() must not be called.
  /// Pre: octaves >= 1.
  explicit BasicLeveledPointGrid(double cell_per_scale, int octaves, bool erasable = true)
      : factor_(cell_per_scale), octaves_(octaves), erasable_(erasable), level_cells_(kMaxLevel - kMinLevel + 1) {
    for (int level = kMinLevel; level <= kMaxLevel; ++level)
      inverse_side_[level - kMinLevel] = 1 / std::ldexp(factor_, (level + 1) * octaves_);
  }

  /// Adds point `id` at position p (finite) with scale `scale` (Å; any value:
  /// non-positive or tiny ones go to the lowest level). Pre: id is not in the
  /// grid; the positions passed to the queries hold p at index id.
  void insert(Index id, const Vec3& p, double scale) { insert_at(level_of(scale), id, p); }
  /// Adds point `id` at position p to every level whose scales meet
  /// [scale_lo, scale_hi] (Å): the levels of the queries that can reach it, so
  /// that such a query reads its own level alone (for_each_near_at). Pre: the
  /// grid is not erasable (a point may have several entries).
  void insert_for_queries(Index id, const Vec3& p, double scale_lo, double scale_hi) {
    SKINMESH_ASSERT_MSG(!erasable_, "insert_for_queries() on an erasable grid");
    const int last = level_of(scale_hi);
    for (int level = level_of(scale_lo); level <= last; ++level) insert_at(level, id, p);
  }
  /// Calls fn(id, position) for every point inserted by insert_for_queries()
  /// for a range of scales that holds `scale` and whose position lies within
  /// distance r of q (as for_each_near). Reads one level.
  template <class Fn>
  void for_each_near_at(const Vec3& q, double r, double scale, std::span<const Vec3> positions, Fn&& fn) const {
    const int level = level_of(scale);
    if (level >= lowest_ && level <= highest_) visit_level(level, q, r, positions, fn);
  }
  /// Removes point `id`; does nothing if it is not in the grid. Pre: erasable.
  void erase(Index id) {
    SKINMESH_ASSERT_MSG(erasable_, "erase() on a grid made without erasure");
    if (!contains(id)) return;
    Where& w = where(id);
    Block& cell = blocks_[w.cell];
    Entry& hole = pool_[cell.start + w.slot];
    hole = pool_[cell.start + cell.size - 1];
    where(id_of(hole)).slot = w.slot;
    --cell.size;
    // A cell the front has passed gives its block back: the grid of the
    // sweep's front then holds memory for the front, not for every place
    // it has been.
    if (cell.size == 0) {
      free_block(cell.start, cell.capacity);
      cell = Block{};
    }
    w = {kNone, 0};
    const std::size_t page = id >> kPageBits;
    if (--page_points_[page] == 0) where_pages_[page].reset();
  }
  /// True if point `id` is in the grid. Pre: erasable.
  bool contains(Index id) const {
    SKINMESH_ASSERT_MSG(erasable_, "contains() on a grid made without erasure");
    const std::size_t page = id >> kPageBits;
    return page < where_pages_.size() && where_pages_[page] && where(id).cell != kNone;
  }

  /// Bytes the grid holds (its pool, tables and the pages of an erasable
  /// grid), for tests and measurements.
  std::size_t memory_bytes() const {
    std::size_t b = pool_.capacity() * sizeof(Entry) + blocks_.capacity() * sizeof(Block) + keys_.memory_bytes() +
                    where_pages_.capacity() * sizeof(where_pages_[0]) + page_points_.capacity() * sizeof(std::uint32_t);
    for (const auto& f : free_) b += f.capacity() * sizeof(std::uint32_t);
    for (const auto& l : level_cells_) b += l.capacity() * sizeof(std::uint32_t);
    for (const auto& page : where_pages_)
      if (page) b += kPageSize * sizeof(Where);
    return b;
  }

  /// Calls fn(id, position) for every point whose scale lies in
  /// [scale_lo, scale_hi] (Å; its level's range meets it) and whose position
  /// (positions[id]) lies within distance r of q, |position - q|² <= r² in
  /// double precision. Points of other scales may be reported too, and a point
  /// added by insert_for_queries() once per level it is in.
  template <class Fn>
  void for_each_near(const Vec3& q, double r, double scale_lo, double scale_hi, std::span<const Vec3> positions,
                     Fn&& fn) const {
    const int first = std::max(lowest_, scale_lo > 0 ? level_of(scale_lo) : kMinLevel);
    const int last = std::min(highest_, level_of(scale_hi));
    for (int level = first; level <= last; ++level) visit_level(level, q, r, positions, fn);
  }

  /// The level of a point of scale `scale`.
  int level_of(double scale) const {
    if (!(scale > 0) || !std::isfinite(scale)) return scale > 0 ? kMaxLevel : kMinLevel;
    const int e = std::ilogb(scale);
    const int k = e >= 0 ? e / octaves_ : -((-e + octaves_ - 1) / octaves_);  // floor(e / octaves)
    return std::clamp(k, kMinLevel, kMaxLevel);
  }

 private:
  static constexpr std::uint32_t kNone = KeyIndex::kNone;
  struct CopyEntry {
    float p[3];
    Index id;
  };
  using Entry = std::conditional_t<kCopies, CopyEntry, Index>;
  static Index id_of(const Entry& e) {
    if constexpr (kCopies)
      return e.id;
    else
      return e;
  }
  static Entry entry(Index id, const Vec3& p) {
    if constexpr (kCopies)
      return {{static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())}, id};
    else
      return id;
  }
  struct Where {
    std::uint32_t cell, slot;
  };
  /// A cell's points: entries [start, start + size) of pool_, in a block of
  /// `capacity` entries (0 or a power of two).
  struct Block {
    std::uint32_t start = 0, size = 0, capacity = 0;
  };
  static constexpr unsigned kPageBits = 10;
  static constexpr std::size_t kPageSize = std::size_t{1} << kPageBits;
  Where& where(Index id) { return where_pages_[id >> kPageBits][id & (kPageSize - 1)]; }
  const Where& where(Index id) const { return where_pages_[id >> kPageBits][id & (kPageSize - 1)]; }
  /// The start of a free block of `capacity` entries (a power of two): the
  /// last one given back of that size, or new at the end of the pool.
  std::uint32_t take_block(std::uint32_t capacity) {
    std::vector<std::uint32_t>& list = free_[std::countr_zero(capacity)];
    if (!list.empty()) {
      const std::uint32_t start = list.back();
      list.pop_back();
      return start;
    }
    const std::size_t start = pool_.size();
    if (start + capacity > std::numeric_limits<std::uint32_t>::max())
      throw std::length_error("LeveledPointGrid: more than 2^32 point entries");
    pool_.resize(start + capacity);
    return static_cast<std::uint32_t>(start);
  }
  void free_block(std::uint32_t start, std::uint32_t capacity) { free_[std::countr_zero(capacity)].push_back(start); }
  /// Appends e to cell number c, moving its block to one twice as large when full.
  void push(std::uint32_t c, const Entry& e) {
    Block& b = blocks_[c];
    if (b.size == b.capacity) {
      if (b.capacity >= (std::uint32_t{1} << 31)) throw std::length_error("LeveledPointGrid: 2^31 points in one cell");
      const std::uint32_t capacity = b.capacity == 0 ? 1 : 2 * b.capacity;
      const std::uint32_t start = take_block(capacity);
      for (std::uint32_t i = 0; i < b.size; ++i) pool_[start + i] = pool_[b.start + i];
      if (b.capacity != 0) free_block(b.start, b.capacity);
      b.start = start;
      b.capacity = capacity;
    }
    pool_[b.start + b.size++] = e;
  }
  void insert_at(int level, Index id, const Vec3& p) {
    const double inv = inverse_side_[level - kMinLevel];
    const std::array<std::int64_t, 3> c{static_cast<std::int64_t>(std::floor(p.x() * inv)),
                                        static_cast<std::int64_t>(std::floor(p.y() * inv)),
                                        static_cast<std::int64_t>(std::floor(p.z() * inv))};
    const auto [number, added] = keys_.find_or_add(key(level, c));
    if (added) {
      blocks_.emplace_back();
      level_cells_[level - kMinLevel].push_back(number);
    }
    if (erasable_) {
      const std::size_t page = id >> kPageBits;
      if (page >= where_pages_.size()) {
        where_pages_.resize(page + 1);
        page_points_.resize(page + 1, 0);
      }
      if (!where_pages_[page]) {
        where_pages_[page] = std::make_unique<Where[]>(kPageSize);
        std::fill_n(where_pages_[page].get(), kPageSize, Where{kNone, 0});
      }
      ++page_points_[page];
      where(id) = {number, blocks_[number].size};
    }
    push(number, entry(id, p));
    // |float(x) - x| <= 2^-24 |x| per coordinate: a stored copy lies within
    // sqrt(3) 2^-24 max_abs_ of the true point (padded). Without copies the
    // queries test the true points only and need no pad.
    if constexpr (kCopies) {
      if (const double m = p.cwiseAbs().maxCoeff(); m > max_abs_) {
        max_abs_ = m;
        pad_ = 1.05e-7 * max_abs_ + 1e-300;
      }
    }
    lowest_ = std::min(lowest_, level), highest_ = std::max(highest_, level);
  }
  /// The points of one level within r of q: the cells meeting the query's
  /// box, or the level's occupied cells when they are fewer.
  template <class Fn>
  void visit_level(int level, const Vec3& q, double r, std::span<const Vec3> positions, Fn&& fn) const {
    const std::vector<std::uint32_t>& occupied = level_cells_[level - kMinLevel];
    if (occupied.empty()) return;
    const double r2 = r * r;
    const double rp = r + pad_;
    [[maybe_unused]] const double rp2 = rp * rp * (1 + 1e-12);
    auto visit = [&](std::uint32_t c) {
      const Block& b = blocks_[c];
      for (const Entry *e = pool_.data() + b.start, *end = e + b.size; e != end; ++e) {
        if constexpr (kCopies) {
          const double dx = double(e->p[0]) - q.x(), dy = double(e->p[1]) - q.y(), dz = double(e->p[2]) - q.z();
          if (dx * dx + dy * dy + dz * dz > rp2) continue;
        }
        const Index id = id_of(*e);
        const Vec3& p = positions[id];
        if ((p - q).squaredNorm() <= r2) fn(id, p);
      }
    };
    const double inv = inverse_side_[level - kMinLevel];
    std::int64_t lo[3], hi[3];
    double box = 1;
    for (int k = 0; k < 3; ++k) {
      lo[k] = static_cast<std::int64_t>(std::floor((q[k] - rp) * inv));
      hi[k] = static_cast<std::int64_t>(std::floor((q[k] + rp) * inv));
      box *= double(hi[k] - lo[k] + 1);
    }
    if (box > double(occupied.size())) {  // fewer occupied cells than cells in the box: read them all
      for (std::uint32_t c : occupied) visit(c);
      return;
    }
    for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
      for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k) {
          const std::uint32_t c = keys_.find(key(level, {i, j, k}));
          if (c != kNone) visit(c);
        }
  }
  static std::uint64_t key(int level, const std::array<std::int64_t, 3>& c) {
    // 6 bits of level, 19 bits per axis (cells beyond ±2^18 wrap, which only costs speed): 63 in all.
    const std::uint64_t m = (1u << 19) - 1;
    return static_cast<std::uint64_t>(level - kMinLevel) | ((static_cast<std::uint64_t>(c[0]) & m) << 6) |
           ((static_cast<std::uint64_t>(c[1]) & m) << 25) | ((static_cast<std::uint64_t>(c[2]) & m) << 44);
  }
  double factor_;
  int octaves_;
  bool erasable_ = true;
  std::array<double, kMaxLevel - kMinLevel + 1> inverse_side_{};  ///< per level: 1 / its cell side
  KeyIndex keys_;
  GrowableArray<Entry> pool_;                             ///< the cells' blocks
  std::vector<Block> blocks_;                             ///< per cell number: its block
  std::array<std::vector<std::uint32_t>, 32> free_;       ///< per log2 capacity: free blocks' starts
  std::vector<std::vector<std::uint32_t>> level_cells_;   ///< per level: its cell numbers
  std::vector<std::unique_ptr<Where[]>> where_pages_;     ///< per page of ids (erasable_ only)
  std::vector<std::uint32_t> page_points_;                ///< per page: its points in the grid
  int lowest_ = kMaxLevel + 1, highest_ = kMinLevel - 1;  ///< levels with points so far
  double max_abs_ = 0, pad_ = 1e-300;
};

/// The leveled grid with a copy of every point in its entries.
using LeveledPointGrid = BasicLeveledPointGrid<true>;
/// The leveled grid with only the points' ids in its entries (4 bytes each
/// instead of 16): a query reads the points from the positions it is given.
using LeveledIndexGrid = BasicLeveledPointGrid<false>;

/// Uniform grid of cubic cells over a fixed set of points, built once, stored
/// by columns: one offset per (x, y) column of the bounding box, and per
/// column only its occupied cells (their z and the start of their points),
/// the points sorted by column, then cell, then index. A query reads one
/// contiguous run of points per column of its box. Memory is O(n) whatever
/// the shape: a hollow shell of radius R with n points needs (2R/h)² column
/// offsets, not the (2R/h)³ offsets of a dense box, so the cell side stays
/// the requested one (a dense box of at most 8 cells per point had to
/// double it on the 1.2-million-atom shell until each cell held 16 times
/// the points it should, papers/decompose/history.md, "The top rung"). The side is the
/// requested size, doubled only while there are more than kMaxCellsPerPoint
/// columns per point (plus 4096). Queries report exactly the points a linear
/// scan with the same distance test reports, in the order of increasing
/// (x, y, z) cell and index (tests/geometry/point_grid_test.cpp).
///
/// kCopies: each entry holds a copy of its point (32 bytes, read in order by
/// a query; the points may change or go after the build), or only its index
/// (4 bytes; a query reads the point from the span the grid was built on,
/// which must outlive the grid unchanged). FlatPointGrid and FlatIndexGrid.
template <bool kCopies>
class BasicFlatPointGrid {
 public:
  /// Bound on the number of columns per point (see the class comment).
  static constexpr double kMaxCellsPerPoint = 8.0;

  /// Grid over points[i], with id i, for every point with finite coordinates
  /// (the others are left out). Pre: cell_size > 0 (Å).
  BasicFlatPointGrid(std::span<const Vec3> points, double cell_size) : points_(points) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    std::size_t n = 0;
    for (const Vec3& p : points)
      if (p.allFinite()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p), ++n;
    if (n == 0) {
      column_cells_.assign(2, 0);
      cells_.push_back({0, 0});
      return;
    }
    lo_ = lo;
    h_ = cell_size;
    const double max_columns = kMaxCellsPerPoint * double(n) + 4096.0;
    for (;;) {
      double columns = 1.0;
      for (int k = 0; k < 2; ++k) columns *= std::floor((hi[k] - lo[k]) / h_) + 1.0;
      // z cells are numbered in 32 bits.
      if (columns <= max_columns && std::floor((hi[2] - lo[2]) / h_) + 1.0 < 2147483647.0) break;
      h_ *= 2.0;
    }
    inv_ = 1.0 / h_;
    for (int k = 0; k < 3; ++k) dims_[k] = std::int64_t(std::floor((hi[k] - lo[k]) / h_)) + 1;
    // A counting sort by column, stable in the index, then each column's
    // points sorted by (z, index): a cell's points stay in index order.
    // column_cells_ holds the columns' counts, then their ends, then (filled
    // from the ends, in decreasing index order) their starts, shifted down.
    const std::size_t num_columns = std::size_t(dims_[0] * dims_[1]);
    column_cells_.assign(num_columns + 1, 0);
    // Each point's column and z cell, computed once (the sorts below compare
    // z cells many times per point).
    std::vector<std::uint32_t> point_column(points.size()), point_z(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
      if (points[i].allFinite()) {
        point_column[i] = std::uint32_t(column_of(points[i]));
        point_z[i] = std::uint32_t(cell(points[i].z(), 2));
        ++column_cells_[point_column[i] + 1];
      }
    for (std::size_t c = 1; c <= num_columns; ++c) column_cells_[c] += column_cells_[c - 1];
    std::vector<std::uint32_t> order(n);
    for (std::size_t i = points.size(); i-- > 0;)
      if (points[i].allFinite()) order[--column_cells_[point_column[i] + 1]] = std::uint32_t(i);
    std::vector<std::uint32_t>().swap(point_column);
    for (std::size_t c = 0; c < num_columns; ++c) column_cells_[c] = column_cells_[c + 1];
    column_cells_[num_columns] = std::uint32_t(n);
    auto z_of = [&](std::uint32_t i) { return point_z[i]; };
    for (std::size_t c = 0; c < num_columns; ++c)
      if (column_cells_[c + 1] - column_cells_[c] > 1)
        std::sort(order.begin() + column_cells_[c], order.begin() + column_cells_[c + 1],
                  [&](std::uint32_t i, std::uint32_t j) { return z_of(i) != z_of(j) ? z_of(i) < z_of(j) : i < j; });
    // Cells: the runs of equal z in each column; column_cells_[c] becomes the
    // column's first cell (its entry range is read before it is replaced).
    entries_.resize(n);
    for (std::size_t e = 0; e < n; ++e) entries_[e] = make_entry(order[e]);
    for (std::size_t c = 0; c < num_columns; ++c) {
      const std::uint32_t begin = column_cells_[c], end = column_cells_[c + 1];
      column_cells_[c] = std::uint32_t(cells_.size());
      for (std::uint32_t e = begin; e < end; ++e)
        if (e == begin || z_of(order[e]) != cells_.back().z) cells_.push_back({z_of(order[e]), e});
    }
    column_cells_[num_columns] = std::uint32_t(cells_.size());
    cells_.push_back({0, std::uint32_t(n)});  // the end of the last cell
    cells_.shrink_to_fit();
  }

  /// Calls fn(id, position) for every point p with |p - q|² <= r² (squared
  /// norms in double precision, as PointGrid::for_each_near()).
  template <class Fn>
  void for_each_near(const Vec3& q, double r, Fn&& fn) const {
    any_near(q, r, [&](Index id, const Vec3& p) {
      fn(id, p);
      return false;
    });
  }

  /// Calls pred(id, position) for the points p with |p - q|² <= r² until it
  /// returns true; returns whether it did (false if no point satisfied it).
  template <class Pred>
  bool any_near(const Vec3& q, double r, Pred&& pred) const {
    if (entries_.empty() || !q.allFinite() || !(r >= 0.0) || !std::isfinite(r)) return false;
    // Pad the box by a relative 1e-12 (and against underflow) so that it holds
    // every point passing the rounded distance test below.
    const double rb = r * (1.0 + 1e-12) + 1e-150;
    std::int64_t a[3], b[3];
    for (int k = 0; k < 3; ++k) {
      a[k] = cell(q[k] - rb, k);
      b[k] = cell(q[k] + rb, k);
    }
    const double r2 = r * r;
    const auto za = std::uint32_t(a[2]), zb = std::uint32_t(b[2]);
    for (std::int64_t x = a[0]; x <= b[0]; ++x)
      for (std::int64_t y = a[1]; y <= b[1]; ++y) {
        const std::size_t column = std::size_t(x * dims_[1] + y);
        std::uint32_t first = column_cells_[column], last = column_cells_[column + 1];
        if (first == last) continue;
        // The column's cells from z = za to zb (a short column: a scan).
        if (last - first > 8)
          first = std::uint32_t(std::lower_bound(cells_.begin() + first, cells_.begin() + last, za,
                                                 [](const Cell& c, std::uint32_t z) { return c.z < z; }) -
                                cells_.begin());
        else
          while (first < last && cells_[first].z < za) ++first;
        std::uint32_t end = first;
        while (end < last && cells_[end].z <= zb) ++end;
        for (std::uint32_t e = cells_[first].start, stop = cells_[end].start; e < stop; ++e) {
          const Vec3& p = position(entries_[e]);
          if ((p - q).squaredNorm() <= r2 && pred(id(entries_[e]), p)) return true;
        }
      }
    return false;
  }

  /// Side of the cells actually used (Å): the requested size or a power-of-two multiple.
  double cell_size() const { return h_; }
  /// Number of occupied cells.
  std::size_t num_cells() const { return cells_.size() - 1; }
  /// Number of (x, y) columns of the grid's bounding box.
  std::size_t num_columns() const { return column_cells_.size() - 1; }

 private:
  struct CopyEntry {
    Vec3 p;
    Index id;
  };
  using Entry = std::conditional_t<kCopies, CopyEntry, Index>;
  /// An occupied cell: its z and the first of its entries (the next cell's
  /// start ends it; a sentinel ends the last).
  struct Cell {
    std::uint32_t z, start;
  };
  Entry make_entry(std::size_t i) const {
    if constexpr (kCopies)
      return {points_[i], Index(i)};
    else
      return Index(i);
  }
  const Vec3& position(const Entry& e) const {
    if constexpr (kCopies)
      return e.p;
    else
      return points_[e];
  }
  static Index id(const Entry& e) {
    if constexpr (kCopies)
      return e.id;
    else
      return e;
  }
  /// Cell coordinate along axis k, clamped to the grid: monotone in x.
  std::int64_t cell(double x, int k) const {
    const double t = std::floor((x - lo_[k]) * inv_);
    return std::int64_t(std::clamp(t, 0.0, double(dims_[k] - 1)));
  }
  std::size_t column_of(const Vec3& p) const { return std::size_t(cell(p.x(), 0) * dims_[1] + cell(p.y(), 1)); }
  std::span<const Vec3> points_;  ///< read by queries only without copies
  Vec3 lo_ = Vec3::Zero();
  double h_ = 1.0, inv_ = 1.0;
  std::int64_t dims_[3] = {1, 1, 1};
  /// Cells of column c: cells_[column_cells_[c] .. column_cells_[c + 1]).
  std::vector<std::uint32_t> column_cells_;
  std::vector<Cell> cells_;  ///< occupied cells by (column, z), and an end sentinel
  std::vector<Entry> entries_;
};

/// The grid with a copy of every point in its entries.
using FlatPointGrid = BasicFlatPointGrid<true>;
/// The grid with only the points' indices in its entries (4 bytes each
/// instead of 32): the points must outlive it unchanged.
using FlatIndexGrid = BasicFlatPointGrid<false>;

/// Items with a position and a size s (a ball's radius, half a segment's
/// length), in one point grid per octave of s, each with cells twice its
/// largest s: for_each_near visits each level with the query's reach plus
/// that level's largest s, so a query reads the items of every size near it
/// and its cost follows the sizes there, not the largest of all. The sizes
/// below half the median share the lowest level: a level of cells far
/// smaller than a query's reach would make the query visit many cells. Up to
/// max_scanned items are not gridded but read one after the other.
class SizedItemGrid {
 public:
  /// The grid of items i at p[i] with size s[i] >= 0 (Å), id i; up to
  /// max_scanned items are read one after the other instead. [measured] The
  /// default suits queries that mostly hit: for the sweep's parking test
  /// reading a few hundred is cheaper than probing the cells of every level
  /// (maltoporin at probe 0 in 24 detoured slabs: sweep 45.6 s scanning, 59.0 s
  /// with levels for every cut); the cut tracer, whose steps mostly meet no
  /// ball, grids every ball (0: the cuts of a 218,760-atom shell chosen in
  /// 26.1 s instead of 30.9 s).
  void build(const std::vector<Vec3>& p, const std::vector<double>& s, std::size_t max_scanned = kScanned) {
    levels_.clear();
    scanned_ = s.size() <= max_scanned ? s.size() : 0;
    if (s.empty() || scanned_ > 0) return;
    std::vector<double> sorted = s;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const int floor = std::ilogb(std::max(0.5 * sorted[sorted.size() / 2], kMinSize));
    for (std::size_t i = 0; i < p.size(); ++i) {
      const int octave = std::max(floor, std::ilogb(std::max(s[i], kMinSize)));
      auto it = levels_.find(octave);
      if (it == levels_.end()) {
        const double top = std::ldexp(1.0, octave + 1);
        it = levels_.emplace(octave, Level{top, PointGrid(2 * top)}).first;
      }
      it->second.grid.insert(static_cast<Index>(i), p[i]);
    }
  }
  /// Calls fn(id) for every item whose position lies within reach + s of q
  /// (and for some farther ones).
  template <class Fn>
  void for_each_near(const Vec3& q, double reach, Fn&& fn) const {
    for (std::size_t i = 0; i < scanned_; ++i) fn(static_cast<Index>(i));
    for (const auto& [octave, level] : levels_)
      level.grid.for_each_near(q, (reach + level.top) * (1 + 1e-9) + kMinSize, [&](Index id, const Vec3&) { fn(id); });
  }

 private:
  static constexpr double kMinSize = 1e-9;
  static constexpr std::size_t kScanned = 512;
  std::size_t scanned_ = 0;
  struct Level {
    double top;  ///< the largest size of the level's items (Å)
    PointGrid grid;
  };
  std::map<int, Level> levels_;
};

}  // namespace skinmesh::geometry
