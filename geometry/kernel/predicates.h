// geometry/kernel/predicates.h: exact geometric predicates (orientation in 2D and 3D, the
// regular-triangulation power test, and its symbolically perturbed version).
// papers/skin/skin_math.md §2.1 and §9; papers/conventions.md §3 "Predicates
// decide; constructions estimate".
//
// Every robust predicate runs in layers, like geogram's side4h_3d_SOS:
//   1. a floating-point filter: the determinant in double plus a semi-static
//      error bound (a constant times the "permanent", i.e. the same polynomial
//      evaluated on absolute values), derived in predicates.cpp;
//   2. if the filter cannot certify the sign, an exact evaluation with the
//      floating-point expansions of geometry/kernel/expansion.h (Shewchuk 1997);
//   3. power_test_sos() only: if the exact determinant is zero, Simulation of
//      Simplicity (Edelsbrunner & Mücke 1990) on the weights decides.
// The `_fast` functions are the plain double evaluation, for benchmarks only.
//
// Admissible inputs (the exactness claims hold under this condition, which keeps
// every exact intermediate away from overflow and underflow): every coordinate
// (Å) is zero or has magnitude in [1e-40, 1e40] and every weight (Å²) is zero or
// has magnitude in [1e-80, 1e80]. Inputs must be finite. Molecules (|x| < 1e4 Å,
// coordinates with a few decimals) are far inside.
//
// Counters: each thread counts its own predicate calls (filter), exact
// evaluations and SoS decisions in plain thread_local counters, read with
// predicate_stats(). They are statistics, not state: nothing depends on them.
#pragma once

#include <cstdint>

#include "core/types.h"
#include "geometry/kernel/weighted_point.h"

