// geometry/weighted_point.h: a weighted point b = (z, w), w the squared radius (Å²).
// papers/skin/skin_math.md §0 and §1. It lives in geometry/, not skin/, because the
// regular triangulation, which geometry/ owns, takes weighted points
// (papers/conventions.md §2).
#pragma once

#include "geometry/types.h"

namespace skinmesh::geometry {

/// Weighted point: centre z (Å) and weight w = squared radius (Å²); w < 0 is
/// allowed (an imaginary ball). papers/skin/skin_math.md §0.
struct WeightedPoint {
  Vec3 z = Vec3::Zero();
  double w = 0.0;
};

/// Power distance pi_b(x) = |x - z|² - w (Å²); negative inside the ball.
/// papers/skin/skin_math.md §0.
inline double power_distance(const WeightedPoint& b, const Vec3& x) {
  return (x - b.z).squaredNorm() - b.w;
}

}  // namespace skinmesh::geometry
