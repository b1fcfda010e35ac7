// geometry/check/mesh_checks_intersections.cpp: the exact self-intersection test of
// check_mesh() — a broad phase over the triangles' exact bounding boxes (a grid
// of (x, y) columns, a z-sweep per column), the simple-fan test that settles
// pairs sharing a vertex or an edge from the mesh's connectivity, then the
// exact mesh_triangles_intersect() of geometry/kernel/triangle_intersection.h on every
// other candidate pair. Declared in mesh_checks_internal.h.
#include <Eigen/Geometry>  // cross()
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "core/parallel.h"
#include "geometry/check/mesh_checks_internal.h"
#include "geometry/kernel/predicates.h"
#include "geometry/kernel/triangle_intersection.h"

namespace skinmesh::geometry::mesh_checks_detail {

namespace {

/// One box of the broad phase with its payload `tri` (any struct with an Index
/// `id`), as make() gives it: exact bounds.
template <class Tri>
struct BoxItem {
  double lo[3], hi[3];
  Tri tri;
};

/// The stored form of a box: its bounds rounded outwards to single precision
/// (the stored box contains the exact one), `first` = its first column (x, y),
/// set by for_each_box_pair(). 48 bytes with a 16-byte payload where the
/// exact form took 72: the array of these was the largest of the check.
template <class Tri>
struct FloatBoxItem {
  float lo[3], hi[3];
  Tri tri;
  std::int32_t first[2];
};

/// The largest float <= x (-inf below the float range); NaN stays NaN.
/// Branch-free in the common case (a rounding direction is a coin toss, and
/// this runs three times per bound): the float nearest x, stepped one unit in
/// the last place down if it lies above x, by its bits (a float's bits order
/// its magnitude; stepping down is -1 for a positive float, +1 for a negative
/// one, and from ±0 lands on the negative denormal).
inline float float_down(double x) {
  constexpr double kMax = double(std::numeric_limits<float>::max());
  if (!(std::abs(x) <= kMax)) {  // beyond the float range, or NaN
    if (std::isnan(x)) return std::numeric_limits<float>::quiet_NaN();
    return x > 0 ? std::numeric_limits<float>::max() : -std::numeric_limits<float>::infinity();
  }
  const float f = static_cast<float>(x);
  const std::uint32_t u = std::bit_cast<std::uint32_t>(f);
  const std::uint32_t above = double(f) > x ? 1u : 0u, negative = u >> 31;
  return std::bit_cast<float>(u - above + 2u * (above & negative));
}
/// The smallest float >= x (+inf above the float range); NaN stays NaN.
/// As float_down(), mirrored.
inline float float_up(double x) {
  constexpr double kMax = double(std::numeric_limits<float>::max());
  if (!(std::abs(x) <= kMax)) {
    if (std::isnan(x)) return std::numeric_limits<float>::quiet_NaN();
    return x > 0 ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::max();
  }
  const float f = static_cast<float>(x);
  const std::uint32_t u = std::bit_cast<std::uint32_t>(f);
  const std::uint32_t below = double(f) < x ? 1u : 0u, negative = u >> 31;
  return std::bit_cast<float>(u + below - 2u * (below & negative));
}

template <class Tri>
FloatBoxItem<Tri> rounded_out(const BoxItem<Tri>& b) {
  FloatBoxItem<Tri> f;
  f.first[0] = f.first[1] = 0;
  for (int k = 0; k < 3; ++k) {
    f.lo[k] = float_down(b.lo[k]);
    f.hi[k] = float_up(b.hi[k]);
  }
  f.tri = b.tri;
  return f;
}

/// Column entries per block of the broad phase's sweep: enough that a block's
/// sort and sweep outweigh handing it to a thread. [chosen]
constexpr std::size_t kEntriesPerBlock = std::size_t{1} << 15;
/// Boxes stored at a time by the broad phase (a band of strips, below): 12
/// MB of them, so that the check's peak follows this, not the mesh's size.
/// [chosen]
constexpr std::size_t kBoxesPerBand = std::size_t{1} << 17;

// Broad phase over n boxes, make(i) giving box i and its payload (BoxItem;
// called at least five times per box, and again for a box stored in two
// bands, so that nothing is kept for all boxes but a 4-byte index): a grid of square columns
// (x, y) of side w about the mean extent of the boxes; each box is entered in
// every column its (x, y) range meets. The grid is swept in bands of
// consecutive strips (x indices of columns) holding about boxes_per_band boxes;
// a band stores its boxes (those whose (x, y) range meets it), rounded
// outwards to single precision (FloatBoxItem), in the order of the strip of
// their first column (a counting sort, for locality); each of its columns
// lists its boxes (4-byte indices) sorted by lower z and is swept along z; a
// pair is tested only in the first column both ranges share (the componentwise
// maximum of their first columns), so exactly once.
// Calls test(block, p, q, maybe) with the payloads of candidate pairs (in
// either order), maybe = true exactly once for every pair whose rounded boxes
// overlap (closed boxes: touching counts), false for the others. The rounded
// boxes contain the exact ones, so every pair of overlapping exact boxes is
// among the `maybe` pairs; the caller decides exactly which of those overlap.
// The columns of a band are sorted and swept in blocks of consecutive columns,
// on up to `threads` threads: before each band blocks(k) is called with the
// number k of blocks so far (it only grows), and test receives the block of the
// pair, so that a caller can keep one tally per block and merge them in block
// order. The bands and blocks depend on the boxes only (about boxes_per_band
// boxes and entries_per_block column entries each), never on the thread count.
template <class Tri, class MakeItem, class Blocks, class PairTest>
void for_each_box_pair(std::size_t n, MakeItem&& make, int threads, Blocks&& blocks, PairTest&& test,
                       std::size_t entries_per_block = kEntriesPerBlock, std::size_t boxes_per_band = kBoxesPerBand) {
  if (n < 2) {
    blocks(std::size_t{0});
    return;
  }
  // The boxes are visited in fixed chunks of consecutive indices, on the
  // threads; each chunk keeps its own partial results, joined in chunk order.
  constexpr std::size_t kBoxesPerChunk = std::size_t{1} << 16;  // [chosen]
  const std::size_t num_chunks = (n + kBoxesPerChunk - 1) / kBoxesPerChunk;
  auto chunk_range = [&](std::size_t c) {
    return std::pair<std::size_t, std::size_t>(c * kBoxesPerChunk, std::min(n, (c + 1) * kBoxesPerChunk));
  };
  Vec3 gmin = Vec3::Constant(std::numeric_limits<double>::infinity()), gmax = -gmin;
  double mean_extent = 0.0;
  // The grid's extent from the exact boxes (the rounded ones may stick out by
  // a unit in the last place: col() clamps them to the grid).
  {
    struct Extent {
      Vec3 lo, hi;
      double sum;
    };
    std::vector<Extent> extent(num_chunks, Extent{gmin, gmax, 0.0});
    parallel_for(num_chunks, threads, 1, [&](std::size_t c) {
      Extent& e = extent[c];
      for (auto [i, end] = chunk_range(c); i < end; ++i) {
        const BoxItem<Tri> b = make(i);
        for (int k = 0; k < 3; ++k) {
          e.lo[k] = std::min(e.lo[k], b.lo[k]);
          e.hi[k] = std::max(e.hi[k], b.hi[k]);
        }
        e.sum += std::max(b.hi[0] - b.lo[0], b.hi[1] - b.lo[1]);
      }
    });
    for (const Extent& e : extent) {
      gmin = gmin.cwiseMin(e.lo);
      gmax = gmax.cwiseMax(e.hi);
      mean_extent += e.sum;
    }
  }
  mean_extent /= double(n);
  const double span = std::max(gmax[0] - gmin[0], gmax[1] - gmin[1]);
  // Column side: kColumnPerExtent times the mean (x, y) extent, coarsened until
  // there are at most 4 columns and 16 (column, box) entries per box. A
  // non-finite span (coordinates near the double range) gives one column.
  // The constants only trade speed (measured on crambin at probe 0), never
  // correctness.
  constexpr double kColumnPerExtent = 1.5;
  constexpr double kMaxColumnsPerBox = 4.0;
  constexpr double kMaxEntriesPerBox = 16.0;
  const bool finite_grid = std::isfinite(span) && std::isfinite(mean_extent);
  double w = mean_extent > 0.0 ? kColumnPerExtent * mean_extent : (span > 0.0 ? span : 1.0);
  std::int64_t dims[2] = {1, 1};
  double inv = 0.0;
  // Column index along axis k (0: x, 1: y): monotone in the coordinate, so
  // boxes overlapping in (x, y) share a column.
  // Without a finite grid (inv = 0) every box is in column 0: (x - gmin) * inv
  // would be inf * 0 = NaN for a bound rounded out to infinity.
  auto col = [&](double x, int k) {
    const double t = std::floor((x - gmin[k]) * inv);
    return t >= 0.0 ? std::int64_t(std::min(t, double(dims[k] - 1))) : std::int64_t{0};
  };
  for (;;) {
    inv = finite_grid ? 1.0 / w : 0.0;
    const double dx = finite_grid ? std::floor((gmax[0] - gmin[0]) * inv) + 1.0 : 1.0;
    const double dy = finite_grid ? std::floor((gmax[1] - gmin[1]) * inv) + 1.0 : 1.0;
    if (dx * dy > kMaxColumnsPerBox * double(n) + 4096.0) {
      w *= 2.0;
      continue;
    }
    dims[0] = std::int64_t(dx);
    dims[1] = std::int64_t(dy);
    std::vector<double> chunk_entries(num_chunks, 0.0);  // whole numbers: the sum is exact
    parallel_for(num_chunks, threads, 1, [&](std::size_t c) {
      for (auto [i, end] = chunk_range(c); i < end; ++i) {
        const FloatBoxItem<Tri> b = rounded_out(make(i));
        chunk_entries[c] +=
            double(col(b.hi[0], 0) - col(b.lo[0], 0) + 1) * double(col(b.hi[1], 1) - col(b.lo[1], 1) + 1);
      }
    });
    double entries = 0.0;
    for (double e : chunk_entries) entries += e;
    if (entries <= kMaxEntriesPerBox * double(n) + 1024.0) break;
    w *= 2.0;
  }
  // The boxes' indices sorted by their first strip (the x index of their
  // first column), for locality: a strip's boxes are swept together. A
  // counting sort, stable, on the threads: each chunk counts its boxes per
  // strip, and writes them from its own offsets (the strips in order, within a
  // strip the chunks in order). The strip's sort is as local as the column's
  // for the sweep and needs counts per strip, not per column, in every chunk;
  // chunks are merged in pairs while those counts would outnumber the boxes.
  // The same pass finds the widest box in strips.
  const auto num_strips = std::size_t(dims[0]);
  std::size_t per_chunk = 1;  // chunks of the sort = runs of per_chunk chunks
  while (per_chunk < num_chunks && ((num_chunks + per_chunk - 1) / per_chunk) * num_strips > 2 * n + 65536)
    per_chunk *= 2;
  const std::size_t sort_chunks = (num_chunks + per_chunk - 1) / per_chunk;
  auto sort_range = [&](std::size_t c) {
    return std::pair<std::size_t, std::size_t>(c * per_chunk * kBoxesPerChunk,
                                               std::min(n, (c + 1) * per_chunk * kBoxesPerChunk));
  };
  // Every pass below reads the strips of the rounded box (the one stored),
  // which may differ from the exact box's by a unit in the last place.
  std::vector<std::uint32_t> offset(sort_chunks * num_strips, 0);  // [chunk][strip]
  std::vector<std::int64_t> chunk_reach(sort_chunks, 0);
  parallel_for(sort_chunks, threads, 1, [&](std::size_t c) {
    for (auto [i, end] = sort_range(c); i < end; ++i) {
      const FloatBoxItem<Tri> b = rounded_out(make(i));
      const std::int64_t x0 = col(b.lo[0], 0), x1 = col(b.hi[0], 0);
      ++offset[c * num_strips + std::size_t(x0)];
      chunk_reach[c] = std::max(chunk_reach[c], x1 - x0);
    }
  });
  std::size_t reach = 0;  // the most strips a box reaches beyond its first
  for (const std::int64_t w_strips : chunk_reach) reach = std::max(reach, std::size_t(w_strips));
  std::vector<std::uint32_t> strip_begin(num_strips + 1);  // the first position of each strip in `order`
  {
    std::uint32_t at = 0;
    for (std::size_t x = 0; x < num_strips; ++x) {
      strip_begin[x] = at;
      for (std::size_t c = 0; c < sort_chunks; ++c) {
        const std::uint32_t count = offset[c * num_strips + x];
        offset[c * num_strips + x] = at;
        at += count;
      }
    }
    strip_begin[num_strips] = at;
  }
  std::vector<std::uint32_t> order(n);
  parallel_for(sort_chunks, threads, 1, [&](std::size_t c) {
    for (auto [i, end] = sort_range(c); i < end; ++i)
      order[offset[c * num_strips + std::size_t(col(rounded_out(make(i)).lo[0], 0))]++] = std::uint32_t(i);
  });
  // offset[c][x] is now the end of chunk c's run of strip x, which is where
  // chunk c + 1's run begins: chunk c's run of strip x is
  // [run_begin(c, x), offset[c][x]).
  auto run_begin = [&](std::size_t c, std::size_t x) {
    return c == 0 ? strip_begin[x] : offset[(c - 1) * num_strips + x];
  };
  // Bands: runs of consecutive strips swept one after the other, each with
  // the stored boxes of its own strips and of the `reach` strips before it that
  // reach into it, so that the stored boxes and the columns' lists (the
  // largest arrays of the check) hold about boxes_per_band boxes at a time,
  // not all of them. A band is at least `reach` strips wide, so that boxes
  // stored twice are at most about as many as the band's own. A pair is
  // tested in its first shared column, which lies in exactly one band, where
  // both boxes are stored.
  auto halo = [&](std::size_t s0) { return s0 > reach ? s0 - reach : std::size_t{0}; };
  std::vector<std::pair<std::size_t, std::size_t>> bands;  // [first strip, end strip)
  std::size_t largest = 0;
  for (std::size_t s0 = 0; s0 < num_strips;) {
    const std::size_t from = strip_begin[halo(s0)];
    std::size_t s1 = s0 + 1;
    while (s1 < num_strips && (s1 - s0 < reach || strip_begin[s1 + 1] - from <= boxes_per_band)) ++s1;
    bands.emplace_back(s0, s1);
    largest = std::max<std::size_t>(largest, strip_begin[s1] - from);
    s0 = s1;
  }
  // Not value-initialised: every slot used is written below (a first pass of
  // zeros over the largest array of the check would cost a tenth of it).
  std::unique_ptr<FloatBoxItem<Tri>[]> item(new FloatBoxItem<Tri>[largest]);
  std::vector<std::uint32_t> start, entry;
  std::size_t blocks_before = 0;
  for (const auto& [s0, s1] : bands) {
    // The band's boxes, in the order of `order`; those of earlier strips that
    // end before the band are marked (first[0] = -1) and squeezed out. Made
    // chunk by chunk of the sort (each chunk's boxes are consecutive indices,
    // so make() reads the mesh where the chunk lies; in the order of `order`
    // it jumped across the whole mesh for every box).
    const std::size_t from = strip_begin[halo(s0)], to = strip_begin[s1];
    const std::size_t count = to - from;
    parallel_for(sort_chunks, threads, 1, [&](std::size_t c) {
      for (std::size_t x = halo(s0); x < s1; ++x)
        for (std::size_t k = run_begin(c, x), end = offset[c * num_strips + x]; k < end; ++k) {
          FloatBoxItem<Tri> b = rounded_out(make(order[k]));
          b.first[0] = std::int32_t(col(b.lo[0], 0));
          b.first[1] = std::int32_t(col(b.lo[1], 1));
          if (std::size_t(col(b.hi[0], 0)) < s0) b.first[0] = -1;
          item[k - from] = b;
        }
    });
    std::size_t m = 0;
    for (std::size_t k = 0; k < count; ++k)
      if (item[k].first[0] >= 0) item[m++] = item[k];
    // Entries per column of the band (CSR of the stored boxes), each column
    // then sorted by lower z; local column (x - s0) * dims[1] + y.
    const std::size_t num_columns = (s1 - s0) * std::size_t(dims[1]);
    auto x_range = [&](const FloatBoxItem<Tri>& b) {
      return std::pair<std::int64_t, std::int64_t>(std::max<std::int64_t>(b.first[0], std::int64_t(s0)),
                                                   std::min<std::int64_t>(col(b.hi[0], 0), std::int64_t(s1) - 1));
    };
    start.assign(num_columns + 1, 0);
    for (std::size_t i = 0; i < m; ++i) {
      const FloatBoxItem<Tri>& b = item[i];
      const auto [x0, x1] = x_range(b);
      for (std::int64_t x = x0; x <= x1; ++x)
        for (std::int64_t y = b.first[1], y1 = col(b.hi[1], 1); y <= y1; ++y)
          ++start[std::size_t((x - std::int64_t(s0)) * dims[1] + y) + 1];
    }
    for (std::size_t c = 0; c < num_columns; ++c) start[c + 1] += start[c];
    entry.resize(start[num_columns]);
    for (std::size_t i = 0; i < m; ++i) {
      const FloatBoxItem<Tri>& b = item[i];
      const auto [x0, x1] = x_range(b);
      for (std::int64_t x = x0; x <= x1; ++x)
        for (std::int64_t y = b.first[1], y1 = col(b.hi[1], 1); y <= y1; ++y)
          entry[start[std::size_t((x - std::int64_t(s0)) * dims[1] + y)]++] = std::uint32_t(i);
    }
    // start[c] now holds the end of column c (and its start is start[c - 1]).
    // Blocks: runs of consecutive columns holding about entries_per_block
    // entries (a column is never split), numbered on from the last band's.
    std::vector<std::size_t> block_begin{0};  // first column of each block, then num_columns
    for (std::size_t c = 0, since = 0; c < num_columns; ++c) {
      since += start[c] - (c ? start[c - 1] : 0);
      if (since >= entries_per_block && c + 1 < num_columns) {
        block_begin.push_back(c + 1);
        since = 0;
      }
    }
    block_begin.push_back(num_columns);
    const std::size_t num_blocks = block_begin.size() - 1;
    blocks(blocks_before + num_blocks);
    auto lower_z = [&](std::uint32_t a, std::uint32_t b) { return item[a].lo[2] < item[b].lo[2]; };
    parallel_for(num_blocks, threads, 1, [&](std::size_t blk) {
      for (std::size_t c = block_begin[blk]; c < block_begin[blk + 1]; ++c) {
        const std::uint32_t begin = c ? start[c - 1] : 0, end = start[c];
        // Each column sorted by lower z, then swept along z: each box is paired
        // only with those starting before it ends. Branch-free apart from the
        // end of each run: the outcome of the box test is passed on, not
        // branched on (it is hard to predict).
        if (end - begin > 1) std::sort(entry.begin() + begin, entry.begin() + end, lower_z);
        const auto cx = std::int32_t(s0 + c / std::size_t(dims[1])), cy = std::int32_t(c % std::size_t(dims[1]));
        for (std::uint32_t a = begin; a + 1 < end; ++a) {
          const FloatBoxItem<Tri>& p = item[entry[a]];
          for (std::uint32_t b = a + 1; b < end; ++b) {
            const FloatBoxItem<Tri>& q = item[entry[b]];
            if (q.lo[2] > p.hi[2]) break;  // this and all later ones start above p's top
            const bool overlap =
                (p.lo[0] <= q.hi[0]) & (q.lo[0] <= p.hi[0]) & (p.lo[1] <= q.hi[1]) & (q.lo[1] <= p.hi[1]);
            const bool first = (std::max(p.first[0], q.first[0]) == cx) & (std::max(p.first[1], q.first[1]) == cy);
            test(blocks_before + blk, p.tri, q.tri, overlap & first);
          }
        }
      }
    });
    blocks_before += num_blocks;
  }
}

// Fan Test ---------------------------------------------------------------------

// True if the good triangles around vertex s (`fan`, triangle ids) form one
// closed fan that a coordinate projection maps one-to-one onto a disc around s:
// every triangle (s, a, b) (its corners in cyclic order from s) contributes the
// link edge a -> b, the link edges form a single cycle through distinct
// vertices, and for some dropped coordinate every projected triangle has the
// same strict orient2d sign and the projected link winds exactly once around s.
// Then the projected triangles tile sectors of angle < pi that cover the plane
// once, so two of them meet only at s (non-consecutive) or along their common
// edge (consecutive), and the projection, injective on each triangle, carries
// this back to R^3: no two of these triangles meet beyond their shared vertex
// or edge. Exact (index comparisons, coordinate comparisons, orient2d).
bool simple_fan(const std::vector<Vec3>& P, const std::vector<std::array<Index, 3>>& T, Index s, const Index* fan,
                std::size_t k) {
  constexpr std::size_t kMaxFan = 32;
  if (k < 3 || k > kMaxFan) return false;
  Index a[kMaxFan], b[kMaxFan];
  for (std::size_t j = 0; j < k; ++j) {
    const auto& t = T[fan[j]];
    const int i = t[0] == s ? 0 : (t[1] == s ? 1 : 2);
    a[j] = t[(i + 1) % 3];
    b[j] = t[(i + 2) % 3];
  }
  // Link cycle in order: order[0] = 0, order[j + 1] = the triangle whose a is b[order[j]].
  std::size_t order[kMaxFan];
  order[0] = 0;
  for (std::size_t j = 0; j < k; ++j)
    for (std::size_t m = j + 1; m < k; ++m)
      if (a[j] == a[m] || b[j] == b[m]) return false;
  for (std::size_t j = 1; j <= k; ++j) {
    const Index want = b[order[j - 1]];
    std::size_t next = k;
    for (std::size_t m = 0; m < k; ++m)
      if (a[m] == want) next = m;
    if (next == k || (next == 0) != (j == k)) return false;  // open, or a shorter cycle
    if (j < k) order[j] = next;
  }
  // The coordinate to drop: the largest component of the summed normals first
  // (a choice only; every decision below is exact).
  const Vec3& ps = P[s];
  Vec3 normal = Vec3::Zero();
  for (std::size_t j = 0; j < k; ++j) normal += (P[a[j]] - ps).cross(P[b[j]] - ps);
  int axes[3] = {0, 1, 2};
  if (std::abs(normal[axes[1]]) > std::abs(normal[axes[0]])) std::swap(axes[0], axes[1]);
  if (std::abs(normal[axes[2]]) > std::abs(normal[axes[1]])) std::swap(axes[1], axes[2]);
  if (std::abs(normal[axes[1]]) > std::abs(normal[axes[0]])) std::swap(axes[0], axes[1]);
  for (const int axis : axes) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;  // the kept coordinates
    const double su = ps[u], sw = ps[w];
    // Half-plane of a link vertex around s: "upper" = angle in [0, pi).
    auto upper = [&](const Vec3& p) { return p[w] > sw || (p[w] == sw && p[u] > su); };
    int sign = 0, crossings = 0;
    bool consistent = true;
    for (std::size_t j = 0; j < k && consistent; ++j) {
      const Vec3& pa = P[a[order[j]]];
      const Vec3& pb = P[b[order[j]]];
      const int o = static_cast<int>(orient2d(su, sw, pa[u], pa[w], pb[u], pb[w]));
      if (o == 0 || (sign != 0 && o != sign)) consistent = false;
      sign = o;
      // Each step turns by less than pi in the direction `sign`; it passes the
      // angle 0 iff it goes from lower to upper (counter-clockwise) or from
      // upper to lower (clockwise).
      const bool ua = upper(pa), ub = upper(pb);
      if (sign > 0 ? (!ua && ub) : (ua && !ub)) ++crossings;
    }
    if (consistent && crossings == 1) return true;
  }
  return false;
}

}  // namespace

