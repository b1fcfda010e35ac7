// skin/dual_complex.cpp: K0 filtration values, Euler characteristic, components
// and voids. papers/skin/skin_math.md §5.
#include "skin/dual_complex.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

#include "core/parallel.h"
#include "geometry/kernel/orthosphere_predicates.h"

namespace skinmesh::skin {

namespace {

/// Union–find with path halving.
struct DisjointSets {
  std::vector<Index> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  Index find(Index a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void unite(Index a, Index b) { parent[find(a)] = find(b); }
};

}  // namespace

SkinTopology dual_complex_topology(const MixedComplex& mc, int threads) {
  const auto& rt = mc.triangulation();
  const Index n = mc.num_cells();
  SkinTopology topo;
  // Membership in K0, tetrahedra first (they have no cofaces). Only the sign
  // of a filtration value matters, and the value of X is either w_X (X
  // unattached) or the minimum over its cofaces, so "value <= 0" propagates as
  // a boolean: attached X is in K0 iff some coface is. Both decisions are
  // exact predicates (papers/skin/dual_complex.md "Exact filtration signs").
  std::vector<char> in_k0(n, 0);
  // The cells of each dimension, in index order (one pass over the cells
  // instead of one per dimension), and each cell's dimension in a byte array:
  // the loops below read the dimension of every plane's neighbour, and a cell
  // record is ~100 bytes (a cache miss each; on maltoporin most of this
  // function's own time). The loops read the neighbour lists, not the planes,
  // which are made only where a walk needs them.
  std::array<std::vector<Index>, 4> by_dim;
  std::vector<std::uint8_t> dim_of(n);
  for (Index c = 0; c < n; ++c) {
    const CellSimplex& X = mc.simplex(c);
    dim_of[c] = static_cast<std::uint8_t>(X.dim);
    if (!X.bounding) by_dim[static_cast<std::size_t>(X.dim)].push_back(c);
  }
  // A cell reads only its cofaces' membership, decided in the pass of the
  // dimension above: each dimension's cells split into blocks on the threads,
  // and the ties and singular simplices are joined in block order (the lists
  // a single loop makes).
  constexpr std::size_t kBlock = 4096;  // [measured] cells per block: about a millisecond of predicates
  for (int dim = 3; dim >= 0; --dim) {
    const std::vector<Index>& cells = by_dim[static_cast<std::size_t>(dim)];
    const std::size_t blocks = (cells.size() + kBlock - 1) / kBlock;
    std::vector<int> ties(blocks, 0);
    std::vector<std::vector<std::array<Index, 4>>> singular(blocks);
    parallel_for(blocks, threads, 1, [&](std::size_t b) {
      for (std::size_t i = b * kBlock, end = std::min(cells.size(), i + kBlock); i < end; ++i) {
        const Index c = cells[i];
        const CellSimplex& X = mc.simplex(c);
        std::array<WeightedPoint, 4> pts;
        for (int j = 0; j <= dim; ++j) pts[j] = rt.point(X.vertices[j]);
        const std::span<const WeightedPoint> xs(pts.data(), dim + 1);
        bool attached = false, tie = false, coface_in = false;
        for (const Index nb : mc.neighbors(c)) {
          if (dim_of[nb] != dim + 1) continue;
          coface_in = coface_in || in_k0[nb];
          if (attached) continue;  // decided; a tie only counts for an unattached X
          const Sign s = geometry::orthosphere_power_sign(xs, rt.point(mc.extra_vertex(c, nb)));
          attached = s == Sign::Negative;
          tie = tie || s == Sign::Zero;
        }
        // A tie (some k orthogonal to the orthosphere, no strict attachment)
        // counts as unattached: z_X then lies on the boundary of nu_X and both
        // readings give the same value w_X (papers/skin/dual_complex.md).
        if (tie && !attached) ++ties[b];
        if (attached) {
          in_k0[c] = coface_in;
        } else {
          const Sign w = geometry::focus_weight_sign(xs);
          in_k0[c] = w != Sign::Positive;  // closed balls: w_X = 0 is in K0
          if (w == Sign::Zero) singular[b].push_back(X.vertices);
        }
      }
    });
    for (std::size_t b = 0; b < blocks; ++b) {
      topo.orthogonal_ties += ties[b];
      topo.singular_simplices.insert(topo.singular_simplices.end(), singular[b].begin(), singular[b].end());
    }
  }
  auto in_k0_fn = [&](Index c) { return in_k0[c] != 0; };

  for (Index c = 0; c < n; ++c)
    if (in_k0_fn(c)) ++topo.k0_simplices[mc.simplex(c).dim];
  topo.euler_k0 = topo.k0_simplices[0] - topo.k0_simplices[1] + topo.k0_simplices[2] - topo.k0_simplices[3];

  // betti0: K0 vertices joined by K0 edges.
  DisjointSets comp(n);
  for (Index c = 0; c < n; ++c) {
    if (mc.simplex(c).dim != 1 || !in_k0_fn(c)) continue;
    for (const Index nb : mc.neighbors(c))
      if (dim_of[nb] == 0) comp.unite(nb, c);
  }
  std::vector<char> seen(n, 0);
  for (Index c = 0; c < n; ++c) {
    if (mc.simplex(c).dim != 0 || !in_k0_fn(c)) continue;
    const Index r = comp.find(c);
    if (!seen[r]) seen[r] = 1, ++topo.betti0;
  }

  // betti2: components of the complement (tetrahedra not in K0 joined across
  // triangles not in K0), minus the unbounded one.
  DisjointSets outside(n);
  Index any_outer = kInvalidIndex;
  for (Index c = 0; c < n; ++c) {
    const CellSimplex& X = mc.simplex(c);
    if (X.dim == 3 && X.bounding) {
      if (any_outer == kInvalidIndex) any_outer = c;
      outside.unite(c, any_outer);
    }
    if (X.dim != 2 || in_k0_fn(c)) continue;
    Index first = kInvalidIndex;
    for (const Index nb : mc.neighbors(c)) {
      if (dim_of[nb] != 3) continue;
      if (first == kInvalidIndex)
        first = nb;
      else
        outside.unite(first, nb);
    }
  }
  std::fill(seen.begin(), seen.end(), 0);
  int complement = 0;
  for (Index c = 0; c < n; ++c) {
    if (mc.simplex(c).dim != 3 || in_k0_fn(c)) continue;
    const Index r = outside.find(c);
    if (!seen[r]) seen[r] = 1, ++complement;
  }
  topo.betti2 = complement - 1;
  return topo;
}

}  // namespace skinmesh::skin
