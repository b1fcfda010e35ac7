// geometry/kernel/angles.h: angles of triangles (the quality measure of every
// mesh stage and of the verifier), in radians.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/types.h"

namespace skinmesh::geometry {

/// Angle (radians, in [0, pi]) at corner a of triangle abc, between b - a and
/// c - a; 0 if an edge has zero length. atan2 form: accurate near 0 and pi.
inline double corner_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 u = b - a, w = c - a;
  return std::atan2(u.cross(w).norm(), u.dot(w));
}

/// The smallest angle (radians) of triangle abc.
inline double min_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  return std::min({corner_angle(a, b, c), corner_angle(b, c, a), corner_angle(c, a, b)});
}

}  // namespace skinmesh::geometry
