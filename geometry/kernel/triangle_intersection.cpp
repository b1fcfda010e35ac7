// geometry/kernel/triangle_intersection.cpp: exact segment/triangle and
// triangle/triangle intersection tests (see triangle_intersection.h).
#include "geometry/kernel/triangle_intersection.h"

#include <Eigen/Geometry>  // cross()
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "geometry/kernel/predicates.h"

namespace skinmesh::geometry {

namespace {

// 2D Helpers ------------------------------------------------------------------

// A point of the plane obtained by dropping one coordinate. Dropping a
// coordinate is exact, and for points in one plane it is an affine bijection
// onto R^2 whenever the plane's triangle stays non-degenerate, so incidences
// and orientations (up to one global sign) are preserved exactly.
struct P2 {
  double x, y;
};

P2 drop(const Vec3& p, int axis) {
  switch (axis) {
    case 0:
      return {p.y(), p.z()};
    case 1:
      return {p.z(), p.x()};
    default:
      return {p.x(), p.y()};
  }
}

int o2(const P2& a, const P2& b, const P2& c) { return static_cast<int>(orient2d(a.x, a.y, b.x, b.y, c.x, c.y)); }

int o3(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) { return static_cast<int>(orient3d(a, b, c, d)); }

// The coordinate to drop so that triangle abc stays non-degenerate: the largest
// component of the (floating-point) normal first, checked exactly; -1 if abc is
// degenerate.
int projection_axis(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a;
  const Vec3 n = ab.cross(ac);
  int order[3] = {0, 1, 2};
  // Sort the three axes by decreasing |n_k| (three elements: by hand).
  auto mag = [&](int k) { return std::abs(n[k]); };
  if (mag(order[1]) > mag(order[0])) std::swap(order[0], order[1]);
  if (mag(order[2]) > mag(order[1])) std::swap(order[1], order[2]);
  if (mag(order[1]) > mag(order[0])) std::swap(order[0], order[1]);
  for (int k : order)
    if (o2(drop(a, k), drop(b, k), drop(c, k)) != 0) return k;
  return -1;
}

int require_projection_axis(const Vec3& a, const Vec3& b, const Vec3& c) {
  const int k = projection_axis(a, b, c);
  if (k < 0)
    throw std::invalid_argument("triangle_intersection: degenerate (collinear) triangle where a plane is needed");
  return k;
}

// p on the closed segment [a, b], given that p, a, b are collinear.
bool on_segment_collinear(const P2& p, const P2& a, const P2& b) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

// Closed segments [p, q] and [a, b] share a point (either may be a point).
bool segments_intersect_2d(const P2& p, const P2& q, const P2& a, const P2& b) {
  const int d1 = o2(p, q, a), d2 = o2(p, q, b), d3 = o2(a, b, p), d4 = o2(a, b, q);
  if (d1 * d2 < 0 && d3 * d4 < 0) return true;  // proper crossing
  if (d1 == 0 && on_segment_collinear(a, p, q)) return true;
  if (d2 == 0 && on_segment_collinear(b, p, q)) return true;
  if (d3 == 0 && on_segment_collinear(p, a, b)) return true;
  if (d4 == 0 && on_segment_collinear(q, a, b)) return true;
  return false;
}

// p in the closed non-degenerate triangle abc (either orientation).
bool point_in_triangle_2d(const P2& p, const P2& a, const P2& b, const P2& c) {
  const int s1 = o2(a, b, p), s2 = o2(b, c, p), s3 = o2(c, a, p);
  const bool neg = s1 < 0 || s2 < 0 || s3<0, pos = s1> 0 || s2 > 0 || s3 > 0;
  return !(neg && pos);
}

// Closed segment [p, q] meets the closed non-degenerate triangle abc, all in a plane.
bool segment_triangle_2d(const P2& p, const P2& q, const P2& a, const P2& b, const P2& c) {
  return point_in_triangle_2d(p, a, b, c) || point_in_triangle_2d(q, a, b, c) || segments_intersect_2d(p, q, a, b) ||
         segments_intersect_2d(p, q, b, c) || segments_intersect_2d(p, q, c, a);
}

// Segment/triangle with the sides op = orient3d(a, b, c, p), oq = orient3d(a, b, c, q)
// already known.
bool segment_triangle_with_sides(const Vec3& p, const Vec3& q, int op, int oq, const Vec3& a, const Vec3& b,
                                 const Vec3& c) {
  if (op == oq && op != 0) return false;  // strictly on one side of the plane
  if (op == 0 && oq == 0) {               // the segment lies in the plane
    const int k = require_projection_axis(a, b, c);
    return segment_triangle_2d(drop(p, k), drop(q, k), drop(a, k), drop(b, k), drop(c, k));
  }
  // The line pq crosses the plane in one point X of the closed segment. X is in
  // the closed triangle iff the orientations of the line with the three edges are
  // not strictly of both signs (they cannot all vanish: pq is not in the plane).
  const int s1 = o3(p, q, a, b), s2 = o3(p, q, b, c), s3 = o3(p, q, c, a);
  const bool neg = s1 < 0 || s2 < 0 || s3<0, pos = s1> 0 || s2 > 0 || s3 > 0;
  return !(neg && pos);
}

}  // namespace

// Triangle Intersection Public Functions ------------------------------------------

bool is_degenerate_triangle(const Vec3& a, const Vec3& b, const Vec3& c) { return projection_axis(a, b, c) < 0; }

bool segment_intersects_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  return segment_triangle_with_sides(p, q, o3(a, b, c, p), o3(a, b, c, q), a, b, c);
}

