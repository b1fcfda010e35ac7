// geometry/kernel/orthosphere_predicates.h: exact signs about the orthosphere (focus)
// of a simplex of 1 to 4 weighted points: the sign of its weight w_X (the "size
// test" of the alpha-shape filtration at alpha = 0) and the sign of
// pi_k(z_X) - w_X for a further weighted point k (the "attached test").
// Derivation: papers/skin/dual_complex.md "Exact filtration signs";
// papers/skin/skin_math.md §2.2 for the focus.
//
// Both signs are signs of polynomials in the input centres and weights
// (bordered Gram determinants, multiplied through by the positive Gram
// determinant of the simplex), so they are decided exactly even when the focus
// z_X itself is ill-conditioned (flat or nearly flat simplices: its position
// along the missing direction is 0/0). Layers as in geometry/kernel/predicates.h:
// a floating-point evaluation with a running (dynamic) error bound, then, if
// that cannot certify the sign, the same polynomial with the exact expansions
// of geometry/kernel/expansion.h. No perturbation: Zero is a possible answer and means
// an exact tie.
//
// Admissible inputs: those of geometry/kernel/predicates.h (coordinates zero or of
// magnitude in [1e-40, 1e40], weights in [1e-80, 1e80], finite); then no exact
// intermediate over- or underflows (degree <= 8 in coordinate differences).
#pragma once

#include <span>

#include "core/types.h"
#include "geometry/kernel/weighted_point.h"

namespace skinmesh::geometry {

/// Sign of the focus weight w_X of the simplex X with the given vertices
/// (1 to 4 weighted points, papers/skin/skin_math.md §2.2: the weight of the
/// smallest weighted point orthogonal to every vertex, centred in aff X).
/// Negative iff the balls of X have a common interior point, Zero iff they
/// meet in exactly one point (e.g. two tangent balls). Exact.
/// Pre: 1 <= x.size() <= 4 and the centres are affinely independent
/// (otherwise the result is meaningless). Throws nothing.
Sign focus_weight_sign(std::span<const WeightedPoint> x);

/// Sign of pi_k(z_X) - w_X: Negative iff k is "closer than orthogonal" to the
/// orthosphere (z_X, w_X) of X, i.e. the focus z_X lies strictly on k's side
/// of the bisector (power) hyperplane of X and k; in the dual-complex
/// filtration, X is attached by the coface X u {k}. Zero iff k is orthogonal
/// to the orthosphere (then X u {k} has the same focus). Exact.
/// Pre: 1 <= x.size() <= 3 and the centres of x are affinely independent.
/// Throws nothing.
Sign orthosphere_power_sign(std::span<const WeightedPoint> x, const WeightedPoint& k);

/// The same two signs without the filter (always the exact expansion
/// evaluation). For tests.
Sign focus_weight_sign_exact(std::span<const WeightedPoint> x);
/// See focus_weight_sign_exact().
Sign orthosphere_power_sign_exact(std::span<const WeightedPoint> x, const WeightedPoint& k);

}  // namespace skinmesh::geometry
