// skin/mixed_complex.cpp: construction of the mixed complex and point location.
// Cheng & Shi 2004 §2.1; papers/skin/skin_math.md §2.2 (foci), §2.3 (half-space
// form), §3.2.
#include "skin/mixed_complex.h"

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <new>
#include <string>
#include <thread>

#include "core/assert.h"
#include "core/errors.h"
#include "core/parallel.h"
#include "geometry/kernel/predicates.h"

namespace skinmesh::skin {

// Focus Computation

void focus_of(std::span<const WeightedPoint> pts, Vec3& z, double& w) {
  const std::size_t k = pts.size() - 1;  // dimension of the simplex
  const Vec3 z0 = pts[0].z;
  const double w0 = pts[0].w;
  if (k == 0) {
    z = z0;
    w = -w0;
    return;
  }
  if (k == 1) {
    // Edge: t = (d² + w0 - w1) / (2d) along u (papers/skin/skin_math.md §2.2,
    // special case).
    const Vec3 e = pts[1].z - z0;
    const double d2 = e.squaredNorm();
    const double t_over_d = (d2 + w0 - pts[1].w) / (2.0 * d2);
    const Vec3 off = t_over_d * e;
    z = z0 + off;
    w = off.squaredNorm() - w0;
    return;
  }
  // Triangle or tetrahedron: 2 E E^T beta = r, z = z0 + E^T beta.
  Vec3 off;
  if (k == 2) {
    // With n = e1 x e2, the offset d = (r1 (e2 x n) + r2 (n x e1)) / (2 |n|²)
    // satisfies 2 e_j·d = r_j and lies in lin X. |n|² is computed from the
    // cross product, not as |e1|²|e2|² - (e1·e2)², which cancels
    // catastrophically for a needle triangle (two nearly coincident centres).
    const Vec3 e1 = pts[1].z - z0, e2 = pts[2].z - z0;
    const double r1 = e1.squaredNorm() + w0 - pts[1].w;
    const double r2 = e2.squaredNorm() + w0 - pts[2].w;
    const Vec3 n = e1.cross(e2);
    off = (r1 * e2.cross(n) + r2 * n.cross(e1)) / (2.0 * n.squaredNorm());
  } else {
    Mat3 E;
    Vec3 r;
    for (int j = 1; j <= 3; ++j) {
      const Vec3 e = pts[j].z - z0;
      E.row(j - 1) = e.transpose();
      r(j - 1) = e.squaredNorm() + w0 - pts[j].w;
    }
    off = E.fullPivLu().solve(0.5 * r);
  }
  z = z0 + off;
  w = off.squaredNorm() - w0;
}

// MixedComplex Construction

namespace {

using RT = geometry::RegularTriangulation;

/// A tetrahedron's vertices in increasing order (the order of its mixed
/// cell's `vertices`), with the local index in rt.tet(t) of each.
struct SortedTet {
  std::array<Index, 4> v;
  std::array<int, 4> local;
};

SortedTet sorted_tet(const RT& rt, Index t) {
  SortedTet s{rt.tet(t), {0, 1, 2, 3}};
  // A sorting network of five compare-exchanges (the vertices are distinct).
  auto order = [&s](int i, int j) {
    if (s.v[j] < s.v[i]) std::swap(s.v[i], s.v[j]), std::swap(s.local[i], s.local[j]);
  };
  order(0, 1), order(2, 3), order(0, 2), order(1, 3), order(1, 2);
  return s;
}

/// Position of vertex w among the sorted vertices of tetrahedron u (w is one
/// of them).
int rank_in(const RT& rt, Index u, Index w) {
  int r = 0;
  for (Index x : rt.tet(u)) r += x < w ? 1 : 0;
  return r;
}

/// The six edges of a tetrahedron as pairs (p, q), p < q, of sorted vertex
/// positions; slot of the edge (p, q).
constexpr std::array<std::array<int, 2>, 6> kTetEdges{{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};
constexpr int edge_slot(int p, int q) { return p == 0 ? q - 1 : (p == 1 ? q + 1 : 5); }
/// The first facet (by the sorted position it leaves out) of a tetrahedron
/// that contains its edge (p, q): the smallest position other than p and q.
constexpr int first_facet(int p, int q) { return p != 0 ? 0 : (q == 1 ? 2 : 1); }
/// The sorted positions of facet s (the three positions other than s).
constexpr std::array<int, 3> facet_positions(int s) {
  return s == 0 ? std::array<int, 3>{1, 2, 3}
                : (s == 1 ? std::array<int, 3>{0, 2, 3}
                          : (s == 2 ? std::array<int, 3>{0, 1, 3} : std::array<int, 3>{0, 1, 2}));
}

/// Result of around_edge().
struct Ring {
  bool stopped = false;  ///< visit returned false
  bool open = false;     ///< the ring meets the boundary of the bounding tetrahedron
};

/// Calls visit(u) for every tetrahedron u other than t around the edge (a, b)
/// of tetrahedron t: one way round from t, and where that meets the boundary
/// of the bounding tetrahedron (an open ring), the other way from t. Stops
/// as soon as visit returns false.
template <class Visit>
Ring around_edge(const RT& rt, Index t, Index a, Index b, Visit&& visit) {
  Index c = kInvalidIndex, d = kInvalidIndex;
  for (Index w : rt.tet(t))
    if (w != a && w != b) (c == kInvalidIndex ? c : d) = w;
  // From tetrahedron {a, b, x, y} across its face {a, b, y} (opposite x) to
  // {a, b, y, z}, whose face {a, b, z} is crossed next.
  auto go = [&](Index x, Index y) -> int {  // 0 closed, 1 open, 2 stopped
    Index cur = t;
    for (Index step = 0;; ++step) {
      SKINMESH_ASSERT_MSG(step <= rt.num_tets(), "the tetrahedra around an edge do not close");
      const Index next = rt.neighbor(cur, rt.local_index(cur, x));
      if (next == kInvalidIndex) return 1;
      if (next == t) return 0;
      if (!visit(next)) return 2;
      Index z = kInvalidIndex;
      for (Index w : rt.tet(next))
        if (w != a && w != b && w != y) z = w;
      cur = next, x = y, y = z;
    }
  };
  Ring r;
  const int one_way = go(c, d);
  r.stopped = one_way == 2;
  if (one_way == 1) {
    r.open = true;
    r.stopped = go(d, c) == 2;
  }
  return r;
}

/// Unit normal of the plane shared by mu_X and mu_Y, Y = X ∪ {k}: the unit
/// vector of lin Y orthogonal to lin X, pointing from aff X towards z_k (the
/// direction of P_perp^X (z_k - z_X), papers/skin/skin_math.md §2.3), computed
/// from the input centres in coordinates relative to a vertex of X. For a
/// triangle X the side of z_k is the exact orient3d sign: Y is a non-flat
/// tetrahedron of the triangulation (SoS), so it is never zero, even when z_k
/// is within rounding of aff X.
Vec3 facet_coface_normal(const geometry::RegularTriangulation& rt, const CellSimplex& X, Index k) {
  const Vec3& za = rt.point(X.vertices[0]).z;
  const Vec3 v = rt.point(k).z - za;
  switch (X.dim) {
    case 0:
      return v.normalized();
    case 1: {
      // (e x v) x e = |e|² v - (e·v) e: the part of v orthogonal to the edge.
      const Vec3 e = rt.point(X.vertices[1]).z - za;
      return e.cross(v).cross(e).normalized();
    }
    default: {
      const Vec3& zb = rt.point(X.vertices[1]).z;
      const Vec3& zc = rt.point(X.vertices[2]).z;
      const Vec3 n = (zb - za).cross(zc - za).normalized();
      const Sign side = geometry::orient3d(za, zb, zc, rt.point(k).z);
      SKINMESH_ASSERT_MSG(side != Sign::Zero, "flat tetrahedron in the regular triangulation");
      return side == Sign::Positive ? n : Vec3(-n);
    }
  }
}

/// Outward unit normals of tetrahedron t of rt at its four facets (normal i
/// at the facet opposite local vertex i), from the input centres, each
/// oriented away from vertex i by the exact orient3d.
std::array<Vec3, 4> facet_normals(const geometry::RegularTriangulation& rt, Index t) {
  using RT = geometry::RegularTriangulation;
  const std::array<Index, 4>& tv = rt.tet(t);
  std::array<Vec3, 4> m;
  for (int i = 0; i < 4; ++i) {
    const std::array<int, 3>& f = RT::kFaceVertices[i];
    const Vec3 &a = rt.point(tv[f[0]]).z, &b = rt.point(tv[f[1]]).z, &c = rt.point(tv[f[2]]).z;
    const Vec3 n = (b - a).cross(c - a).normalized();
    const Sign side = geometry::orient3d(a, b, c, rt.point(tv[i]).z);
    m[i] = side == Sign::Positive ? Vec3(-n) : n;
  }
  return m;
}

}  // namespace

void MixedComplex::order_flat_foci(Index first_tet_cell) {
  const geometry::RegularTriangulation& rt = *rt_;
  constexpr double kParallel = 1e-12;  // 1 - |cos|: about 1.4e-6 rad
  // Candidates: 6 |vol| <= 1e-5 diam³ (every flat tetrahedron, as defined
  // below, passes; the exact normal test then decides).
  struct Flat {
    Index t;
    Vec3 n;                 // reference normal: the outward normal at facet 0
    std::array<Vec3, 4> m;  // outward facet normals
  };
  std::vector<Flat> flat;
  for (Index t = 0; t < rt.num_tets(); ++t) {
    const std::array<Index, 4>& tv = rt.tet(t);
    const Vec3& p0 = rt.point(tv[0]).z;
    const Vec3 e1 = rt.point(tv[1]).z - p0, e2 = rt.point(tv[2]).z - p0, e3 = rt.point(tv[3]).z - p0;
    const double d2 = std::max({e1.squaredNorm(), e2.squaredNorm(), e3.squaredNorm(), (e2 - e1).squaredNorm(),
                                (e3 - e1).squaredNorm(), (e3 - e2).squaredNorm()});
    const double vol6 = std::abs(e1.dot(e2.cross(e3)));
    constexpr double kFlatVolume = 1e-5;  // [measured] 6 vol / diameter³ of a tetrahedron worth the flatness test
    if (!(vol6 <= kFlatVolume * d2 * std::sqrt(d2))) continue;
    const std::array<Vec3, 4> m = facet_normals(rt, t);
    bool is_flat = true;
    for (int i = 1; i < 4 && is_flat; ++i) is_flat = 1.0 - std::abs(m[i].dot(m[0])) <= kParallel;
    if (is_flat) flat.push_back({t, m[0], m});
  }
  // For the facet i of T with outward normal m_i and the tetrahedron T_i across
  // it, the Voronoi edge dual to the facet runs from z_T to z_{T_i} along m_i:
  // m_i·(z_{T_i} - z_T) >= 0. Move z_T along n by the smallest delta that
  // satisfies the four (a slab, as every m_i is ±n); neighbours that are flat
  // themselves use their current focus, so a few passes settle chains of them.
  // The flat tetrahedra's foci, current while the passes run (the others are
  // never moved: their foci are computed where read).
  std::vector<MixedCell> current(flat.size());
  std::vector<bool> moved_any(flat.size(), false);
  auto flat_index = [&](Index t) {
    const auto it = std::lower_bound(flat.begin(), flat.end(), t, [](const Flat& f, Index u) { return f.t < u; });
    return it != flat.end() && it->t == t ? std::size_t(it - flat.begin()) : flat.size();
  };
  for (std::size_t i = 0; i < flat.size(); ++i) fill_cell(first_tet_cell + flat[i].t, current[i]);
  for (int pass = 0; pass < 4; ++pass) {
    bool moved = false;
    for (std::size_t fi = 0; fi < flat.size(); ++fi) {
      const Flat& F = flat[fi];
      MixedCell& T = current[fi];
      double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
      for (int i = 0; i < 4; ++i) {
        const Index nb = rt.neighbor(F.t, i);
        if (nb == kInvalidIndex) continue;
        const double c = F.m[i].dot(F.n);
        const std::size_t nf = flat_index(nb);
        const Vec3 nb_focus = nf < flat.size() ? current[nf].focus : cell_value(first_tet_cell + nb).focus;
        const double bound = F.m[i].dot(nb_focus - T.focus) / c;
        if (c > 0)
          hi = std::min(hi, bound);
        else
          lo = std::max(lo, bound);
      }
      const double delta = lo <= hi ? std::clamp(0.0, lo, hi) : 0.5 * (lo + hi);
      if (delta == 0.0 || !std::isfinite(delta)) continue;
      T.focus += delta * F.n;
      const WeightedPoint& p0 = rt.point(T.vertices[0]);
      T.focus_weight = (T.focus - p0.z).squaredNorm() - p0.w;
      moved = moved_any[fi] = true;
      ++num_reordered_foci_;
    }
    if (!moved) break;
  }
  for (std::size_t i = 0; i < flat.size(); ++i)
    if (moved_any[i]) moved_foci_.push_back({first_tet_cell + flat[i].t, current[i].focus, current[i].focus_weight});
}

MixedComplex::MixedComplex(const geometry::RegularTriangulation& rt, int threads) : rt_(&rt) {
  const Index np = rt.num_points();
  const Index nt = rt.num_tets();
  constexpr std::size_t kGrain = 4096;  // [measured] items per block of the loops below: a few hundred µs

  // Length scale of the input (papers/skin/skin_math.md §9).
  {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 hi = -lo;
    double rmax = 0;
    for (Index v = 0; v < rt.num_input_points(); ++v) {
      const WeightedPoint& p = rt.point(v);
      lo = lo.cwiseMin(p.z);
      hi = hi.cwiseMax(p.z);
      rmax = std::max(rmax, std::sqrt(std::max(p.w, 0.0)));
    }
    length_scale_ = std::max((hi - lo).norm() + 2 * rmax, 1.0);
  }

  // The cells are numbered as a scan of the triangulation meets the simplices:
  // the vertices in index order, the tetrahedra in index order, then for each
  // tetrahedron t in order and each of its facets (leaving out its sorted
  // vertices 0, 1, 2, 3 in turn) the facet if t meets it first, followed by
  // its edges (in the facet's order 01, 02, 12) that t meets first. Every
  // simplex is met first by the lowest-numbered tetrahedron that contains it,
  // so a tetrahedron can tell which of its facets and edges are its own from
  // its neighbours alone, and all of them can number their simplices at once
  // (papers/skin/mixed_complex.md, "Construction").
  vertex_cell_.assign(np, kInvalidIndex);
  Index nv = 0;
  for (Index v = 0; v < np; ++v)
    if (rt.is_vertex(v)) vertex_cell_[v] = nv++;

  // Per tetrahedron: bit s (0..3) if it owns the facet leaving out sorted
  // vertex s, bit 4 + e if it owns edge slot e; and per facet and edge slot,
  // the cell (once numbered). Before the numbering, an edge slot holds the
  // number of triangles around the edge (owned) or a lower tetrahedron around
  // it (not owned).
  std::vector<std::uint16_t> owns(nt);
  std::vector<Index> tet_tri(4 * std::size_t(nt)), tet_edge(6 * std::size_t(nt));
  parallel_for(nt, threads, kGrain, [&](std::size_t ti) {
    const Index t = static_cast<Index>(ti);
    const SortedTet st = sorted_tet(rt, t);
    std::uint16_t own = 0;
    std::array<Index, 4> below{};  // the tetrahedron across facet s if lower
    for (int s = 0; s < 4; ++s) {
      const Index nb = rt.neighbor(t, st.local[s]);
      below[s] = nb != kInvalidIndex && nb < t ? nb : kInvalidIndex;
      if (below[s] == kInvalidIndex) own |= std::uint16_t(1u << s);
    }
    for (int e = 0; e < 6; ++e) {
      const auto [p, q] = kTetEdges[e];
      // The two facets through the edge leave out the other two positions;
      // a lower tetrahedron across either of them contains the edge.
      Index lower = kInvalidIndex;
      for (int s = 0; s < 4; ++s)
        if (s != p && s != q && below[s] != kInvalidIndex) lower = below[s];
      Index triangles = 1;  // k tetrahedra around the edge: k triangles, k + 1 if the ring is open
      if (lower == kInvalidIndex) {
        const Ring ring = around_edge(rt, t, st.v[p], st.v[q], [&](Index u) {
          if (u < t) lower = u;
          ++triangles;
          return u > t;
        });
        triangles += ring.open ? 1 : 0;
      }
      if (lower == kInvalidIndex) {
        own |= std::uint16_t(1u << (4 + e));
        tet_edge[6 * ti + e] = triangles;
      } else {
        tet_edge[6 * ti + e] = lower;
      }
    }
    owns[ti] = own;
  });

  // The numbering: per tetrahedron, its first new cell.
  const Index first_tet_cell = nv;
  std::vector<Index> cell_base(nt);
  std::size_t num_cells = std::size_t(nv) + nt, num_edges = 0;
  for (Index t = 0; t < nt; ++t) {
    cell_base[t] = static_cast<Index>(num_cells);
    const int facets = std::popcount(unsigned(owns[t] & 0xFu)), edges = std::popcount(unsigned(owns[t] >> 4));
    num_cells += std::size_t(facets) + edges;
    num_edges += std::size_t(edges);
    SKINMESH_ASSERT_MSG(num_cells < kInvalidIndex, "too many mixed cells for 32-bit indices");
  }
  // The triangulation fills the bounding tetrahedron, a ball: with V vertices
  // and T tetrahedra it has F = 2T + 2 triangles (4T facets, 4 on the hull)
  // and, by Euler (V - E + F - T = 1), E = V + T + 1 edges.
  SKINMESH_ASSERT_MSG(num_cells == 2 * std::size_t(nv) + 4 * std::size_t(nt) + 3,
                      "the triangulation is not a triangulated ball");
  simplices_.resize(num_cells + 1);
  std::vector<Index> plane_count(num_cells, 0);
  for (Index v = 0; v < np; ++v) {
    if (vertex_cell_[v] == kInvalidIndex) continue;
    CellSimplex& c = simplices_[vertex_cell_[v]];
    c.vertices[0] = v;
    c.bounding = rt.is_bounding(v);
  }
  auto make_cell = [&](Index id, int dim, std::array<Index, 4> v) {
    CellSimplex& c = simplices_[id];
    c.dim = static_cast<std::uint8_t>(dim);
    c.vertices = v;
    for (int i = 0; i <= dim; ++i) c.bounding = c.bounding || rt.is_bounding(v[i]);
  };
  parallel_for(nt, threads, kGrain, [&](std::size_t ti) {
    const Index t = static_cast<Index>(ti);
    const SortedTet st = sorted_tet(rt, t);
    const std::uint16_t own = owns[ti];
    make_cell(first_tet_cell + t, 3, st.v);
    plane_count[first_tet_cell + t] = 4;
    Index id = cell_base[t];
    for (int s = 0; s < 4; ++s) {
      if (!(own & (1u << s))) continue;
      const std::array<int, 3> f = facet_positions(s);
      make_cell(id, 2, {st.v[f[0]], st.v[f[1]], st.v[f[2]], kInvalidIndex});
      plane_count[id] = rt.neighbor(t, st.local[s]) == kInvalidIndex ? 4 : 5;  // 3 edges, 1 or 2 tetrahedra
      tet_tri[4 * ti + s] = id++;
      for (const auto& [p, q] : {std::array<int, 2>{f[0], f[1]}, {f[0], f[2]}, {f[1], f[2]}}) {
        const int e = edge_slot(p, q);
        if (!(own & (1u << (4 + e))) || first_facet(p, q) != s) continue;
        make_cell(id, 1, {st.v[p], st.v[q], kInvalidIndex, kInvalidIndex});
        plane_count[id] = 2 + tet_edge[6 * ti + e];  // 2 vertices, its triangles
        tet_edge[6 * ti + e] = id++;
        // A vertex cell's planes are those with its edges.
        for (Index w : {st.v[p], st.v[q]})
          std::atomic_ref<Index>(plane_count[vertex_cell_[w]]).fetch_add(1, std::memory_order_relaxed);
      }
    }
  });
  // The facets a tetrahedron does not own: the cell of their owner, the
  // lower tetrahedron across them (its slot was set above).
  parallel_for(nt, threads, kGrain, [&](std::size_t ti) {
    const Index t = static_cast<Index>(ti);
    const SortedTet st = sorted_tet(rt, t);
    for (int s = 0; s < 4; ++s) {
      if (owns[ti] & (1u << s)) continue;
      const Index nb = rt.neighbor(t, st.local[s]);
      Index apex = kInvalidIndex;  // the vertex of nb off the facet
      for (Index w : rt.tet(nb))
        if (std::find(st.v.begin(), st.v.end(), w) == st.v.end()) apex = w;
      tet_tri[4 * ti + s] = tet_tri[4 * std::size_t(nb) + rank_in(rt, nb, apex)];
    }
  });
  // The edges it does not own: the slot holds some lower tetrahedron around
  // the edge, whose own slot is final once the lower tetrahedra are done
  // (hence in increasing order, on one thread).
  for (Index t = 0; t < nt; ++t) {
    if ((owns[t] >> 4) == 0x3Fu) continue;
    const SortedTet st = sorted_tet(rt, t);
    for (int e = 0; e < 6; ++e) {
      if (owns[t] & (1u << (4 + e))) continue;
      const Index u = tet_edge[6 * std::size_t(t) + e];
      const int p = rank_in(rt, u, st.v[kTetEdges[e][0]]), q = rank_in(rt, u, st.v[kTetEdges[e][1]]);
      tet_edge[6 * std::size_t(t) + e] = tet_edge[6 * std::size_t(u) + edge_slot(p, q)];
    }
  }

  // Foci of flat tetrahedra (slivers) put back in the order their Voronoi
  // edges require (papers/skin/mixed_complex.md, "Flat tetrahedra").
  order_flat_foci(first_tet_cell);

  // The walk bound of locate() (computed here: a cube root per query was 4 %
  // of the sweep).
  // [measured] a straight walk crosses about cbrt(cells) cells per axis; the
  // floor and the factors are the bound of locate()'s walk before it falls
  // back on a scan.
  constexpr std::size_t kWalkFloor = 64;
  constexpr double kWalkPerCubeRoot = 8;
  max_walk_steps_ = kWalkFloor + 4 * static_cast<std::size_t>(std::cbrt(double(num_cells)) * kWalkPerCubeRoot);

  // The plane lists: the cell across each plane of each cell, in the order
  // planes() makes them. A cell lists its facets first (in the order of its
  // vertices left out: a tetrahedron's four, a triangle's edges 01, 02, 12,
  // an edge's two vertices), then its cofaces by increasing cell number.
  std::size_t total = 0;
  for (std::size_t c = 0; c < num_cells; ++c) {
    simplices_[c].first_plane = static_cast<Index>(total);
    total += plane_count[c];
    SKINMESH_ASSERT_MSG(total < kInvalidIndex, "too many mixed cell planes for 32-bit indices");
  }
  simplices_[num_cells].first_plane = static_cast<Index>(total);
  std::vector<Index>().swap(plane_count);
  SKINMESH_ASSERT_MSG(simplices_[first_tet_cell].first_plane == 2 * num_edges, "the edges of the vertices miscounted");
  neighbors_.resize(total);
  std::vector<Index> vertex_fill(nv, 0);
  auto fill_tet_lists = [&](std::size_t ti, std::vector<Index>& triangles) {
    const Index t = static_cast<Index>(ti);
    const SortedTet st = sorted_tet(rt, t);
    const std::uint16_t own = owns[ti];
    const Index tc = first_tet_cell + t;
    // The tetrahedron's facets; a facet lists its tetrahedra after its three
    // edges, the lower (its owner) first.
    for (int s = 0; s < 4; ++s) {
      const Index f = tet_tri[4 * ti + s];
      neighbors_[simplices_[tc].first_plane + s] = f;
      neighbors_[simplices_[f].first_plane + 3 + ((own & (1u << s)) ? 0 : 1)] = tc;
    }
    // Its own triangles' edges.
    for (int s = 0; s < 4; ++s) {
      if (!(own & (1u << s))) continue;
      const Index f = tet_tri[4 * ti + s];
      const std::array<int, 3> fp = facet_positions(s);
      const std::array<std::array<int, 2>, 3> edges{{{fp[0], fp[1]}, {fp[0], fp[2]}, {fp[1], fp[2]}}};
      for (int j = 0; j < 3; ++j)
        neighbors_[simplices_[f].first_plane + j] = tet_edge[6 * ti + edge_slot(edges[j][0], edges[j][1])];
    }
    // Its own edges' two vertices (and the edge in each vertex's list, sorted
    // below), and their triangles by increasing cell number.
    for (int k = 0; k < 6; ++k) {
      if (!(own & (1u << (4 + k)))) continue;
      const Index e = tet_edge[6 * ti + k];
      const Index a = st.v[kTetEdges[k][0]], b = st.v[kTetEdges[k][1]];
      for (int j = 0; j < 2; ++j) {
        const Index vc = vertex_cell_[j == 0 ? a : b];
        const Index slot = std::atomic_ref<Index>(vertex_fill[vc]).fetch_add(1, std::memory_order_relaxed);
        neighbors_[simplices_[vc].first_plane + slot] = e;
        neighbors_[simplices_[e].first_plane + j] = vc;
      }
      triangles.clear();
      auto add_triangles = [&](Index u) {
        for (Index w : rt.tet(u))
          if (w != a && w != b) triangles.push_back(tet_tri[4 * std::size_t(u) + rank_in(rt, u, w)]);
        return true;
      };
      add_triangles(t);
      around_edge(rt, t, a, b, add_triangles);
      std::sort(triangles.begin(), triangles.end());
      triangles.erase(std::unique(triangles.begin(), triangles.end()), triangles.end());
      SKINMESH_ASSERT_MSG(triangles.size() + 2 == num_planes(e), "the triangles around an edge miscounted");
      std::copy(triangles.begin(), triangles.end(), neighbors_.begin() + simplices_[e].first_plane + 2);
    }
  };
  const std::size_t blocks = (std::size_t(nt) + kGrain - 1) / kGrain;
  parallel_for(blocks, threads, 1, [&](std::size_t block) {
    std::vector<Index> triangles;
    for (std::size_t ti = block * kGrain, end = std::min<std::size_t>(nt, ti + kGrain); ti < end; ++ti)
      fill_tet_lists(ti, triangles);
  });
  // A vertex's edges, by increasing cell number.
  parallel_for(nv, threads, kGrain, [&](std::size_t v) {
    const CellSimplex& c = simplices_[v];
    SKINMESH_ASSERT_MSG(vertex_fill[v] == num_planes(Index(v)), "the edges of a vertex miscounted");
    std::sort(neighbors_.begin() + c.first_plane, neighbors_.begin() + c.first_plane + vertex_fill[v]);
  });

  // The cells' geometry and planes are made on first use (make_cell(),
  // make_planes()).
  made_cells_.init(num_cells, num_cells);
  made_planes_.init(num_cells, neighbors_.size());
}

// MixedComplex Cells and Planes Made on First Use

const MixedCell* MixedComplex::make_cell(Index c) const {
  return made_cells_.make(c, 1, [&](MixedCell* out) { fill_cell(c, *out); });
}

void MixedComplex::fill_cell(Index c, MixedCell& m) const {
  const CellSimplex& x = simplices_[c];
  m.vertices = x.vertices;
  m.dim = x.dim;
  m.bounding = x.bounding;
  m.first_plane = x.first_plane;
  m.num_planes = num_planes(c);
  std::array<WeightedPoint, 4> p;
  for (int j = 0; j <= m.dim; ++j) p[j] = rt_->point(m.vertices[j]);
  focus_of(std::span<const WeightedPoint>(p.data(), m.dim + 1), m.focus, m.focus_weight);
  m.axis = Vec3::Zero();
  if (m.dim == 1) m.axis = (p[1].z - p[0].z).normalized();
  if (m.dim == 2) m.axis = (p[1].z - p[0].z).cross(p[2].z - p[0].z).normalized();
  if (const MovedFocus* moved = m.dim == 3 ? moved_focus(c) : nullptr)
    m.focus = moved->focus, m.focus_weight = moved->weight;
}

const MixedComplex::MovedFocus* MixedComplex::moved_focus(Index c) const {
  if (moved_foci_.empty()) return nullptr;
  const auto it = std::lower_bound(moved_foci_.begin(), moved_foci_.end(), c,
                                   [](const MovedFocus& f, Index u) { return f.cell < u; });
  return it != moved_foci_.end() && it->cell == c ? &*it : nullptr;
}

Vec3 MixedComplex::focus_of_cell(Index c) const {
  if (const MixedCell* made = made_cells_.find(c)) return made->focus;
  const CellSimplex& x = simplices_[c];
  if (const MovedFocus* moved = x.dim == 3 ? moved_focus(c) : nullptr) return moved->focus;
  std::array<WeightedPoint, 4> p;
  for (int j = 0; j <= x.dim; ++j) p[j] = rt_->point(x.vertices[j]);
  Vec3 z;
  double w;
  focus_of(std::span<const WeightedPoint>(p.data(), x.dim + 1), z, w);
  return z;
}

MixedCell MixedComplex::cell_value(Index c) const {
  MixedCell m;
  fill_cell(c, m);
  return m;
}

const CellPlane* MixedComplex::make_planes(Index c) const {
  return made_planes_.make(c, num_planes(c), [&](CellPlane* out) { fill_planes(c, out); });
}

void MixedComplex::fill_planes(Index c, CellPlane* out) const {
  // Planes (papers/skin/skin_math.md §2.3): for X ⊂ Y = X ∪ {k}, the face
  // mu_X ∩ mu_Y = (1-s) delta_X + s nu_Y lies in the plane with unit normal n
  // in lin Y, orthogonal to lin X and pointing from aff X towards z_k, through
  // (1-s) z_a + s z_Y for any vertex a of X; mu_X lies on the side n·x <= offset.
  // n comes from the input centres alone (its orientation, for a triangle, from
  // the exact orient3d of the coface), and the offset from an input centre and
  // the coface's focus z_Y, the same z_Y for every plane of mu_Y. This is the
  // bisector form m·(x - z_X) <= (s/2)(pi_k(z_X) - w_X), m = P_perp^X (z_k - z_X),
  // of papers/skin/skin_math.md §2.3 without its division by |m|: for a nearly
  // flat coface (coplanar atoms, a rotated lattice) |m| and pi_k(z_X) - w_X both
  // vanish, z_Y may coincide with z_X, and the quotient is 0/0, while n, z_a and
  // z_Y stay well defined (papers/skin/mixed_complex.md, "Degenerate inputs").
  // Both cells of a plane compute it as X sees it (a function of X, k and z_Y:
  // the same bits on both sides), and Y stores it negated. A coface's focus
  // is its made cell's, or computed here and not kept (its cell may never be
  // read).
  const geometry::RegularTriangulation& rt = *rt_;
  const CellSimplex& m = simplices_[c];
  const Index n_planes = num_planes(c);
  Vec3 own_focus = Vec3::Zero();
  bool own_focus_made = false;
  for (Index i = 0; i < n_planes; ++i) {
    constexpr double s = 0.5;
    const Index nb = neighbors_[m.first_plane + i];
    const CellSimplex& N = simplices_[nb];
    const bool coface = N.dim < m.dim;  // this cell is Y
    const CellSimplex& X = coface ? N : m;
    const CellSimplex& Y = coface ? m : N;
    const Index k = extra_of(X, Y);
    const Vec3& za = rt.point(X.vertices[0]).z;
    const Vec3 n = facet_coface_normal(rt, X, k);
    Vec3 zY;
    if (coface) {
      if (!own_focus_made) own_focus = focus_of_cell(c), own_focus_made = true;
      zY = own_focus;
    } else {
      zY = focus_of_cell(nb);
    }
    const double off = (1.0 - s) * n.dot(za) + s * n.dot(zY);
    SKINMESH_ASSERT_MSG(std::isfinite(off) && n.allFinite(), "non-finite plane in the mixed complex");
    out[i] = {coface ? Vec3(-n) : n, coface ? -off : off};
  }
}

void MixedComplex::planes_into(Index c, std::vector<CellPlane>& out) const {
  out.resize(num_planes(c));
  fill_planes(c, out.data());
}

void MixedComplex::release_made() const {
  made_cells_.release();
  made_planes_.release();
}

std::size_t MixedComplex::made_bytes() const { return made_cells_.bytes() + made_planes_.bytes(); }

Index MixedComplex::num_cells_of_dim(int d) const {
  Index n = 0;
  for (Index c = 0; c < num_cells(); ++c) n += (simplices_[c].dim == d && !simplices_[c].bounding) ? 1 : 0;
  return n;
}

// MixedComplex Evaluation

double MixedComplex::violation(std::span<const CellPlane> planes, const Vec3& x) {
  double worst = -std::numeric_limits<double>::infinity();
  for (const CellPlane& p : planes) worst = std::max(worst, p.normal.dot(x) - p.offset);
  return worst;
}

Index MixedComplex::locate(const Vec3& x, Index hint) const {
  constexpr double kInsideTolerance = 1e-12;  // [derived] times L: a few ulps of coordinates of size L
  const double tol = kInsideTolerance * length_scale_;
  Index c = hint;
  if (c == kInvalidIndex || c >= num_cells()) {
    // Start from the vertex cell of the tet's vertex nearest in power distance.
    const Index t = rt_->locate(x);
    if (t == kInvalidIndex)
      throw GeometryError("mixed complex: point (" + std::to_string(x.x()) + ", " + std::to_string(x.y()) + ", " +
                          std::to_string(x.z()) + ") lies outside the bounding tetrahedron");
    Index best = kInvalidIndex;
    double best_pow = std::numeric_limits<double>::infinity();
    for (Index v : rt_->tet(t)) {
      if (vertex_cell_[v] == kInvalidIndex) continue;
      const double pw = geometry::power_distance(rt_->point(v), x);
      if (pw < best_pow) {
        best_pow = pw;
        best = v;
      }
    }
    c = vertex_cell_[best];
  }
  // Visibility walk: cross the most violated plane. Bounded number of steps.
  for (std::size_t step = 0; step < max_walk_steps_; ++step) {
    double worst = tol;
    Index next = kInvalidIndex;
    const std::span<const CellPlane> ps = planes(c);
    for (std::size_t i = 0; i < ps.size(); ++i) {
      const double v = ps[i].normal.dot(x) - ps[i].offset;
      if (v > worst) {
        worst = v;
        next = neighbors_[simplices_[c].first_plane + i];
      }
    }
    if (next == kInvalidIndex) return c;
    c = next;
  }
  // Fallback: the cell with the smallest violation.
  Index best = kInvalidIndex;
  double best_v = std::numeric_limits<double>::infinity();
  std::vector<CellPlane> scratch;
  for (Index i = 0; i < num_cells(); ++i) {
    planes_into(i, scratch);
    const double v = violation(scratch, x);
    if (v < best_v) {
      best_v = v;
      best = i;
    }
  }
  constexpr double kOutsideEveryCell = 1e-9;  // [derived] times L: far above the planes' rounding
  if (best_v > kOutsideEveryCell * length_scale_)
    throw GeometryError("mixed complex: no cell contains the point (" + std::to_string(x.x()) + ", " +
                        std::to_string(x.y()) + ", " + std::to_string(x.z()) + ")");
  return best;
}

double MixedComplex::f(Index c, const Vec3& x) const {
  const MixedCell& m = cell(c);
  const Vec3 y = x - m.focus;
  const double yy = y.squaredNorm();
  switch (m.dim) {
    case 0:
      return yy + 0.5 * m.focus_weight;
    case 1: {
      const double a = y.dot(m.axis);
      return yy - 2.0 * a * a + 0.5 * m.focus_weight;
    }
    case 2: {
      const double a = y.dot(m.axis);
      return 2.0 * a * a - yy + 0.5 * m.focus_weight;
    }
    default:
      return -yy + 0.5 * m.focus_weight;
  }
}

Vec3 MixedComplex::gradient(Index c, const Vec3& x) const {
  const MixedCell& m = cell(c);
  const Vec3 y = x - m.focus;
  switch (m.dim) {
    case 0:
      return 2.0 * y;
    case 1:
      return 2.0 * (y - 2.0 * y.dot(m.axis) * m.axis);
    case 2:
      return 2.0 * (2.0 * y.dot(m.axis) * m.axis - y);
    default:
      return -2.0 * y;
  }
}

Mat3 MixedComplex::quadric_matrix(const MixedCell& m) {
  switch (m.dim) {
    case 0:
      return Mat3::Identity();
    case 1:
      return Mat3::Identity() - 2.0 * m.axis * m.axis.transpose();
    case 2:
      return 2.0 * m.axis * m.axis.transpose() - Mat3::Identity();
    default:
      return -Mat3::Identity();
  }
}

}  // namespace skinmesh::skin
