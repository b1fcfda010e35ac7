// skin/restricted_delaunay.h: surface Delaunay balls and the restricted
// Delaunay test for triangles of a mesh with vertices on the skin.
// Cheng & Shi 2004 §2.2 ("Restricted Delaunay triangulation"), §4.3 (edge
// flipping keeps it); papers/front/open_questions.md Q9.2 (the flip criterion).
// Notes: papers/skin/restricted_delaunay.md
#pragma once

#include <cmath>

#include "core/types.h"
#include "skin/skin_surface.h"

namespace skinmesh::skin {

/// Circumcentre (Å) of triangle abc in its plane. Pre: abc not degenerate.
Vec3 circumcentre(const Vec3& a, const Vec3& b, const Vec3& c);

/// The surface Delaunay ball of triangle abc (vertices on the skin): its
/// centre m is the point where the line through the circumcentre along the
/// triangle normal (the line of the dual Voronoi edge) meets the skin, the
/// intersection nearest to the circumcentre within distance 2R (R the
/// circumradius); its radius is |m - a|. `cell` is a mixed-cell hint on entry
/// and m's cell on exit. Returns false if the line does not meet the skin
/// there (a triangle far from restricted Delaunay).
bool surface_delaunay_centre(const skin::SkinSurface& skin, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& m,
                             Index& cell);

/// Exact-answer filter for the surface Delaunay ball test: true if point d
/// lies outside (or on) every ball through a, b, c whose centre is
/// cc + t n with |t| <= 2R + 1e-12 L (cc, R: circumcentre and circumradius, n
/// the unit normal, L = `length_scale`, Å) — the range surface_delaunay_centre
/// searches, its fallback t = 0 included. Then d is outside the surface
/// Delaunay ball whatever its centre, without projecting onto the skin.
/// Uses |d - m|² - |a - m|² = |d - cc|² - R² - 2t (d - cc)·n, with a relative
/// margin of 1e-9. False for a degenerate triangle (decide by projecting).
bool outside_every_surface_ball(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double length_scale);

/// outside_every_surface_ball() for many points d against one triangle abc:
/// the triangle's circumcentre, radius and normal computed once (the same
/// arithmetic, so the same answers).
class SurfaceBallFilter {
 public:
  SurfaceBallFilter(const Vec3& a, const Vec3& b, const Vec3& c, double length_scale);
  /// outside_every_surface_ball(a, b, c, d, length_scale).
  bool outside(const Vec3& d) const {
    if (!(len_ > 0)) return false;
    const Vec3 y = d - cc_;
    const double lhs = y.squaredNorm() - R2_;
    const double slack = 2.0 * t_max_ * std::abs(y.dot(nn_)) / len_;
    return lhs > slack + 1e-9 * (y.squaredNorm() + R2_);
  }

 private:
  Vec3 nn_, cc_;  ///< (b - a) x (c - a), circumcentre (Å)
  double len_, R2_ = 0, t_max_ = 0;
};

}  // namespace skinmesh::skin
