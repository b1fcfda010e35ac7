// geometry/mesh_checks_intersections.cpp: the exact self-intersection test of
// check_mesh() — a uniform-grid broad phase over the triangles' exact bounding
// boxes (radix-sorted cell keys, an x-sweep per cell), then the exact
// mesh_triangles_intersect() of geometry/triangle_intersection.h on each
// candidate pair. Declared in mesh_checks_internal.h.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "geometry/mesh_checks_internal.h"
#include "geometry/triangle_intersection.h"

namespace skinmesh::geometry::mesh_checks_detail {

namespace {

// Sort (key, value) pairs by key with an LSD radix sort on the low `bits` bits
// of the keys (stable; 11-bit digits). O(n bits / 11).
void radix_sort(std::vector<std::pair<std::uint64_t, Index>>& a, int bits) {
  constexpr int kDigit = 11;
  constexpr std::size_t kBuckets = std::size_t(1) << kDigit;
  std::vector<std::pair<std::uint64_t, Index>> tmp(a.size());
  std::vector<std::size_t> count(kBuckets);
  for (int shift = 0; shift < bits; shift += kDigit) {
    std::fill(count.begin(), count.end(), 0);
    for (const auto& x : a) ++count[(x.first >> shift) & (kBuckets - 1)];
    std::size_t sum = 0;
    for (std::size_t& c : count) {
      const std::size_t n = c;
      c = sum;
      sum += n;
    }
    for (const auto& x : a) tmp[count[(x.first >> shift) & (kBuckets - 1)]++] = x;
    a.swap(tmp);
  }
}

// Uniform-grid broad phase over triangle boxes. Calls test(i, j) once for every
// pair of listed triangles whose (closed, exact) bounding boxes overlap.
template <class PairTest>
void for_each_box_pair(const std::vector<Index>& tris, const std::vector<std::array<double, 6>>& box,
                       PairTest&& test) {
  const std::size_t n = tris.size();
  if (n < 2) return;
  Vec3 gmin = Vec3::Constant(std::numeric_limits<double>::infinity()), gmax = -gmin;
  double mean_extent = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& b = box[i];
    for (int k = 0; k < 3; ++k) {
      gmin[k] = std::min(gmin[k], b[k]);
      gmax[k] = std::max(gmax[k], b[3 + k]);
    }
    mean_extent += std::max({b[3] - b[0], b[4] - b[1], b[5] - b[2]});
  }
  mean_extent /= double(n);
  const double span = (gmax - gmin).maxCoeff();
  // Cell size: kCellPerExtent times the mean triangle extent (so a triangle
  // covers a few cells), coarsened until the grid has at most 2^21 cells per
  // axis and the (cell, triangle) entries stay below kMaxEntriesPerTriangle per
  // triangle. Both constants only trade speed (measured on spheres of 1e6
  // triangles), never correctness.
  constexpr double kCellPerExtent = 2.0;
  constexpr double kMaxEntriesPerTriangle = 16.0;
  constexpr double kMaxCellsPerAxis = double(1 << 21);
  double cell = mean_extent > 0.0 ? kCellPerExtent * mean_extent : (span > 0.0 ? span : 1.0);
  std::array<std::uint64_t, 3> dims{};
  std::vector<std::array<Index, 6>> range(n);  // cell index ranges [lo, hi] per axis
  for (;;) {
    const double inv = 1.0 / cell;
    bool fits = true;
    for (int k = 0; k < 3; ++k) {
      const double d = std::floor((gmax[k] - gmin[k]) * inv) + 1.0;
      fits = fits && d <= kMaxCellsPerAxis;
      dims[k] = fits ? std::uint64_t(d) : 1;
    }
    if (!fits) {
      cell *= 2.0;
      continue;
    }
    double entries = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      double cells = 1.0;
      for (int k = 0; k < 3; ++k) {
        // Monotone in the coordinate, so overlapping boxes share a cell.
        auto c = [&](double x) {
          const double t = std::floor((x - gmin[k]) * inv);
          return Index(std::clamp(t, 0.0, double(dims[k] - 1)));
        };
        range[i][k] = c(box[i][k]);
        range[i][3 + k] = c(box[i][3 + k]);
        cells *= double(range[i][3 + k] - range[i][k] + 1);
      }
      entries += cells;
    }
    if (entries <= kMaxEntriesPerTriangle * double(n) + 1024.0) break;
    cell *= 2.0;
  }
  auto key = [&](std::uint64_t x, std::uint64_t y, std::uint64_t z) {
    return (z * dims[1] + y) * dims[0] + x;
  };
  const int key_bits = std::bit_width(dims[0] * dims[1] * dims[2] - 1);
  // Renumber the triangles in the order of the cell of their box's lower corner
  // (stable), so that the triangles of one cell lie close together in memory:
  // the sweeps below then read the boxes and ranges mostly from the cache.
  std::vector<std::pair<std::uint64_t, Index>> entries;
  entries.reserve(4 * n);
  for (std::size_t i = 0; i < n; ++i) entries.emplace_back(key(range[i][0], range[i][1], range[i][2]), Index(i));
  radix_sort(entries, key_bits);
  std::vector<Index> tri(n);                      // renumbered -> input triangle
  std::vector<std::array<double, 6>> sbox(n);     // renumbered boxes
  std::vector<std::array<Index, 6>> srange(n);    // renumbered cell ranges
  for (std::size_t k = 0; k < n; ++k) {
    const Index i = entries[k].second;
    tri[k] = tris[i];
    sbox[k] = box[i];
    srange[k] = range[i];
  }
  range = std::vector<std::array<Index, 6>>();
  entries.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const auto& r = srange[i];
    for (Index z = r[2]; z <= r[5]; ++z)
      for (Index y = r[1]; y <= r[4]; ++y)
        for (Index x = r[0]; x <= r[3]; ++x) entries.emplace_back(key(x, y, z), Index(i));
  }
  radix_sort(entries, key_bits);
  // In each cell, sweep along x: copy the cell's boxes into one contiguous
  // array, sort it by the boxes' lower x and pair each box only with those
  // starting before it ends.
  struct Item {
    double lo[3], hi[3];  // the box
    Index first[3];       // its lowest cell per axis
    Index id;             // renumbered triangle
  };
  std::vector<Item> items;
  for (std::size_t s = 0; s < entries.size();) {
    std::size_t e = s + 1;
    while (e < entries.size() && entries[e].first == entries[s].first) ++e;
    items.clear();
    for (std::size_t a = s; a < e; ++a) {
      const Index i = entries[a].second;
      const auto& b = sbox[i];
      const auto& r = srange[i];
      items.push_back({{b[0], b[1], b[2]}, {b[3], b[4], b[5]}, {r[0], r[1], r[2]}, i});
    }
    std::sort(items.begin(), items.end(), [](const Item& p, const Item& q) {
      return p.lo[0] < q.lo[0] || (p.lo[0] == q.lo[0] && p.id < q.id);
    });
    // The cell's coordinates: a pair is tested only in the first cell both
    // ranges share, the cell of the componentwise maximum of their lowest cells.
    const std::uint64_t cx = entries[s].first % dims[0], cy = entries[s].first / dims[0] % dims[1],
                        cz = entries[s].first / dims[0] / dims[1];
    for (std::size_t a = 0; a < items.size(); ++a) {
      const Item& p = items[a];
      for (std::size_t b = a + 1; b < items.size(); ++b) {
        const Item& q = items[b];
        if (q.lo[0] > p.hi[0]) break;  // this and all later ones start after p ends
        // Non-short-circuit: these outcomes are hard to predict, the loads are cheap.
        const bool overlap = (p.lo[1] <= q.hi[1]) & (q.lo[1] <= p.hi[1]) & (p.lo[2] <= q.hi[2]) &
                             (q.lo[2] <= p.hi[2]);
        const bool first_cell = (std::max(p.first[0], q.first[0]) == cx) &
                                (std::max(p.first[1], q.first[1]) == cy) &
                                (std::max(p.first[2], q.first[2]) == cz);
        if (!(overlap & first_cell)) continue;
        test(std::min(tri[p.id], tri[q.id]), std::max(tri[p.id], tri[q.id]));
      }
    }
    s = e;
  }
}

}  // namespace

