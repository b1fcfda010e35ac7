// geometry/triangulation/cavity.h: the Bowyer–Watson insertion step shared by
// the regular triangulation (the skin's, §4.1 "Initialization") and the
// Delaunay triangulation (the dynamic-skin baseline's): the cavity of a new
// point grown from a tetrahedron in conflict, and the cone from the point
// over the cavity's boundary, its faces matched by their edges. The two
// triangulations differ only in their conflict test (the power test or the
// insphere test, both with symbolic perturbation) and their bookkeeping.
// Notes: papers/geometry/triangulation/regular_triangulation.md
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/types.h"

namespace skinmesh::geometry::cavity {

/// A facet of the cavity, and the new tetrahedron on it: the dead tetrahedron
/// with its local vertex i replaced by the new point.
struct Facet {
  std::array<Index, 4> vertices;  ///< the new tetrahedron
  Index outside;                  ///< the tetrahedron across the facet (kInvalidIndex on the hull)
  std::uint8_t i;                 ///< local index of the new point
  std::uint8_t outside_face;      ///< the face of `outside` that is this facet
};

/// A slot of the table that matches the faces of the cone's tetrahedra by
/// their edge on the cavity's boundary (open addressing; a slot whose stamp
/// is not the current generation's is empty).
struct EdgeSlot {
  std::uint64_t key = 0;
  std::uint32_t stamp = 0;
  Index tet = 0;
  int face = 0;
};

/// Grows the conflict region of new point v from `start` (a tetrahedron in
/// conflict) by depth-first search over neighbours: a neighbour joins when
/// in_conflict(u) is Sign::Positive. `mark` holds per tetrahedron `inside`,
/// `outside` or an older generation's value. Fills `conflict` with the
/// tetrahedra of the region in the order they were reached and `boundary`
/// with its facets (each with the new tetrahedron on it), and calls
/// visit(t) on each tetrahedron of the region when it is reached. `stack`
/// is scratch. Cells are any type with members v and n (std::array<Index, 4>
/// of vertices and of neighbours opposite them).
template <class Cell, class InConflict, class Visit>
void grow(const std::vector<Cell>& cells, std::vector<std::uint32_t>& mark, std::uint32_t inside, std::uint32_t outside,
          Index start, Index v, InConflict&& in_conflict, Visit&& visit, std::vector<Index>& stack,
          std::vector<Index>& conflict, std::vector<Facet>& boundary) {
  conflict.clear();
  boundary.clear();
  stack.clear();
  mark[start] = inside;
  stack.push_back(start);
  while (!stack.empty()) {
    const Index t = stack.back();
    stack.pop_back();
    conflict.push_back(t);
    visit(t);
    for (int i = 0; i < 4; ++i) {
      const Index u = cells[t].n[i];
      if (u != kInvalidIndex) {
        if (mark[u] == inside) continue;
        if (mark[u] != outside) {
          if (in_conflict(u) == Sign::Positive) {
            mark[u] = inside;
            stack.push_back(u);
            continue;
          }
          mark[u] = outside;
        }
      }
      // Facet i of t bounds the cavity: remember the new tetrahedron on it.
      Facet f;
      f.vertices = cells[t].v;
      f.vertices[i] = v;
      f.i = static_cast<std::uint8_t>(i);
      f.outside = u;
      f.outside_face = 0;
      if (u != kInvalidIndex) {
        while (cells[u].n[f.outside_face] != t) ++f.outside_face;
      }
      boundary.push_back(f);
    }
  }
}

/// Makes `table` large enough for the cone over `facets` cavity facets (at
/// most 3 · facets / 2 edges, at most a quarter full) and returns its mask
/// and hash shift. The sizes are powers of two of at least 64.
inline std::pair<std::uint64_t, int> prepare_edge_table(std::vector<EdgeSlot>& table, std::size_t facets) {
  std::size_t size = 64;
  while (size < 4 * facets) size *= 2;
  if (table.size() < size) table.assign(size, EdgeSlot{});
  return {table.size() - 1, 64 - std::countr_zero(table.size())};
}

/// Links the three faces through the new point of cone tetrahedron nt, built
/// on facet f, with the cone tetrahedra already built on the facets that
/// share an edge with f (the cavity's boundary is a triangulated sphere: each
/// edge is in exactly two facets, whose cone tetrahedra share the face of the
/// new point and that edge). `table` was prepared by prepare_edge_table for
/// this insertion (mask, shift); `stamp` is the insertion's generation.
template <class Cell>
void link_cone_faces(std::vector<Cell>& cells, std::vector<EdgeSlot>& table, std::pair<std::uint64_t, int> mask_shift,
                     std::uint32_t stamp, Index nt, const Facet& f) {
  // With the new point at local index i, the face opposite local j != i holds
  // the edge of the other two local indices kEdgeOf[i][j].
  static constexpr int kEdgeOf[4][4][2] = {
      {{-1, -1}, {2, 3}, {1, 3}, {1, 2}},
      {{2, 3}, {-1, -1}, {0, 3}, {0, 2}},
      {{1, 3}, {0, 3}, {-1, -1}, {0, 1}},
      {{1, 2}, {0, 2}, {0, 1}, {-1, -1}},
  };
  const auto [mask, shift] = mask_shift;
  for (int j = 0; j < 4; ++j) {
    if (j == f.i) continue;
    Index a = f.vertices[kEdgeOf[f.i][j][0]], b = f.vertices[kEdgeOf[f.i][j][1]];
    if (a > b) std::swap(a, b);
    const std::uint64_t key = (std::uint64_t(a) << 32) | b;
    std::uint64_t slot = (key * 0x9E3779B97F4A7C15ULL) >> shift;  // Fibonacci hashing
    while (true) {
      EdgeSlot& e = table[slot];
      if (e.stamp != stamp) {  // empty in this generation: the first of the two faces
        e = EdgeSlot{key, stamp, nt, j};
        break;
      }
      if (e.key == key) {  // the second face: link both
        cells[nt].n[j] = e.tet;
        cells[e.tet].n[e.face] = nt;
        break;
      }
      slot = (slot + 1) & mask;
    }
  }
}

}  // namespace skinmesh::geometry::cavity