namespace skinmesh::geometry {

// Predicate Statistics --------------------------------------------------------

/// How often one predicate ran each layer: `calls` = every call (the filter
/// always runs), `exact` = the filter was uncertain and expansions were used,
/// `sos` = the exact value was zero and symbolic perturbation decided.
struct PredicateCounters {
  std::uint64_t calls = 0;
  std::uint64_t exact = 0;
  std::uint64_t sos = 0;
};

/// Counters of every robust predicate of this file, for the calling thread.
struct PredicateStats {
  PredicateCounters orient2d;
  PredicateCounters orient3d;
  PredicateCounters power_test;  ///< power_test() and power_test_sos() together
};

/// The calling thread's predicate counters since the thread started or since
/// the last reset_predicate_stats(). Throws nothing.
PredicateStats predicate_stats();

/// Sets the calling thread's predicate counters to zero. Throws nothing.
void reset_predicate_stats();

/// The calling thread's predicate counters, which are set to zero. With
/// add_predicate_stats(), a parallel loop moves its blocks' counts to the
/// thread that called it, so that thread's statistics do not depend on the
/// thread count. Throws nothing.
PredicateStats take_predicate_stats();

/// Adds d to the calling thread's predicate counters. Throws nothing.
void add_predicate_stats(const PredicateStats& d);

// Orientation Predicates ----------------------------------------------------------

/// Sign of the 2D cross product (b - a) x (c - a): Positive iff c lies to the
/// left of the directed line ab (a, b, c counter-clockwise), Negative iff to the
/// right, Zero iff the three points are collinear. Exact. Coordinates in any
/// length unit. Throws nothing. Shewchuk 1997 §4 (orient2d), own derivation.
Sign orient2d(double ax, double ay, double bx, double by, double cx, double cy);

/// Sign of ((b - a) x (c - a)) . (d - a), i.e. six times the signed volume of
/// the tetrahedron abcd: Positive iff d lies on the side of the plane abc into
/// which the normal (b - a) x (c - a) points. The tetrahedron (a, b, c, d) is
/// *positively oriented* iff this is Positive (e.g. a = 0, b = e_x, c = e_y,
/// d = e_z). Zero iff the points are coplanar: no perturbation. Exact. Throws
/// nothing.
Sign orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// orient3d() without the filter: always the exact expansion evaluation. For
/// tests and timings. Does not touch the counters.
Sign orient3d_exact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// orient2d() without the filter (exact expansion evaluation). For tests.
Sign orient2d_exact(double ax, double ay, double bx, double by, double cx, double cy);

/// Plain double evaluation of (b - a) x (c - a): NOT robust (the sign can be
/// wrong for nearly collinear points). For benchmarks.
double orient2d_fast(double ax, double ay, double bx, double by, double cx, double cy);

/// Plain double evaluation of ((b - a) x (c - a)) . (d - a) (Å³): NOT robust.
/// For benchmarks and for estimates (volumes) where a wrong sign is harmless.
double orient3d_fast(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// Power Test --------------------------------------------------------------------

/// Regular-triangulation "in-sphere" test of e against the tetrahedron abcd.
/// Pre: orient3d(a.z, b.z, c.z, d.z) == Positive (for a negatively oriented
/// tetrahedron the result is reversed; for a flat one it is meaningless).
/// Returns Positive iff e is in conflict with abcd, i.e. pi_e(z_T) < w_T where
/// z_T is the orthocentre (the point with equal power distance w_T to a, b, c,
/// d); equivalently the lifted point (e.z, |e.z|² - e.w) lies strictly below the
/// hyperplane of R^4 through the lifted a, b, c, d. Negative iff e is strictly
/// outside (its lift above), Zero iff e is orthogonal to the orthosphere.
/// Exact. The determinant: D = -det[[x_i, y_i, z_i, |z_i|² - w_i, 1]] (rows i =
/// a, b, c, d, e) = (w_T - pi_e(z_T)) * orient3d(a, b, c, d); see predicates.cpp.
/// papers/skin/skin_math.md §2.1 (tetrahedron test). Throws nothing.
Sign power_test(const WeightedPoint& a, const WeightedPoint& b, const WeightedPoint& c, const WeightedPoint& d,
                const WeightedPoint& e);

/// power_test() without the filter (exact expansion evaluation). For tests.
Sign power_test_exact(const WeightedPoint& a, const WeightedPoint& b, const WeightedPoint& c, const WeightedPoint& d,
                      const WeightedPoint& e);

/// Plain double evaluation of the power-test determinant D (see power_test()),
/// translated to e: NOT robust. For benchmarks.
double power_test_fast(const WeightedPoint& a, const WeightedPoint& b, const WeightedPoint& c, const WeightedPoint& d,
                       const WeightedPoint& e);

/// power_test() with Simulation of Simplicity on the weights: the point with
/// index i gets weight w_i + eps_i with 0 < eps_i infinitesimal and
/// eps_i >> eps_j whenever i > j (e.g. eps_i = eps^(N - i)): a larger index
/// means a (symbolically) larger weight, so ties are broken by index order; in
/// particular two points with equal centre and equal weight: the one with the
/// larger index wins (the other is redundant). Pre: the indices are pairwise
/// distinct and identify the points consistently across calls;
/// orient3d(a, b, c, d) == Positive. Never returns Zero. (The value is the
/// sign of the perturbed determinant D(eps), antisymmetric in a, b, c, d: for
/// a negatively oriented abcd it is reversed; if all five 4-subsets are flat it
/// is undefined and an assertion fires.)
///
/// Only the lifted coordinate is perturbed. Rationale (Devillers & Teillaud,
/// "Perturbations for Delaunay and weighted Delaunay 3D triangulations", CGAL):
/// with the centres untouched, no facet of the lower hull of the perturbed
/// lifted points is ever vertical, so the regular triangulation built with this
/// predicate never contains a flat tetrahedron, even for exactly coplanar or
/// cospherical inputs, and the decisions need only orient3d of 4-subsets
/// (the cofactors of the lifting column), derived in predicates.cpp.
/// Throws nothing.
Sign power_test_sos(const WeightedPoint& a, const WeightedPoint& b, const WeightedPoint& c, const WeightedPoint& d,
                    const WeightedPoint& e, Index ia, Index ib, Index ic, Index id, Index ie);

}  // namespace skinmesh::geometry
