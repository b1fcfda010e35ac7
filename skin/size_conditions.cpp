// skin/size_conditions.cpp: circumradius and the angle bound. Cheng & Shi §2.2.
#include "skin/size_conditions.h"

#include <limits>
#include <numbers>

namespace skinmesh::skin {

double SizeConstants::min_angle_bound_deg() const { return std::asin(1.0 / (Q * Q)) * 180.0 / std::numbers::pi; }

double circumradius(const Vec3& a, const Vec3& b, const Vec3& c) {
  // R = |ab| |bc| |ca| / (4 area) = |ab||bc||ca| / (2 |(b - a) x (c - a)|).
  const double cross = (b - a).cross(c - a).norm();
  if (cross == 0.0) return std::numeric_limits<double>::infinity();
  return (b - a).norm() * (c - b).norm() * (a - c).norm() / (2.0 * cross);
}

}  // namespace skinmesh::skin
