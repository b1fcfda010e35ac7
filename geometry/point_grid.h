// geometry/point_grid.h: a uniform hash grid over points for fixed-radius
// neighbour queries (critical-point lookup, front proximity, verifier).
#pragma once

#include <cmath>
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "geometry/types.h"

namespace skinmesh::geometry {

/// Uniform grid of cubic cells of side `cell_size` (Å) hashing point indices.
/// Points can be added after construction; removal is not supported (callers
/// filter stale entries). Queries visit the cells overlapping the query box.
class PointGrid {
 public:
  /// Pre: cell_size > 0.
  explicit PointGrid(double cell_size) : h_(cell_size) {}

  /// Adds point `id` at position p.
  void insert(Index id, const Vec3& p) { cells_[key(cell_of(p))].push_back({id, p}); }

  /// Calls fn(id, position) for every point within distance r (Å) of q.
  template <class Fn>
  void for_each_near(const Vec3& q, double r, Fn&& fn) const {
    const auto lo = cell_of(q - Vec3::Constant(r));
    const auto hi = cell_of(q + Vec3::Constant(r));
    const double r2 = r * r;
    for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
      for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k) {
          auto it = cells_.find(key({i, j, k}));
          if (it == cells_.end()) continue;
          for (const Entry& e : it->second)
            if ((e.p - q).squaredNorm() <= r2) fn(e.id, e.p);
        }
  }

  double cell_size() const { return h_; }

 private:
  struct Entry {
    Index id;
    Vec3 p;
  };
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
  std::unordered_map<std::uint64_t, std::vector<Entry>> cells_;
};

}  // namespace skinmesh::geometry
