// skin/mixed_complex.cpp: construction of the mixed complex and point location.
// Cheng & Shi 2004 §2.1; papers/skin/skin_math.md §2.2 (foci), §2.3 (half-space
// form), §3.2.
#include "skin/mixed_complex.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>

#include "core/assert.h"
#include "core/errors.h"
#include "geometry/kernel/predicates.h"
#include "geometry/triangulation/key_index.h"

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

/// Key of a sorted edge or triangle: vertex ids packed in 21-bit fields, so
/// below 2^63 as geometry::KeyIndex requires.
std::uint64_t simplex_key(const std::array<Index, 4>& v, int dim) {
  std::uint64_t k = 0;
  for (int i = 0; i <= dim; ++i) k = (k << 21) | static_cast<std::uint64_t>(v[i]);
  return k;
}

constexpr Index kMaxPoints = (1u << 21) - 1;

/// Unit normal of the plane shared by mu_X and mu_Y, Y = X ∪ {k}: the unit
/// vector of lin Y orthogonal to lin X, pointing from aff X towards z_k (the
/// direction of P_perp^X (z_k - z_X), papers/skin/skin_math.md §2.3), computed
/// from the input centres in coordinates relative to a vertex of X. For a
/// triangle X the side of z_k is the exact orient3d sign: Y is a non-flat
/// tetrahedron of the triangulation (SoS), so it is never zero, even when z_k
/// is within rounding of aff X.
Vec3 facet_coface_normal(const geometry::RegularTriangulation& rt, const MixedCell& X, Index k) {
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

void MixedComplex::order_flat_foci(const std::vector<Index>& tet_cell) {
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
  for (int pass = 0; pass < 4; ++pass) {
    bool moved = false;
    for (const Flat& F : flat) {
      MixedCell& T = cells_[tet_cell[F.t]];
      double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
      for (int i = 0; i < 4; ++i) {
        const Index nb = rt.neighbor(F.t, i);
        if (nb == kInvalidIndex) continue;
        const double c = F.m[i].dot(F.n);
        const double bound = F.m[i].dot(cells_[tet_cell[nb]].focus - T.focus) / c;
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
      moved = true;
      ++num_reordered_foci_;
    }
    if (!moved) break;
  }
}

MixedComplex::MixedComplex(const geometry::RegularTriangulation& rt) : rt_(&rt) {
  const Index np = rt.num_points();
  SKINMESH_ASSERT_MSG(np <= kMaxPoints, "at most 2^21 - 1 weighted points are supported");
  const Index nt = rt.num_tets();

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

  // Enumerate the simplices: vertices, then edges, triangles, tetrahedra.
  vertex_cell_.assign(np, kInvalidIndex);
  auto add_cell = [&](int dim, std::array<Index, 4> v) {
    MixedCell c;
    c.dim = static_cast<std::uint8_t>(dim);
    c.vertices = v;
    for (int i = 0; i <= dim; ++i) c.bounding = c.bounding || rt.is_bounding(v[i]);
    cells_.push_back(c);
    return static_cast<Index>(cells_.size() - 1);
  };
  {
    // The triangulation fills the bounding tetrahedron, a ball: with V vertices
    // and T tetrahedra it has F = 2T + 2 triangles (4T facets, 4 on the hull)
    // and, by Euler (V - E + F - T = 1), E = V + T + 1 edges. Reserving the
    // exact count saves the vector's growth (up to half of the complex's
    // memory on large inputs).
    std::size_t nv = 0;
    for (Index v = 0; v < np; ++v) nv += rt.is_vertex(v) ? 1 : 0;
    cells_.reserve(2 * nv + 4 * std::size_t(nt) + 3);
  }
  for (Index v = 0; v < np; ++v)
    if (rt.is_vertex(v)) vertex_cell_[v] = add_cell(0, {v, kInvalidIndex, kInvalidIndex, kInvalidIndex});

  // Euler's formula for the triangulated ball (below): E = V + T + 1 edges and
  // F = 2T + 2 triangles, V <= np.
  // Keys of the edges and triangles met so far, numbered in order; the cell
  // of number i is edge_cell[i] (tri_cell[i]).
  geometry::KeyIndex edge_id(std::size_t(np) + nt + 1), tri_id(2 * std::size_t(nt) + 2);
  std::vector<Index> edge_cell, tri_cell;
  edge_cell.reserve(std::size_t(np) + nt + 1);
  tri_cell.reserve(2 * std::size_t(nt) + 2);
  // Facet/coface pairs (X, Y, k) with Y = X + {k}: one shared plane each.
  struct Pair {
    Index x, y, k;
  };
  std::vector<Pair> pairs;
  pairs.reserve(static_cast<std::size_t>(nt) * 10);

  std::vector<Index> tet_cell(nt);
  for (Index t = 0; t < nt; ++t) {
    std::array<Index, 4> tv = rt.tet(t);
    std::sort(tv.begin(), tv.end());
    tet_cell[t] = add_cell(3, tv);
  }
  auto edge_of = [&](Index a, Index b) {
    std::array<Index, 4> v{std::min(a, b), std::max(a, b), kInvalidIndex, kInvalidIndex};
    const auto [i, fresh] = edge_id.find_or_add(simplex_key(v, 1));
    if (fresh) {
      edge_cell.push_back(add_cell(1, v));
      pairs.push_back({vertex_cell_[v[0]], edge_cell[i], v[1]});
      pairs.push_back({vertex_cell_[v[1]], edge_cell[i], v[0]});
    }
    return edge_cell[i];
  };
  for (Index t = 0; t < nt; ++t) {
    const std::array<Index, 4> tv = cells_[tet_cell[t]].vertices;
    for (int skip = 0; skip < 4; ++skip) {
      std::array<Index, 4> f{kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex};
      for (int i = 0, j = 0; i < 4; ++i)
        if (i != skip) f[j++] = tv[i];
      const auto [i, fresh] = tri_id.find_or_add(simplex_key(f, 2));
      if (fresh) tri_cell.push_back(add_cell(2, f));
      const Index tc = tri_cell[i];
      if (fresh) {
        pairs.push_back({edge_of(f[0], f[1]), tc, f[2]});
        pairs.push_back({edge_of(f[0], f[2]), tc, f[1]});
        pairs.push_back({edge_of(f[1], f[2]), tc, f[0]});
      }
      pairs.push_back({tc, tet_cell[t], tv[skip]});
    }
  }

  cells_.shrink_to_fit();  // a no-op when the count above was exact
  // Foci and axes.
  for (MixedCell& c : cells_) {
    std::array<WeightedPoint, 4> p;
    for (int i = 0; i <= c.dim; ++i) p[i] = rt.point(c.vertices[i]);
    focus_of(std::span<const WeightedPoint>(p.data(), c.dim + 1), c.focus, c.focus_weight);
    if (c.dim == 1) c.axis = (p[1].z - p[0].z).normalized();
    if (c.dim == 2) c.axis = (p[1].z - p[0].z).cross(p[2].z - p[0].z).normalized();
  }

  // Foci of flat tetrahedra (slivers) put back in the order their Voronoi
  // edges require (papers/skin/mixed_complex.md, "Flat tetrahedra").
  order_flat_foci(tet_cell);

  // The walk bound of locate() (computed here: a cube root per query was 4 %
  // of the sweep).
  // [measured] a straight walk crosses about cbrt(cells) cells per axis; the
  // floor and the factors are the bound of locate()'s walk before it falls
  // back on a scan.
  constexpr std::size_t kWalkFloor = 64;
  constexpr double kWalkPerCubeRoot = 8;
  max_walk_steps_ = kWalkFloor + 4 * static_cast<std::size_t>(std::cbrt(double(cells_.size())) * kWalkPerCubeRoot);

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
  constexpr double s = 0.5;
  std::vector<Index> count(cells_.size(), 0);
  for (const Pair& pr : pairs) {
    ++count[pr.x];
    ++count[pr.y];
  }
  Index total = 0;
  for (std::size_t c = 0; c < cells_.size(); ++c) {
    cells_[c].first_plane = total;
    cells_[c].num_planes = count[c];
    total += count[c];
  }
  // Each plane stored once (as X sees it; Y reads it negated), its uses listed
  // per cell in the order of `pairs`.
  SKINMESH_ASSERT_MSG(pairs.size() < (std::size_t{1} << 31), "too many mixed-cell planes");
  shared_planes_.resize(pairs.size());
  plane_extra_.resize(pairs.size());
  plane_uses_.resize(total);
  std::vector<Index> fill(cells_.size(), 0);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const Pair& pr = pairs[i];
    const MixedCell& X = cells_[pr.x];
    const MixedCell& Y = cells_[pr.y];
    const Vec3& za = rt.point(X.vertices[0]).z;
    const Vec3 n = facet_coface_normal(rt, X, pr.k);
    const double off = (1.0 - s) * n.dot(za) + s * n.dot(Y.focus);
    SKINMESH_ASSERT_MSG(std::isfinite(off) && n.allFinite(), "non-finite plane in the mixed complex");
    shared_planes_[i] = {n, off};
    plane_extra_[i] = pr.k;
    const auto id = static_cast<std::uint32_t>(2 * i);
    plane_uses_[X.first_plane + fill[pr.x]++] = {id, pr.y};
    plane_uses_[Y.first_plane + fill[pr.y]++] = {id + 1, pr.x};
  }
}

Index MixedComplex::num_cells_of_dim(int d) const {
  Index n = 0;
  for (const MixedCell& c : cells_) n += (c.dim == d && !c.bounding) ? 1 : 0;
  return n;
}

// MixedComplex Evaluation

double MixedComplex::violation(Index c, const Vec3& x) const {
  double worst = -std::numeric_limits<double>::infinity();
  const MixedCell& m = cells_[c];
  for (Index i = m.first_plane, e = m.first_plane + m.num_planes; i < e; ++i) {
    const PlaneUse u = plane_uses_[i];
    const SharedPlane& p = shared_planes_[u.plane_side >> 1];
    worst = std::max(worst, on_side(p.normal.dot(x) - p.offset, u.plane_side));
  }
  return worst;
}

Index MixedComplex::locate(const Vec3& x, Index hint) const {
  constexpr double kInsideTolerance = 1e-12;  // [derived] times L: a few ulps of coordinates of size L
  const double tol = kInsideTolerance * length_scale_;
  Index c = hint;
  if (c == kInvalidIndex || c >= cells_.size()) {
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
    // The coface side reads the plane negated: -(n·x - offset) is exactly
    // (-n)·x - (-offset), the value of a copy stored for that side.
    const MixedCell& m = cells_[c];
    for (Index i = m.first_plane, e = m.first_plane + m.num_planes; i < e; ++i) {
      const PlaneUse u = plane_uses_[i];
      const SharedPlane& p = shared_planes_[u.plane_side >> 1];
      const double v = on_side(p.normal.dot(x) - p.offset, u.plane_side);
      if (v > worst) {
        worst = v;
        next = u.neighbor;
      }
    }
    if (next == kInvalidIndex) return c;
    c = next;
  }
  // Fallback: the cell with the smallest violation.
  Index best = kInvalidIndex;
  double best_v = std::numeric_limits<double>::infinity();
  for (Index i = 0; i < cells_.size(); ++i) {
    const double v = violation(i, x);
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
  const MixedCell& m = cells_[c];
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
  const MixedCell& m = cells_[c];
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

Mat3 MixedComplex::quadric_matrix(Index c) const {
  const MixedCell& m = cells_[c];
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
