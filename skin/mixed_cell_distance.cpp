// skin/mixed_cell_distance.cpp: cell_distance(), exact where the half-space
// form of a mixed cell is ill-conditioned.
// Notes: papers/morse/critical_points.md ("Flat tetrahedra", "Slivers")
#include "skin/mixed_cell_distance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "geometry/kernel/predicates.h"

namespace skinmesh::skin {

namespace {

/// Distance (Å) from x to the closed triangle abc: the closest point is found
/// by the Voronoi regions of the corners, the edges and the face, so a
/// needle-shaped triangle is handled like any other (its edges take over).
double distance_to_triangle(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ax = x - a;
  const double d1 = ab.dot(ax), d2 = ac.dot(ax);
  if (d1 <= 0 && d2 <= 0) return ax.norm();
  const Vec3 bx = x - b;
  const double d3 = ab.dot(bx), d4 = ac.dot(bx);
  if (d3 >= 0 && d4 <= d3) return bx.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (x - (a + (d1 / (d1 - d3)) * ab)).norm();
  const Vec3 cx = x - c;
  const double d5 = ab.dot(cx), d6 = ac.dot(cx);
  if (d6 >= 0 && d5 <= d6) return cx.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (x - (a + (d2 / (d2 - d6)) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (x - (b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b))).norm();
  const double denom = va + vb + vc;
  if (!(denom > 0)) {  // collinear corners: the nearest of the three edges
    auto seg = [&](const Vec3& p, const Vec3& q) {
      const Vec3 pq = q - p;
      const double l2 = pq.squaredNorm();
      const double t = l2 > 0 ? std::clamp(pq.dot(x - p) / l2, 0.0, 1.0) : 0.0;
      return (x - (p + t * pq)).norm();
    };
    return std::min({seg(a, b), seg(b, c), seg(c, a)});
  }
  return (x - (a + (vb / denom) * ab + (vc / denom) * ac)).norm();
}

/// Distance (Å) from x to the closed tetrahedron v[0..3]: 0 if the exact
/// orientation tests put x inside, otherwise the distance to the nearest
/// facet. Unlike a test against the four facet planes with a tolerance, this
/// stays exact for a sliver (four nearly coplanar corners), whose widened
/// facet half-spaces would contain a whole slab of space.
double distance_to_tetrahedron(const Vec3& x, const std::array<Vec3, 4>& v) {
  static constexpr int kFacet[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  bool inside = true;
  for (int i = 0; i < 4 && inside; ++i) {
    const Vec3 &a = v[kFacet[i][0]], &b = v[kFacet[i][1]], &c = v[kFacet[i][2]];
    const Sign ref = geometry::orient3d(a, b, c, v[i]);
    const Sign sx = geometry::orient3d(a, b, c, x);
    inside = ref != Sign::Zero && (sx == ref || sx == Sign::Zero);
  }
  if (inside) return 0.0;
  double d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i)
    d = std::min(d, distance_to_triangle(x, v[kFacet[i][0]], v[kFacet[i][1]], v[kFacet[i][2]]));
  return d;
}

}  // namespace

double cell_distance(const skin::MixedComplex& mc, Index c, const Vec3& p) {
  const MixedCell& X = mc.cell(c);
  return cell_distance(mc, c, X, p, X.dim <= 1 ? mc.planes(c) : std::span<const CellPlane>());
}

double cell_distance(const skin::MixedComplex& mc, Index c, const MixedCell& X, const Vec3& p,
                     std::span<const CellPlane> planes) {
  const geometry::RegularTriangulation& rt = mc.triangulation();
  if (X.dim == 3) {
    // mu_T = (T + z_T) / 2: p in mu_T iff q = 2 p - z_T in T.
    std::array<Vec3, 4> v;
    for (int i = 0; i < 4; ++i) v[i] = rt.point(X.vertices[i]).z;
    return 0.5 * distance_to_tetrahedron(2.0 * p - X.focus, v);
  }
  if (X.dim == 2) {
    // mu_t = (t + V_t) / 2 with n = X.axis: p = z_t + x/2 + s n/2, x in
    // t - z_t (the plane of t), z_t + s n on the Voronoi edge V_t. V_t is
    // oriented: it ends at the focus of the coface T on the side of T's apex
    // (sigma = ±1, the side of the plane's normal, from exact orientation), so
    // sigma s <= sigma n·(z_T - z_t) for both cofaces (the mixed complex has
    // put the focus of a flat coface in the order its neighbours require).
    // With the two foci in the wrong order V_t is empty: every s is outside.
    // The side of T's apex k is that of its plane's normal, which is ±n by
    // the same exact orient3d (MixedComplex's planes): no plane is needed.
    std::array<Index, 2> tets{};
    int nt = 0;
    for (const Index nb : mc.neighbors(c))
      if (mc.simplex(nb).dim == 3 && nt < 2) tets[nt++] = nb;
    if (nt != 2) {  // a hull triangle (one coface): the half-space form
      std::vector<CellPlane> own;
      if (planes.empty()) mc.planes_into(c, own), planes = own;
      return std::max(skin::MixedComplex::violation(planes, p), 0.0);
    }
    const Vec3& n = X.axis;
    const Vec3 y = p - X.focus;
    const double s = 2.0 * n.dot(y);
    double out_s = 0.0;
    const Vec3 &a = rt.point(X.vertices[0]).z, &b = rt.point(X.vertices[1]).z, &cz = rt.point(X.vertices[2]).z;
    for (const Index T : tets) {
      const double sigma =
          geometry::orient3d(a, b, cz, rt.point(mc.extra_vertex(c, T)).z) == Sign::Positive ? 1.0 : -1.0;
      const double sT = n.dot(mc.cell_value(T).focus - X.focus);
      out_s = std::max(out_s, sigma * (s - sT));
    }
    const Vec3 x = X.focus + 2.0 * (y - n.dot(y) * n);
    const double out_t =
        distance_to_triangle(x, rt.point(X.vertices[0]).z, rt.point(X.vertices[1]).z, rt.point(X.vertices[2]).z);
    return 0.5 * std::hypot(out_s, out_t);
  }
  return std::max(skin::MixedComplex::violation(planes, p), 0.0);
}

}  // namespace skinmesh::skin
