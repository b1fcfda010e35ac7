// skin/restricted_delaunay.cpp: surface Delaunay ball centres.
#include "skin/restricted_delaunay.h"

#include <cmath>

#include "skin/size_conditions.h"

namespace skinmesh::skin {

Vec3 circumcentre(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a;
  const Vec3 n = ab.cross(ac);
  return a + (ac.squaredNorm() * n.cross(ab) + ab.squaredNorm() * ac.cross(n)) / (2.0 * n.squaredNorm());
}

bool surface_delaunay_centre(const skin::SkinSurface& skin, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& m,
                             Index& cell) {
  const Vec3 n = (b - a).cross(c - a);
  const double len = n.norm();
  if (len == 0.0) return false;
  const Vec3 cc = circumcentre(a, b, c);
  const double R = (a - cc).norm();
  return skin.project_along_line(cc, n / len, 2.0 * R, m, cell);
}

SurfaceBallFilter::SurfaceBallFilter(const Vec3& a, const Vec3& b, const Vec3& c, double length_scale)
    : nn_((b - a).cross(c - a)), cc_(Vec3::Zero()), len_(nn_.norm()) {
  if (!(len_ > 0)) return;
  cc_ = circumcentre(a, b, c);
  R2_ = (a - cc_).squaredNorm();
  // |t| <= 2R plus the root finder's margin (1e-12 L), rounded up. [derived]
  constexpr double kRelativeSlack = 1e-9, kAbsoluteSlack = 1e-11;  // the latter times the length scale
  t_max_ = 2.0 * std::sqrt(R2_) * (1 + kRelativeSlack) + kAbsoluteSlack * length_scale;
}

bool outside_every_surface_ball(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double length_scale) {
  return SurfaceBallFilter(a, b, c, length_scale).outside(d);
}

}  // namespace skinmesh::skin
