// geometry/point_grid.h: uniform grids over points for fixed-radius neighbour
// queries: PointGrid, a hash grid that grows point by point (critical-point
// lookup, front proximity), and FlatPointGrid, a grid over a fixed point set
// stored in flat arrays (the verifier's restricted-Delaunay test).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "geometry/types.h"

namespace skinmesh::geometry {

/// Uniform grid of cubic cells of side `cell_size` (Å) hashing point indices.
/// Points can be added after construction; removal is not supported (callers
/// filter stale entries). Queries visit the cells overlapping the query box,
/// and, within a cell, the points in insertion order.
///
/// Layout: an open-addressing table (linear probing, at most half full) maps
/// a cell's key to the first and last of its points; the points live in one
/// flat array, each linked to the next point of its cell. No allocation per
/// cell, one probe sequence per visited cell. [measured: it replaced a
/// node-based std::unordered_map of per-cell vectors; same queries, same
/// order, byte-identical meshes, the sweep of maltoporin 1.58 -> 1.48 s; most
/// of the remaining cost is reading the points of the visited cells
/// (papers/bench/profile.md)]
class PointGrid {
 public:
  /// Pre: cell_size > 0.
  explicit PointGrid(double cell_size) : h_(cell_size), slots_(kInitialSlots) {}

  /// Adds point `id` at position p.
  void insert(Index id, const Vec3& p) {
    if (2 * (used_ + 1) > slots_.size()) grow();
    Slot& s = slot_for_insert(key(cell_of(p)));
    const auto e = static_cast<std::uint32_t>(entries_.size());
    entries_.push_back({p, id, kNone});
    if (s.head == kNone) {
      s.head = e;
    } else {
      entries_[s.tail].next = e;
    }
    s.tail = e;
  }

  /// Calls fn(id, position) for every point within distance r (Å) of q.
  template <class Fn>
  void for_each_near(const Vec3& q, double r, Fn&& fn) const {
    const auto lo = cell_of(q - Vec3::Constant(r));
    const auto hi = cell_of(q + Vec3::Constant(r));
    const double r2 = r * r;
    for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
      for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k) {
          const Slot* s = find(key({i, j, k}));
          if (!s) continue;
          for (std::uint32_t e = s->head; e != kNone; e = entries_[e].next)
            if ((entries_[e].p - q).squaredNorm() <= r2) fn(entries_[e].id, entries_[e].p);
        }
  }

  double cell_size() const { return h_; }

 private:
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  /// Keys use 63 bits, so the all-ones key marks an empty slot.
  static constexpr std::uint64_t kEmpty = std::numeric_limits<std::uint64_t>::max();
  static constexpr std::size_t kInitialSlots = 64;  // a power of two
  struct Entry {
    Vec3 p;
    Index id;
    std::uint32_t next;  ///< the next point of the same cell, or kNone
  };
  struct Slot {
    std::uint64_t key = kEmpty;
    std::uint32_t head = kNone, tail = kNone;
  };
  std::size_t home(std::uint64_t k) const {
    // Fibonacci hashing: the high bits of k times 2^64 / golden ratio.
    return static_cast<std::size_t>((k * 0x9E3779B97F4A7C15ull) >> shift_);
  }
  /// The slot holding key k, or the empty slot where it would go.
  std::size_t probe(std::uint64_t k) const {
    const std::size_t mask = slots_.size() - 1;
    std::size_t i = home(k);
    while (slots_[i].key != k && slots_[i].key != kEmpty) i = (i + 1) & mask;
    return i;
  }
  const Slot* find(std::uint64_t k) const {
    const Slot& s = slots_[probe(k)];
    return s.key == k ? &s : nullptr;
  }
  Slot& slot_for_insert(std::uint64_t k) {
    Slot& s = slots_[probe(k)];
    if (s.key == kEmpty) s.key = k, ++used_;
    return s;
  }
  void grow() {
    std::vector<Slot> old(slots_.size() * 2);
    old.swap(slots_);
    --shift_;
    const std::size_t mask = slots_.size() - 1;
    for (const Slot& s : old) {
      if (s.key == kEmpty) continue;
      std::size_t i = home(s.key);
      while (slots_[i].key != kEmpty) i = (i + 1) & mask;
      slots_[i] = s;
    }
  }
  std::array<std::int64_t, 3> cell_of(const Vec3& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x() / h_)),
            static_cast<std::int64_t>(std::floor(p.y() / h_)),
            static_cast<std::int64_t>(std::floor(p.z() / h_))};
  }
  static std::uint64_t key(const std::array<std::int64_t, 3>& c) {
    // 21 bits per axis (cells beyond ±2^20 wrap, which only costs speed).
    const std::uint64_t m = (1u << 21) - 1;
    return (static_cast<std::uint64_t>(c[0]) & m) | ((static_cast<std::uint64_t>(c[1]) & m) << 21) |
           ((static_cast<std::uint64_t>(c[2]) & m) << 42);
  }
  double h_;
  std::vector<Slot> slots_;
  std::vector<Entry> entries_;
  std::size_t used_ = 0;  ///< occupied slots
  int shift_ = 64 - 6;    ///< 64 - log2(slots_.size())
};

