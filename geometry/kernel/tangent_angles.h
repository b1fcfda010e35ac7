// geometry/kernel/tangent_angles.h: angles between directions in a tangent
// plane (unit normal n), the front's numerics: exact-rounding atan2 angles,
// pseudo-angles that order directions without atan2, and a coarse polynomial
// arctangent for tests with a tolerance of degrees.
// Notes: papers/front/creep.md ("Angles in tangent planes")
#pragma once

#include <algorithm>
#include <cmath>

#include "core/types.h"

namespace skinmesh::geometry {

/// Unit tangent direction from p towards x, in the tangent plane with unit
/// normal n; zero if x - p is parallel to n.
inline Vec3 tangent_dir(const Vec3& p, const Vec3& n, const Vec3& x) {
  Vec3 d = x - p;
  d -= d.dot(n) * n;
  const double len = d.norm();
  return len > 0 ? Vec3(d / len) : Vec3::Zero();
}

/// Counter-clockwise angle (about unit n) from unit tangent a to unit tangent
/// b, in [0, 2 pi).
inline double ccw_angle(const Vec3& a, const Vec3& b, const Vec3& n) {
  double t = std::atan2(a.cross(b).dot(n), a.dot(b));
  if (t < 0) t += 2 * kPi;
  return t;
}

/// A pseudo-angle of the direction (x, y) (a tangent's coordinates along
/// and across a reference direction): a monotone map of the angle
/// t = atan2(y, x) taken in [0, 2 pi) as ccw_angle() takes it (including
/// its treatment of signed zeros) onto [0, 4], with dt/dp between 1 and 2,
/// so that pseudo-angle differences bound angle differences:
/// p1 - p0 <= t1 - t0 <= 2 (p1 - p0) for p1 >= p0. Costs a division, no
/// atan2. (0, 0) gives 0, as atan2(0, 0); a NaN gives NaN.
inline double pseudo_angle(double y, double x) {
  const double s = std::abs(x) + std::abs(y);
  if (s == 0) return 0.0;
  const double c = x / s;
  return y >= 0 ? 1 - c : 3 + c;
}

/// The answer of a test decided from pseudo-angles, when it can be.
enum class PseudoVerdict { Holds, Fails, Undecided };

/// Three-valued test of t1 - t0 > tol from pseudo-angles p1, p0 of t1, t0
/// (pseudo_angle, angles in radians): Holds if it certainly holds, Fails if
/// it certainly fails, Undecided if the pseudo-angles cannot tell (within a
/// factor of two of tol, or NaN); kPseudoRounding covers the rounding of both
/// sides.
inline PseudoVerdict pseudo_exceeds(double p1, double p0, double tol) {
  constexpr double kPseudoRounding = 1e-12;  // [derived] a few units in the last place of values in [0, 4]
  const double d = p1 - p0;
  if (d > tol + kPseudoRounding) return PseudoVerdict::Holds;
  if (2 * d < tol - kPseudoRounding) return PseudoVerdict::Fails;
  return PseudoVerdict::Undecided;
}

/// The project's one polynomial arctangent: atan2(y, x) taken in [0, 2 pi),
/// to within kCoarseAtan2Error rad, for tests that only need a tolerance (the
/// sweep's fold test, the verifier's fast path): a minimax odd polynomial of
/// degree 9 on [0, 1] and the usual octant reduction, a few multiplications
/// instead of std::atan2. (0, 0) gives 0; a NaN gives 0.
inline constexpr double kCoarseAtan2Error = 2e-5;  // [measured] tests/geometry/tangent_angles_test.cpp
inline double coarse_atan2(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  const double hi = std::max(ax, ay), lo = std::min(ax, ay);
  if (!(hi > 0)) return 0.0;
  const double z = lo / hi, z2 = z * z;
  double t = z * (0.99986600 + z2 * (-0.33029950 + z2 * (0.18014100 + z2 * (-0.08513300 + z2 * 0.02083510))));
  if (ay > ax) t = kPi / 2 - t;
  if (x < 0) t = kPi - t;
  if (y < 0) t = 2 * kPi - t;
  return t >= 2 * kPi ? t - 2 * kPi : t;
}

/// ccw_angle() to within kCoarseAtan2Error rad for tangent vectors a, b of
/// any nonzero length (zero vectors give 0), for tests with a tolerance of
/// degrees (fold_excess): coarse_atan2, and no normalisation (the angle does
/// not depend on the lengths).
inline double coarse_ccw_angle(const Vec3& a, const Vec3& b, const Vec3& n) {
  return coarse_atan2(a.cross(b).dot(n), a.dot(b));
}

/// Rotates tangent vector a about unit axis n by angle t (radians).
inline Vec3 rotate(const Vec3& a, const Vec3& n, double t) {
  return std::cos(t) * a + std::sin(t) * n.cross(a) + (1 - std::cos(t)) * n.dot(a) * n;
}

}  // namespace skinmesh::geometry
