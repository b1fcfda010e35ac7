// morse/critical_points.h: critical points of the height function h(x) = e·x
// on the skin, found analytically patch by patch, with their index.
// Cheng & Shi 2004 §3.1, §3.2 "Construction"; papers/skin/skin_math.md §5.
// Notes: papers/morse/critical_points.md
#pragma once

#include <vector>

#include "core/types.h"
#include "skin/skin_surface.h"

namespace skinmesh::morse {

/// Morse index of a critical point of the height: 0 minimum, 1 saddle, 2 maximum.
enum class CriticalKind : int { Minimum = 0, Saddle = 1, Maximum = 2 };

/// Default height direction: a fixed generic unit vector close to the y axis
/// (the paper's h(p) = y_p, Cheng & Shi §3.1), tilted by about 2.4° so that
/// symmetric molecules (axes along coordinate directions, atoms on lattices)
/// do not put critical points on mixed-cell faces or create saddle–saddle
/// connections (papers/skin/skin_math.md §9 "Generic height direction").
Vec3 default_height_direction();

/// A critical point of h on the skin.
struct CriticalPoint {
  Vec3 position = Vec3::Zero();  ///< on the skin (Å)
  CriticalKind kind = CriticalKind::Minimum;
  Index cell = kInvalidIndex;  ///< mixed cell whose patch holds it
  double height = 0;           ///< e·position (Å)
  double rho = 0;              ///< local length scale (Å)
  /// Outward normal is sigma·e (sigma = ±1).
  int sigma = 1;
  /// Principal curvatures at the point (1/Å), papers/skin/skin_math.md §4.1.
  double k1 = 0, k2 = 0;
  /// For saddles: unit horizontal tangent directions of steepest ascent and
  /// descent (each up to sign), papers/skin/skin_math.md §5 "Steepest directions".
  Vec3 ascent = Vec3::Zero(), descent = Vec3::Zero();
};

/// All critical points of h(x) = e·x (e unit) on the skin, sorted by height.
/// For each non-bounding mixed cell X the candidates are
/// p = z_X ± |mu| A e with mu² = -w_X / (2 e^T A e), A = P_perp - P_par
/// (papers/skin/skin_math.md §5, s = 1/2), kept if p lies in the cell (within 1e-9 L,
/// cell_distance);
/// points found in two cells (on a shared face) are merged. The index comes
/// from the Gauss curvature sign and sigma (papers/skin/skin_math.md §5 "Index rule").
/// The cells are scanned in blocks on up to `threads` threads (0: every
/// core); the result does not depend on the count. The cells' planes are
/// made for the test and not kept (MixedComplex::planes_into).
std::vector<CriticalPoint> critical_points(const skin::SkinSurface& skin, const Vec3& e, int threads = 1);

/// Counts per kind: [minima, saddles, maxima].
struct MorseCount {
  int minima = 0, saddles = 0, maxima = 0;
  /// #min - #saddle + #max, which equals chi(skin) for a Morse function.
  int euler() const { return minima - saddles + maxima; }
};
MorseCount count_critical_points(const std::vector<CriticalPoint>& cps);

}  // namespace skinmesh::morse
