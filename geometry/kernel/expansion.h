// geometry/kernel/expansion.h: floating-point expansion arithmetic, the exact layer
// under the predicates of geometry/kernel/predicates. Shewchuk, "Adaptive Precision
// Floating-Point Arithmetic and Fast Robust Geometric Predicates" (DCG 18, 1997),
// §2; Dekker (1971) for the split; Knuth, TAOCP vol. 2 §4.2.2 for two-sum.
//
// An *expansion* is an array e[0..n) of doubles whose exact sum is the value it
// represents. Components are sorted by increasing magnitude and are
// nonoverlapping (the lowest set bit of a larger component lies above the
// highest set bit of a smaller one); zero components are removed by every routine
// here ("zero elimination"), so an empty expansion (n = 0) represents 0 and the
// last component carries the sign.
//
// Requirements (read before changing anything):
// * IEEE-754 binary64, round-to-nearest-even, no extended precision (x86-64 SSE2,
//   AArch64). expansion_sum() relies on round-to-even (Shewchuk, Thm 13).
// * No fused multiply-add and no reassociation. The library is compiled with
//   -ffp-contract=off (CMakeLists.txt) and without -ffast-math. The inline
//   error-free transformations below must only be used from translation units
//   compiled the same way (geometry/ and the tests are).
// * No overflow and no underflow of any exact intermediate value. See
//   geometry/kernel/predicates.h for the input range this gives for the predicates.
#pragma once

#include "core/types.h"

#if defined(__clang__)
#pragma clang fp contract(off)
#endif

namespace skinmesh::geometry {

// Error-free transformations ------------------------------------------------

/// x + y == a + b exactly, x = fl(a + b). Knuth's branch-free two-sum (6 flops).
/// Any a, b (no magnitude precondition).
inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double b_virtual = x - a;
  const double a_virtual = x - b_virtual;
  const double b_round = b - b_virtual;
  const double a_round = a - a_virtual;
  y = a_round + b_round;
}

/// x + y == a + b exactly, x = fl(a + b). Dekker's fast two-sum (3 flops).
/// Pre: |a| >= |b| or a == 0.
inline void fast_two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double b_virtual = x - a;
  y = b - b_virtual;
}

/// x + y == a - b exactly, x = fl(a - b). Any a, b.
inline void two_diff(double a, double b, double& x, double& y) {
  x = a - b;
  const double b_virtual = a - x;
  const double a_virtual = x + b_virtual;
  const double b_round = b_virtual - b;
  const double a_round = a - a_virtual;
  y = a_round + b_round;
}

/// Veltkamp/Dekker split: a == hi + lo exactly, each half fitting in 26 bits
/// (plus sign), so products of halves are exact. The factor is 2^27 + 1.
/// Pre: |a| < 2^996 (no overflow of the scaled value).
inline void split(double a, double& hi, double& lo) {
  constexpr double kSplitter = 134217729.0;  // 2^27 + 1
  const double c = kSplitter * a;
  const double big = c - a;
  hi = c - big;
  lo = a - hi;
}

/// x + y == a * b exactly, x = fl(a * b) (Dekker's two-product, 17 flops, no FMA).
/// Pre: no overflow; the low part y exact needs |a*b| well above the underflow
/// threshold (see predicates.h for the admissible input range).
inline void two_product(double a, double b, double& x, double& y) {
  x = a * b;
  double ahi, alo, bhi, blo;
  split(a, ahi, alo);
  split(b, bhi, blo);
  const double err1 = x - ahi * bhi;
  const double err2 = err1 - alo * bhi;
  const double err3 = err2 - ahi * blo;
  y = alo * blo - err3;
}

/// Same as two_product() with b already split into (bhi, blo).
inline void two_product_presplit(double a, double b, double bhi, double blo, double& x, double& y) {
  x = a * b;
  double ahi, alo;
  split(a, ahi, alo);
  const double err1 = x - ahi * bhi;
  const double err2 = err1 - alo * bhi;
  const double err3 = err2 - ahi * blo;
  y = alo * blo - err3;
}

/// x + y == a * a exactly, x = fl(a * a).
inline void two_square(double a, double& x, double& y) {
  x = a * a;
  double ahi, alo;
  split(a, ahi, alo);
  const double err1 = x - ahi * ahi;
  const double err3 = err1 - (ahi + ahi) * alo;  // 2*ahi is exact
  y = alo * alo - err3;
}

// Expansion Operations --------------------------------------------------------
// Every routine returns the number of components written to its output h.
// Inputs are nonoverlapping expansions sorted by increasing magnitude (as
// produced by these routines and by two_sum/two_product, low part first); the
// output is one as well, without zero components. The output must not alias
// an input unless stated.

// Capacities: output lengths are at most elen + 1 (grow), elen + flen (sum),
// 2 * elen (scale), elen (compress).

/// h = e + b. h may alias e. Shewchuk's GROW-EXPANSION with zero elimination.
int grow_expansion(int elen, const double* e, double b, double* h);

/// h = e + f, by merging the components by magnitude, then one pass of
/// two-sums (Shewchuk's FAST-EXPANSION-SUM with zero elimination; needs
/// round-to-even and strongly nonoverlapping inputs, which every routine here
/// produces). h must not alias e or f.
int expansion_sum(int elen, const double* e, int flen, const double* f, double* h);

/// h = e - f (negates f on the fly). h must not alias e or f.
int expansion_diff(int elen, const double* e, int flen, const double* f, double* h);

/// h = b * e (Shewchuk's SCALE-EXPANSION with zero elimination). h must not alias e.
int scale_expansion(int elen, const double* e, double b, double* h);

/// h = e * f. Needs `scratch` of capacity 4 * elen * flen (two work buffers of
/// 2 * elen * flen) plus h of capacity 2 * elen * flen. Cost O(elen^2 * flen):
/// use it on compressed (short) expansions. No aliasing among e, f, h, scratch.
int expansion_product(int elen, const double* e, int flen, const double* f, double* h, double* scratch);

/// h = e with the fewest components: a nonadjacent expansion whose largest
/// component approximates the value to within one ulp (Shewchuk's COMPRESS).
/// h may alias e.
int compress_expansion(int elen, const double* e, double* h);

/// Sign of the value of e (that of its largest component, zero elimination assumed;
/// an expansion with stray zero components is handled too).
Sign expansion_sign(int elen, const double* e);

}  // namespace skinmesh::geometry
