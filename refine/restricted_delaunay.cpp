// refine/restricted_delaunay.cpp: surface Delaunay ball centres.
#include "refine/restricted_delaunay.h"

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

}  // namespace skinmesh::refine
