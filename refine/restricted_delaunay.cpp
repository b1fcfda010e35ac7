// refine/restricted_delaunay.cpp: surface Delaunay ball centres.
#include "refine/restricted_delaunay.h"

#include <cmath>

#include "refine/size_conditions.h"

namespace skinmesh::refine {

Vec3 circumcentre(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a;
  const Vec3 n = ab.cross(ac);
  return a + (ac.squaredNorm() * n.cross(ab) + ab.squaredNorm() * ac.cross(n)) / (2.0 * n.squaredNorm());
}

bool surface_delaunay_centre(const skin::SkinSurface& skin, const Vec3& a, const Vec3& b,
                             const Vec3& c, Vec3& m, Index& cell) {
  const Vec3 n = (b - a).cross(c - a);
  const double len = n.norm();
  if (len == 0.0) return false;
  const Vec3 cc = circumcentre(a, b, c);
  const double R = (a - cc).norm();
  return skin.project_along_line(cc, n / len, 2.0 * R, m, cell);
}

bool outside_every_surface_ball(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double length_scale) {
  const Vec3 nn = (b - a).cross(c - a);
  const double len = nn.norm();
  if (!(len > 0)) return false;
  const Vec3 cc = circumcentre(a, b, c);
  const double R2 = (a - cc).squaredNorm();
  const Vec3 y = d - cc;
  const double lhs = y.squaredNorm() - R2;
  // |t| <= 2R plus the root finder's margin (1e-12 L), rounded up.
  const double t_max = 2.0 * std::sqrt(R2) * (1 + 1e-9) + 1e-11 * length_scale;
  const double slack = 2.0 * t_max * std::abs(y.dot(nn)) / len;
  return lhs > slack + 1e-9 * (y.squaredNorm() + R2);
}

}  // namespace skinmesh::refine