/// Uniform grid of cubic cells over a fixed set of points, built once: the
/// points sorted by cell (counting sort, stable in the point index) and one
/// offset per cell of the bounding box, cells numbered with z fastest so that
/// a query reads one contiguous run of points per (x, y) column of its box.
/// The cell side is the requested size, doubled until the grid has at most
/// kMaxCellsPerPoint cells per point (plus 4096), so memory stays O(n).
/// Queries report exactly the points a linear scan with the same distance test
/// reports (tests/geometry/point_grid_test.cpp).
class FlatPointGrid {
 public:
  /// Bound on the number of cells per point (see the class comment).
  static constexpr double kMaxCellsPerPoint = 8.0;

  /// Grid over points[i], with id i, for every point with finite coordinates
  /// (the others are left out). Pre: cell_size > 0 (Å).
  FlatPointGrid(const std::vector<Vec3>& points, double cell_size) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    std::size_t n = 0;
    for (const Vec3& p : points)
      if (p.allFinite()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p), ++n;
    if (n == 0) {
      offsets_.assign(2, 0);
      return;
    }
    lo_ = lo;
    h_ = cell_size;
    const double max_cells = kMaxCellsPerPoint * double(n) + 4096.0;
    for (;;) {
      double total = 1.0;
      for (int k = 0; k < 3; ++k) total *= std::floor((hi[k] - lo[k]) / h_) + 1.0;
      if (total <= max_cells) break;
      h_ *= 2.0;
    }
    inv_ = 1.0 / h_;
    for (int k = 0; k < 3; ++k) dims_[k] = std::int64_t(std::floor((hi[k] - lo[k]) / h_)) + 1;
    std::vector<std::uint32_t> cell_of_point(points.size());
    offsets_.assign(std::size_t(dims_[0] * dims_[1] * dims_[2]) + 1, 0);
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!points[i].allFinite()) continue;
      const std::int64_t x = cell(points[i].x(), 0), y = cell(points[i].y(), 1), z = cell(points[i].z(), 2);
      cell_of_point[i] = std::uint32_t((x * dims_[1] + y) * dims_[2] + z);
      ++offsets_[cell_of_point[i] + 1];
    }
    for (std::size_t c = 1; c < offsets_.size(); ++c) offsets_[c] += offsets_[c - 1];
    entries_.resize(n);
    std::vector<std::uint32_t> fill(offsets_.begin(), offsets_.end() - 1);
    for (std::size_t i = 0; i < points.size(); ++i)
      if (points[i].allFinite()) entries_[fill[cell_of_point[i]]++] = {points[i], Index(i)};
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
    for (std::int64_t x = a[0]; x <= b[0]; ++x)
      for (std::int64_t y = a[1]; y <= b[1]; ++y) {
        const std::int64_t column = (x * dims_[1] + y) * dims_[2];
        const std::uint32_t end = offsets_[std::size_t(column + b[2]) + 1];
        for (std::uint32_t e = offsets_[std::size_t(column + a[2])]; e < end; ++e)
          if ((entries_[e].p - q).squaredNorm() <= r2 && pred(entries_[e].id, entries_[e].p)) return true;
      }
    return false;
  }

  /// Side of the cells actually used (Å): the requested size or a power-of-two multiple.
  double cell_size() const { return h_; }
  /// Number of cells of the grid (its bounding box, empty cells included).
  std::size_t num_cells() const { return offsets_.size() - 1; }

 private:
  struct Entry {
    Vec3 p;
    Index id;
  };
  /// Cell coordinate along axis k, clamped to the grid: monotone in x.
  std::int64_t cell(double x, int k) const {
    const double t = std::floor((x - lo_[k]) * inv_);
    return std::int64_t(std::clamp(t, 0.0, double(dims_[k] - 1)));
  }
  Vec3 lo_ = Vec3::Zero();
  double h_ = 1.0, inv_ = 1.0;
  std::int64_t dims_[3] = {1, 1, 1};
  std::vector<std::uint32_t> offsets_;  ///< points of cell c: entries_[offsets_[c] .. offsets_[c + 1])
  std::vector<Entry> entries_;
};

}  // namespace skinmesh::geometry