bool triangles_intersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1,
                         const Vec3& b2) {
  // Vertices of B against the plane of A, then of A against the plane of B.
  const int db[3] = {o3(a0, a1, a2, b0), o3(a0, a1, a2, b1), o3(a0, a1, a2, b2)};
  if (db[0] == db[1] && db[1] == db[2] && db[0] != 0) return false;
  const int da[3] = {o3(b0, b1, b2, a0), o3(b0, b1, b2, a1), o3(b0, b1, b2, a2)};
  if (da[0] == da[1] && da[1] == da[2] && da[0] != 0) return false;

  const Vec3* A[3] = {&a0, &a1, &a2};
  const Vec3* B[3] = {&b0, &b1, &b2};
  if (db[0] == 0 && db[1] == 0 && db[2] == 0) {
    // Coplanar: in 2D, an edge of A meets B, or B lies inside A.
    const int k = require_projection_axis(a0, a1, a2);
    P2 pa[3], pb[3];
    for (int i = 0; i < 3; ++i) {
      pa[i] = drop(*A[i], k);
      pb[i] = drop(*B[i], k);
    }
    if (o2(pb[0], pb[1], pb[2]) == 0)
      throw std::invalid_argument("triangles_intersect: degenerate (collinear) triangle");
    for (int i = 0; i < 3; ++i)
      if (segment_triangle_2d(pa[i], pa[(i + 1) % 3], pb[0], pb[1], pb[2])) return true;
    return point_in_triangle_2d(pb[0], pa[0], pa[1], pa[2]);
  }
  // Not coplanar: the two intersection intervals on the common line overlap
  // iff an edge of one triangle meets the other triangle.
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (segment_triangle_with_sides(*A[i], *A[j], da[i], da[j], b0, b1, b2)) return true;
    if (segment_triangle_with_sides(*B[i], *B[j], db[i], db[j], a0, a1, a2)) return true;
  }
  return false;
}

bool triangles_intersect_beyond_vertex(const Vec3& s, const Vec3& a1, const Vec3& a2, const Vec3& b1, const Vec3& b2) {
  // If a1 and a2 lie strictly on one side of the plane of B = (s, b1, b2), every
  // point of A = (s, a1, a2) but s does too (orient3d is affine in its last
  // point and vanishes at s), so A and B meet only at s; likewise with A and B
  // exchanged. This settles most pairs of a mesh's fan with two orient3d.
  const int sa1 = o3(s, b1, b2, a1), sa2 = o3(s, b1, b2, a2);
  if (sa1 == sa2 && sa1 != 0) return false;
  const int sb1 = o3(s, a1, a2, b1), sb2 = o3(s, a1, a2, b2);
  if (sb1 == sb2 && sb1 != 0) return false;
  return segment_triangle_with_sides(a1, a2, sa1, sa2, s, b1, b2) ||
         segment_triangle_with_sides(b1, b2, sb1, sb2, s, a1, a2);
}

bool triangles_intersect_beyond_edge(const Vec3& u, const Vec3& v, const Vec3& a, const Vec3& b) {
  if (o3(u, v, a, b) != 0) return false;
  const int k = require_projection_axis(u, v, a);
  const P2 pu = drop(u, k), pv = drop(v, k);
  const int sa = o2(pu, pv, drop(a, k)), sb = o2(pu, pv, drop(b, k));
  if (sb == 0) throw std::invalid_argument("triangles_intersect_beyond_edge: degenerate (collinear) triangle");
  return sa == sb;
}

bool mesh_triangles_intersect(const std::array<Index, 3>& t, const std::array<Index, 3>& u,
                              std::span<const Vec3> positions) {
  // Positions in t and u of the shared indices.
  int ti[3], ui[3], n = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (t[i] == u[j]) {
        ti[n] = i;
        ui[n] = j;
        ++n;
      }
  auto P = [&](Index i) -> const Vec3& { return positions[i]; };
  switch (n) {
    case 0:
      return triangles_intersect(P(t[0]), P(t[1]), P(t[2]), P(u[0]), P(u[1]), P(u[2]));
    case 1: {
      const int i = ti[0], j = ui[0];
      return triangles_intersect_beyond_vertex(P(t[i]), P(t[(i + 1) % 3]), P(t[(i + 2) % 3]), P(u[(j + 1) % 3]),
                                               P(u[(j + 2) % 3]));
    }
    case 2: {
      const int a = 3 - ti[0] - ti[1], b = 3 - ui[0] - ui[1];  // the unshared corners
      return triangles_intersect_beyond_edge(P(t[ti[0]]), P(t[ti[1]]), P(t[a]), P(u[b]));
    }
    default:
      return true;
  }
}

}  // namespace skinmesh::geometry