void find_self_intersections(const IndexedMesh& mesh, const TriangleClasses& classes,
                             std::size_t max_examples, MeshCheckReport& r) {
  const auto& P = mesh.positions;
  const auto& T = mesh.triangles;
  const std::size_t nt = T.size();
  r.self_intersections_checked = true;
  std::vector<Index> tris;
  std::vector<std::array<double, 6>> boxes;
  for (std::size_t t = 0; t < nt; ++t) {
    if (classes.kind[t] != TriangleKind::kGood) continue;
    std::array<double, 6> b;
    for (int k = 0; k < 3; ++k) {
      b[k] = std::min({P[T[t][0]][k], P[T[t][1]][k], P[T[t][2]][k]});
      b[3 + k] = std::max({P[T[t][0]][k], P[T[t][1]][k], P[T[t][2]][k]});
    }
    tris.push_back(Index(t));
    boxes.push_back(b);
  }
  std::vector<std::array<Index, 2>> found;
  for_each_box_pair(tris, boxes, [&](Index i, Index j) {
    const auto& ti = T[i];
    const auto& tj = T[j];
    int shared = 0;
    for (Index a : ti)
      for (Index b : tj) shared += a == b ? 1 : 0;
    if (shared == 3) return;  // a duplicate, counted separately
    ++r.num_pairs_tested;
    if (mesh_triangles_intersect(ti, tj, P)) {
      ++r.num_self_intersections;
      found.push_back({i, j});
    }
  });
  std::sort(found.begin(), found.end());
  if (found.size() > max_examples) found.resize(max_examples);
  r.self_intersection_examples = std::move(found);
}

}  // namespace skinmesh::geometry::mesh_checks_detail
