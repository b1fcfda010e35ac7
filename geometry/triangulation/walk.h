// geometry/triangulation/walk.h: point location in a tetrahedral mesh by a
// remembering stochastic visibility walk, shared by the regular and the
// Delaunay triangulation (both keep cells with vertices v and neighbours n).
// Notes: papers/geometry/triangulation/regular_triangulation.md
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "geometry/kernel/predicates.h"

namespace skinmesh::geometry::walk {

/// Local vertex indices of the face opposite local vertex i, ordered so that
/// vertex i is on the positive side of the face (orient3d).
inline constexpr std::array<std::array<int, 3>, 4> kFaceVertices = {{{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}}};

/// xorshift64* (Vigna 2016): a small, fully specified generator for the
/// walk's face order, so that every walk is reproducible.
inline std::uint64_t next_random(std::uint64_t& state) {
  state ^= state >> 12;
  state ^= state << 25;
  state ^= state >> 27;
  return state * 0x2545F4914F6CDD1DULL;
}

/// The live tetrahedron of `cells` whose closed hull contains p, by a walk
/// from `start`: leave the current tetrahedron through a face that separates
/// it from p (exact orient3d), testing the faces in a random cyclic order and
/// never the face just crossed. kInvalidIndex if the walk would leave the
/// mesh (p outside its hull). A walk longer than 1000 + 4 · cells steps is
/// taken as a (theoretically possible, never observed) cycle: scan() decides.
/// `points[i].z` is the position of vertex i; `steps` and `fallbacks`, when
/// given, count the steps and the scans.
template <class Cell, class Points, class Scan>
Index locate(const std::vector<Cell>& cells, const Points& points, const Vec3& p, Index start, std::uint64_t& rng,
             std::uint64_t* steps, std::uint64_t* fallbacks, Scan&& scan) {
  Index t = start, previous = kInvalidIndex;
  const std::uint64_t limit = 1000 + 4 * std::uint64_t(cells.size());
  for (std::uint64_t step = 0;; ++step) {
    if (step > limit) {
      if (fallbacks) ++*fallbacks;
      return scan();
    }
    if (steps) ++*steps;
    const int first = static_cast<int>(next_random(rng) >> 62);
    const std::array<Index, 4>& tv = cells[t].v;
    bool moved = false;
    for (int k = 0; k < 4; ++k) {
      const int i = (first + k) & 3;
      const Index u = cells[t].n[i];
      if (u == previous && u != kInvalidIndex) continue;
      const auto& f = kFaceVertices[i];
      if (orient3d(points[tv[f[0]]].z, points[tv[f[1]]].z, points[tv[f[2]]].z, p) == Sign::Negative) {
        if (u == kInvalidIndex) return kInvalidIndex;  // outside the bounding tetrahedron
        previous = t;
        t = u;
        moved = true;
        break;
      }
    }
    if (!moved) return t;
  }
}

}  // namespace skinmesh::geometry::walk
