// skin/skin_surface.h: the skin surface F_B of a set of weighted points
// (shrink factor 1/2) as an implicit surface f = 0 over the mixed complex, with
// evaluation, normals, curvature, local length scale and projection.
// Cheng & Shi 2004 §2.1, §4.2 (Figure 9); papers/skin/skin_math.md §3, §4, §7.
// Notes: papers/skin/skin_surface.md
#pragma once

#include <cmath>

#include <memory>
#include <utility>
#include <vector>

#include "core/types.h"
#include "geometry/kernel/weighted_point.h"
#include "geometry/triangulation/regular_triangulation.h"
#include "skin/mixed_complex.h"
#include "skin/molecule.h"

namespace skinmesh::skin {

/// Weight of an atom of van der Waals radius r (Å) with probe radius p (Å):
/// w = 2 (r + p)², so the shrunk ball (s = 1/2) is the solvent-accessible ball
/// of radius r + p. Cheng & Shi §2.1 as read by papers/skin/skin_math.md §1.3
/// (the paper's "weight is sqrt 2 times the sum" is dimensionally a radius).
/// Pre: r + p > 0.
inline double atom_weight(double radius, double probe) { return 2.0 * (radius + probe) * (radius + probe); }

/// The weighted points of a molecule: centre = atom centre (Å), weight =
/// atom_weight(radius, probe) (Å²), in atom order. Pre: probe >= 0.
inline std::vector<geometry::WeightedPoint> weighted_points(const Molecule& molecule, double probe) {
  std::vector<geometry::WeightedPoint> points;
  points.reserve(molecule.atoms.size());
  for (const Atom& a : molecule.atoms) points.push_back({a.centre, atom_weight(a.radius, probe)});
  return points;
}

/// The centre of the local frame of a set of weighted points: the midpoint of
/// their bounding box (Å), rounded to a multiple of 2^-10 Å so that a point
/// list translated by a vector of such multiples gets the same local
/// coordinates. The mesher and the checker work in coordinates relative to
/// it, so that a molecule far from the origin (1e6 Å) is meshed like the same
/// molecule at the origin: the geometry's floating-point tolerances are
/// relative to the molecule's size, not to its distance from the origin.
/// Zero for an empty list.
inline Vec3 local_frame_centre(const std::vector<geometry::WeightedPoint>& points) {
  if (points.empty()) return Vec3::Zero();
  Vec3 lo = points.front().z, hi = lo;
  for (const auto& p : points) lo = lo.cwiseMin(p.z), hi = hi.cwiseMax(p.z);
  Vec3 c = 0.5 * (lo + hi);
  // floor(v + 1/2), not round(v): round() takes halves away from zero, which
  // does not commute with a translation.
  for (int i = 0; i < 3; ++i) c[i] = std::ldexp(std::floor(std::ldexp(c[i], 10) + 0.5), -10);
  return c;
}

/// The points translated by -centre (weights unchanged).
inline std::vector<geometry::WeightedPoint> translated(std::vector<geometry::WeightedPoint> points,
                                                       const Vec3& centre) {
  for (auto& p : points) p.z -= centre;
  return points;
}

/// Value of the skin function and its derivatives at a point.
struct SkinSample {
  double f = 0;                  ///< f(x) (Å²); < 0 inside the body
  Vec3 gradient = Vec3::Zero();  ///< grad f(x) (Å); |grad f| = 2 rho on the skin
  double rho = 0;                ///< local length scale |x - z_X| (Å)
  Index cell = kInvalidIndex;    ///< mixed cell containing x
};

/// Principal curvatures (1/Å) with the sign convention of
/// papers/skin/skin_math.md §0 (positive when the surface bends away from the
/// outward normal).
struct PrincipalCurvatures {
  double k1 = 0, k2 = 0;
};

// SkinSurface Definition

/// The skin surface of weighted points: owns the regular triangulation and the
/// mixed complex. All queries take a cell hint (any cell index, or
/// kInvalidIndex) to start the point-location walk; pass the cell of a nearby
/// earlier query for O(1) evaluation.
class SkinSurface {
 public:
  /// Builds the regular triangulation and the mixed complex of `points`
  /// (weights w = squared radii, Å²; non-empty; finite); the mixed complex
  /// on up to `threads` threads (0: every core; the result does not depend on
  /// the count). Throws InputError on an empty or non-finite input.
  explicit SkinSurface(std::vector<geometry::WeightedPoint> points, int threads = 1);

  const std::vector<geometry::WeightedPoint>& points() const { return points_; }
  const geometry::RegularTriangulation& triangulation() const { return *rt_; }
  const MixedComplex& mixed_complex() const { return *mc_; }
  /// Input length scale L (Å), the unit of tolerances (papers/skin/skin_math.md §9).
  double length_scale() const { return mc_->length_scale(); }

  /// f, grad f, rho and the containing cell at x (papers/skin/skin_math.md §3, §4.1).
  SkinSample sample(const Vec3& x, Index hint = kInvalidIndex) const;
  /// Outward unit normal grad f / |grad f| at x (papers/skin/skin_math.md §3.2).
  Vec3 normal(const Vec3& x, Index hint = kInvalidIndex) const;
  /// Principal curvatures at a skin point x of cell c (closed forms,
  /// papers/skin/skin_math.md §4.1).
  PrincipalCurvatures curvatures(Index c, const Vec3& x) const;

  /// Normal-line projection (papers/skin/skin_math.md §7.2, Cheng & Shi
  /// Figure 9): the point q + t n with f = 0 and t in [-delta, delta] closest
  /// to t = 0. The bracket is guaranteed by the sandwiching balls when q lies
  /// in the tangent disc of radius r at a skin point a with outward normal n
  /// and delta = rho(a) - sqrt(rho(a)² - r²). Returns false if f does not change
  /// sign on the segment. `cell` is the hint on entry and the cell of the
  /// result on exit.
  bool project_along_line(const Vec3& q, const Vec3& n, double delta, Vec3& out, Index& cell) const;
  /// Gradient–Newton pull-back x <- x - f grad f / |grad f|² until
  /// |f| / |grad f| <= tolerance · L (papers/skin/skin_math.md §7.3; the
  /// default 1e-14 is the surface to rounding, a looser one serves callers that
  /// need only the gradient near the surface). Converges from offsets up to
  /// about rho/2. Throws GeometryError if it does not converge in 100 steps. If
  /// `at_result` is given, it receives the sample at the returned point (the one
  /// the convergence test read: the same as sample(result, cell)), so that
  /// callers need not sample it again.
  Vec3 pull_back(const Vec3& x, Index& cell, SkinSample* at_result = nullptr, double tolerance = 1e-14) const;
  /// Distance estimate |f(x)| / |grad f(x)| (Å): first-order distance to the skin.
  double distance_estimate(const Vec3& x, Index hint = kInvalidIndex) const;

  /// Index of the input atom whose patch holds the skin point x of cell c: the
  /// vertex of the cell's simplex closest to x in power distance.
  Index atom_of(Index c, const Vec3& x) const;

 private:
  std::vector<geometry::WeightedPoint> points_;
  std::unique_ptr<geometry::RegularTriangulation> rt_;
  std::unique_ptr<MixedComplex> mc_;
};

}  // namespace skinmesh::skin
