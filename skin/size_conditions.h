// skin/size_conditions.h: the size conditions [L] and [U] that give the
// restricted Delaunay triangulation the closed-ball property and every angle
// above arcsin(1/Q²) (Cheng & Shi 2004 §2.2, from Cheng et al. [3]), and the
// tangent-disc radius derived from them (§4.2).
// Notes: papers/skin/size_conditions.md
#pragma once

#include <algorithm>
#include <cmath>

#include "core/types.h"

namespace skinmesh::skin {

/// The constants C and Q of conditions [L] and [U] (Cheng & Shi §2.2; the
/// proof of the closed-ball property holds for C = 0.08, Q = 1.65).
struct SizeConstants {
  double C = 0.08;
  double Q = 1.65;

  /// Guaranteed minimum angle arcsin(1/Q²) in degrees (21.55° for Q = 1.65).
  double min_angle_bound_deg() const;
  /// Lower end of the tangent-disc window, r_a / rho(a) > 2C / (Q - 2C)
  /// (0.1074 for the defaults; Cheng & Shi §4.2).
  double disc_factor_lower() const { return 2 * C / (Q - 2 * C); }
  /// Upper end of the tangent-disc window,
  /// r_a / rho(a) = 2CQ / (1 + 2CQ)² · sqrt((1 + CQ)(1 + 3CQ)) (0.2077; the
  /// paper prints this without the factor 2, papers/skin/skin_math.md §8 error 1).
  double disc_factor_upper() const {
    const double cq = C * Q;
    return 2 * cq / ((1 + 2 * cq) * (1 + 2 * cq)) * std::sqrt((1 + cq) * (1 + 3 * cq));
  }
};

/// [L] (Cheng & Shi §2.2): R_ab = |ab| / 2 > (C/Q) max(rho_a, rho_b).
/// Positions in Å, rho in Å. Returns true if the edge satisfies [L].
inline bool satisfies_L(const Vec3& a, const Vec3& b, double rho_a, double rho_b, const SizeConstants& k) {
  return 0.5 * (b - a).norm() > (k.C / k.Q) * std::max(rho_a, rho_b);
}

/// Circumradius (Å) of triangle abc; +infinity for a degenerate triangle.
double circumradius(const Vec3& a, const Vec3& b, const Vec3& c);

/// [U] (Cheng & Shi §2.2): R_abc < C Q min(rho_a, rho_b, rho_c).
/// Returns true if the triangle satisfies [U].
inline bool satisfies_U(const Vec3& a, const Vec3& b, const Vec3& c, double rho_a, double rho_b, double rho_c,
                        const SizeConstants& k) {
  return circumradius(a, b, c) < k.C * k.Q * std::min({rho_a, rho_b, rho_c});
}

}  // namespace skinmesh::skin