std::vector<std::uint8_t> simple_fan_vertices(const IndexedMesh& mesh, const TriangleClasses& classes,
                                              const VertexIncidence& incidence, int threads) {
  const std::size_t nv = mesh.positions.size();
  std::vector<std::uint8_t> ok(nv, 0);
  constexpr std::size_t kGrain = 4096;  // vertices per block handed to a thread [chosen]
  parallel_for(nv, threads, kGrain, [&](std::size_t v) {
    const Index b = incidence.start[v], e = incidence.start[v + 1];
    if (e - b > 64) return;
    Index fan[64];
    std::size_t k = 0;
    for (Index j = b; j < e; ++j)
      if (classes.kind[incidence.incident[j]] == TriangleKind::kGood) fan[k++] = incidence.incident[j];
    ok[v] = simple_fan(mesh.positions, mesh.triangles, Index(v), fan, k) ? 1 : 0;
  });
  return ok;
}

std::vector<std::array<Index, 2>> box_overlap_pairs(const std::vector<std::array<double, 6>>& boxes, int threads,
                                                    std::size_t entries_per_block, std::size_t boxes_per_band) {
  struct Id {
    Index id;
  };
  std::vector<std::vector<std::array<Index, 2>>> per_block;
  for_each_box_pair<Id>(
      boxes.size(),
      [&](std::size_t i) {
        const auto& b = boxes[i];
        return BoxItem<Id>{{b[0], b[1], b[2]}, {b[3], b[4], b[5]}, {Index(i)}};
      },
      threads, [&](std::size_t k) { per_block.resize(k); },
      [&](std::size_t block, const Id& i, const Id& j, bool maybe) {
        if (!maybe) return;
        const auto &a = boxes[i.id], &b = boxes[j.id];
        bool overlap = true;
        for (int k = 0; k < 3; ++k) overlap = overlap && a[k] <= b[k + 3] && b[k] <= a[k + 3];
        if (overlap) per_block[block].push_back({std::min(i.id, j.id), std::max(i.id, j.id)});
      },
      entries_per_block == 0 ? kEntriesPerBlock : entries_per_block,
      boxes_per_band == 0 ? kBoxesPerBand : boxes_per_band);
  std::vector<std::array<Index, 2>> pairs;
  for (const auto& found : per_block) pairs.insert(pairs.end(), found.begin(), found.end());
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

namespace {

/// True if the exact bounding boxes of triangles a and b (closed) overlap.
bool exact_boxes_overlap(const std::vector<Vec3>& P, const std::array<Index, 3>& a, const std::array<Index, 3>& b) {
  for (int k = 0; k < 3; ++k) {
    const double alo = std::min({P[a[0]][k], P[a[1]][k], P[a[2]][k]});
    const double ahi = std::max({P[a[0]][k], P[a[1]][k], P[a[2]][k]});
    const double blo = std::min({P[b[0]][k], P[b[1]][k], P[b[2]][k]});
    const double bhi = std::max({P[b[0]][k], P[b[1]][k], P[b[2]][k]});
    if (!(alo <= bhi && blo <= ahi)) return false;
  }
  return true;
}

}  // namespace

void find_self_intersections(const IndexedMesh& mesh, const TriangleClasses& classes,
                             const std::vector<std::uint8_t>& fan_ok, std::size_t max_examples, int threads,
                             MeshCheckReport& r) {
  const auto& P = mesh.positions;
  const auto& T = mesh.triangles;
  const std::size_t nt = T.size();
  r.self_intersections_checked = true;
  struct Tri {
    Index id;                // triangle
    std::array<Index, 3> v;  // its vertices
  };
  std::vector<Index> good;
  for (std::size_t t = 0; t < nt; ++t)
    if (classes.kind[t] == TriangleKind::kGood) good.push_back(Index(t));
  auto make = [&](std::size_t i) {
    const Index t = good[i];
    const Vec3 &a = P[T[t][0]], &b = P[T[t][1]], &c = P[T[t][2]];
    BoxItem<Tri> item;
    for (int k = 0; k < 3; ++k) {
      item.lo[k] = std::min({a[k], b[k], c[k]});
      item.hi[k] = std::max({a[k], b[k], c[k]});
    }
    item.tri = {t, T[t]};
    return item;
  };
  // Pairs that share a vertex (or an edge) of a simple fan cannot meet beyond
  // what they share (simple_fan()): counted as tested, decided without the
  // exact test. Every other pair goes through mesh_triangles_intersect().
  // One tally per block of columns; the found pairs are sorted below, so the
  // report does not depend on the thread count.
  struct Tally {
    std::vector<std::array<Index, 2>> found;
    std::size_t tested = 0;
  };
  std::vector<Tally> tally;
  auto blocks = [&](std::size_t k) { tally.resize(k); };
  for_each_box_pair<Tri>(
      good.size(), make, threads, blocks, [&](std::size_t block, const Tri& ti, const Tri& tj, bool maybe) {
        // Shared vertices, without branches: m[k] = whether ti.v[k] is a vertex of tj.
        bool m[3];
        for (int k = 0; k < 3; ++k) m[k] = (ti.v[k] == tj.v[0]) | (ti.v[k] == tj.v[1]) | (ti.v[k] == tj.v[2]);
        const int ns = int(m[0]) + int(m[1]) + int(m[2]);
        // The exact boxes overlap: certainly if the triangles share a vertex (it
        // lies in both), else decided from the positions (rare: such pairs go on
        // to the exact triangle test anyway).
        const bool hit = maybe & ((ns > 0) || (maybe && exact_boxes_overlap(P, ti.v, tj.v)));
        const bool counted = hit & (ns != 3);  // a duplicate is counted separately
        tally[block].tested += counted;
        // One or two shared vertices, one of them a simple fan: settled.
        const bool settled =
            (m[0] & (fan_ok[ti.v[0]] != 0)) | (m[1] & (fan_ok[ti.v[1]] != 0)) | (m[2] & (fan_ok[ti.v[2]] != 0));
        if (!(counted & !settled)) return;
        const Tri& lo = ti.id < tj.id ? ti : tj;
        const Tri& hi = ti.id < tj.id ? tj : ti;
        if (mesh_triangles_intersect(lo.v, hi.v, P)) tally[block].found.push_back({lo.id, hi.id});
      });
  std::vector<std::array<Index, 2>> found;
  std::size_t tested = 0;
  for (const Tally& t : tally) {
    found.insert(found.end(), t.found.begin(), t.found.end());
    tested += t.tested;
  }
  r.num_pairs_tested = tested;
  r.num_self_intersections = found.size();
  std::sort(found.begin(), found.end());
  if (found.size() > max_examples) found.resize(max_examples);
  r.self_intersection_examples = std::move(found);
}

}  // namespace skinmesh::geometry::mesh_checks_detail
