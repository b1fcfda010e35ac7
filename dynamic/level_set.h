// dynamic/level_set.h: the level sets {f = c} of the skin function, which are
// the skins of the grown (c < 0: shrunk) weighted points, with the evaluation,
// projection and segment crossing the dynamic-skin baseline needs.
// Notes: papers/dynamic/dynamic_skin.md ("Growth: one function, its level sets")
#pragma once

#include "core/types.h"
#include "skin/skin_surface.h"

namespace skinmesh::dynamic {

/// The level set F_c = {x : f(x) = c} of the skin function f of `skin`
/// (f < 0 inside the body, Å²). Adding δ to every weight leaves the regular
/// triangulation and the mixed complex unchanged and turns f into f - δ/2
/// (shrink factor 1/2), so F_c is the skin of the weighted points with every
/// weight increased by δ = 2c; F_0 is the skin. In every mixed cell the local
/// length scale of F_c is rho(x) = |x - z_X| and |grad f| = 2 rho, as on the skin.
class LevelSet {
 public:
  /// Pre: `skin` outlives this object; c <= 0 (every F_c with c <= 0 lies in
  /// the hull box below, which is what value() relies on).
  LevelSet(const skin::SkinSurface& skin, double c);

  const skin::SkinSurface& skin() const { return *skin_; }
  /// The level c (Å²).
  double level() const { return c_; }
  /// Input length scale L (Å) of the skin.
  double length_scale() const { return skin_->length_scale(); }

  /// True if x lies outside the box of the atom centres widened by the
  /// largest atom radius sqrt(w): the body of every F_c, c <= 0, lies in the
  /// convex hull of the atoms' balls (convex combinations of balls have
  /// smaller weights), so there f > 0 >= c.
  bool outside_hull(const Vec3& x) const;
  /// Corners of the hull box (Å).
  const Vec3& hull_lo() const { return lo_; }
  const Vec3& hull_hi() const { return hi_; }

  /// f(x) - c (Å²); `cell` is the point-location hint on entry and x's mixed
  /// cell on exit. A point outside_hull() is not located: the result is then
  /// its squared distance to the hull box plus 1 Å², positive like f - c, and
  /// `cell` is left unchanged.
  double value(const Vec3& x, Index& cell) const;

  /// Gradient–Newton projection x <- x - (f - c) grad f / |grad f|² until
  /// |f - c| / |grad f| <= 1e-14 L (papers/skin/skin_math.md §7.3 for the skin
  /// itself). Returns false if it has not reached 1e-11 L after 100 steps.
  /// Out: the point, its cell and rho there (Å).
  bool project(const Vec3& x, Vec3& out, Index& cell, double& rho) const;

  /// A point of F_c on the segment [p, q], given vp = value(p) and vq =
  /// value(q) of opposite signs: Illinois regula falsi with a bisection every
  /// third step, to 1e-12 L along the segment, then project(). `cell` is a
  /// hint on entry. Returns false if the projection fails.
  bool crossing(const Vec3& p, const Vec3& q, double vp, double vq, Vec3& out, Index& cell, double& rho) const;

 private:
  const skin::SkinSurface* skin_;
  double c_;
  Vec3 lo_, hi_;  // the hull box
};

}  // namespace skinmesh::dynamic
