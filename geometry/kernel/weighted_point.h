// geometry/kernel/weighted_point.h: a weighted point b = (z, w), w the squared radius (Å²).
// papers/skin/skin_math.md §0 and §1. It lives in geometry/, not skin/, because the
// regular triangulation, which geometry/ owns, takes weighted points
// (papers/conventions.md §2).
#pragma once

#include "core/types.h"

namespace skinmesh::geometry {

/// Weighted point: centre z (Å) and weight w = squared radius (Å²); w < 0 is
/// allowed (an imaginary ball). papers/skin/skin_math.md §0.
struct WeightedPoint {
  Vec3 z = Vec3::Zero();
  double w = 0.0;
};

/// The admissible input range (papers/conventions.md §3 "Errors"): every
/// coordinate of a centre within ±kMaxCoordinate Å (1 mm: far beyond any
/// molecule, and double precision still resolves 2e-9 Å there) and every
/// weight within ±kMaxWeight Å² (a radius of 1e5 Å). Inside it the exact
/// predicates cannot overflow; outside it the readers and the regular
/// triangulation refuse the input with an InputError.
inline constexpr double kMaxCoordinate = 1e7;
inline constexpr double kMaxWeight = 1e10;

/// Power distance pi_b(x) = |x - z|² - w (Å²); negative inside the ball.
/// papers/skin/skin_math.md §0.
inline double power_distance(const WeightedPoint& b, const Vec3& x) { return (x - b.z).squaredNorm() - b.w; }

}  // namespace skinmesh::geometry
