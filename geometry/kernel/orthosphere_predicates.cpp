// geometry/kernel/orthosphere_predicates.cpp: the size and attached tests of
// geometry/kernel/orthosphere_predicates.h as signs of bordered Gram determinants,
// evaluated once with a floating-point running error bound and, if needed,
// exactly with expansions. Derivation: papers/skin/dual_complex.md
// "Exact filtration signs".
//
// Floating point: compiled with -ffp-contract=off and without -ffast-math
// (CMakeLists.txt), like geometry/kernel/predicates.cpp: the error bounds count
// roundings and the exact layer relies on error-free transformations.
#include "geometry/kernel/orthosphere_predicates.h"

#include <array>
#include <cfloat>
#include <cmath>
#include <vector>

#include "core/assert.h"
#include "geometry/kernel/expansion.h"

#if defined(__clang__)
#pragma clang fp contract(off)
#endif

namespace skinmesh::geometry {

namespace {

// Filter Number -----------------------------------------------------------------
//
// A double v with a bound e on |v - V|, V the exact real value of the same
// expression on the exact inputs (running error analysis, Higham §3.3). With
// u = 2^-53, for fl(a op b) = (a op b)(1 + d), |d| <= u, and |a op b| <=
// |v| / (1 - u) <= (1 + 2u)|v|:
//   add/sub:  |v - V| <= e_a + e_b + 2u |v|
//   mul:      |v - V| <= |a| e_b + |b| e_a + e_a e_b + 2u |v|
// (A B - a b = a (B - b) + b (A - a) + (A - a)(B - b)). The bound itself is
// computed in floating point with at most 8 roundings of nonnegative terms, so
// it is multiplied by kInflate = 1 + 16u >= (1 - u)^-9; kTiny covers the
// absolute error of a gradual underflow (never reached by admissible inputs,
// whose nonzero intermediates stay far above 2^-900).
constexpr double kU = DBL_EPSILON / 2;
constexpr double kInflate = 1.0 + 16.0 * kU;
constexpr double kTiny = 0x1p-1000;

struct FNum {
  double v = 0.0;
  double e = 0.0;
  static FNum of(double x) { return {x, 0.0}; }
  static FNum diff(double a, double b) {
    const double v = a - b;
    return {v, (2.0 * kU * std::abs(v) + kTiny) * kInflate};
  }
  friend FNum operator+(const FNum& a, const FNum& b) {
    const double v = a.v + b.v;
    return {v, (((a.e + b.e) + 2.0 * kU * std::abs(v)) + kTiny) * kInflate};
  }
  friend FNum operator-(const FNum& a, const FNum& b) {
    const double v = a.v - b.v;
    return {v, (((a.e + b.e) + 2.0 * kU * std::abs(v)) + kTiny) * kInflate};
  }
  friend FNum operator*(const FNum& a, const FNum& b) {
    const double v = a.v * b.v;
    const double e = (((std::abs(a.v) * b.e + std::abs(b.v) * a.e) + a.e * b.e) + 2.0 * kU * std::abs(v)) + kTiny;
    return {v, e * kInflate};
  }
  // The certified sign, or Zero if the filter cannot decide.
  Sign sign() const {
    if (v > e) return Sign::Positive;
    if (-v > e) return Sign::Negative;
    return Sign::Zero;
  }
};

// Exact Number ------------------------------------------------------------------
//
// An expansion (geometry/kernel/expansion.h), kept compressed. Heap-allocated: only
// the rare uncertain cases get here.
struct ENum {
  std::vector<double> c;  // components, increasing magnitude, no zeros

  static ENum of(double x) {
    ENum r;
    if (x != 0.0) r.c.push_back(x);
    return r;
  }
  static ENum diff(double a, double b) {
    double x, y;
    two_diff(a, b, x, y);
    ENum r;
    if (y != 0.0) r.c.push_back(y);
    if (x != 0.0) r.c.push_back(x);
    return r;
  }
  int n() const { return static_cast<int>(c.size()); }
  void compress() { c.resize(compress_expansion(n(), c.data(), c.data())); }

  friend ENum operator+(const ENum& a, const ENum& b) {
    ENum r;
    r.c.resize(a.c.size() + b.c.size() + 1);
    r.c.resize(expansion_sum(a.n(), a.c.data(), b.n(), b.c.data(), r.c.data()));
    r.compress();
    return r;
  }
  friend ENum operator-(const ENum& a, const ENum& b) {
    ENum r;
    r.c.resize(a.c.size() + b.c.size() + 1);
    r.c.resize(expansion_diff(a.n(), a.c.data(), b.n(), b.c.data(), r.c.data()));
    r.compress();
    return r;
  }
  friend ENum operator*(const ENum& a, const ENum& b) {
    ENum r;
    if (a.c.empty() || b.c.empty()) return r;
    // The shorter factor drives the loop of expansion_product (cost
    // O(flen * (elen + result))).
    const ENum& e = (a.n() >= b.n()) ? a : b;
    const ENum& f = (a.n() >= b.n()) ? b : a;
    const std::size_t cap = 2 * e.c.size() * f.c.size();
    std::vector<double> scratch(2 * cap);
    r.c.resize(cap);
    r.c.resize(expansion_product(e.n(), e.c.data(), f.n(), f.c.data(), r.c.data(), scratch.data()));
    r.compress();
    return r;
  }
  Sign sign() const { return expansion_sign(n(), c.data()); }
};

// Bordered Gram Determinants ----------------------------------------------------

template <class T>
using Matrix4 = std::array<std::array<T, 4>, 4>;

// Determinant of the n x n block a[row..n) x (columns in `cols`), by Laplace
// expansion along the first row (n <= 4: at most 24 products of 4 entries).
template <class T>
T minor_det(const Matrix4<T>& a, int n, int row, unsigned cols) {
  if (row == n - 1) {
    for (int j = 0; j < n; ++j)
      if (cols & (1u << j)) return a[row][j];
  }
  T sum = T::of(0.0);
  bool plus = true;
  for (int j = 0; j < n; ++j) {
    if (!(cols & (1u << j))) continue;
    const T term = a[row][j] * minor_det(a, n, row + 1, cols & ~(1u << j));
    sum = plus ? sum + term : sum - term;
    plus = !plus;
  }
  return sum;
}

template <class T>
T det(const Matrix4<T>& a, int n) {
  return minor_det(a, n, 0, (1u << n) - 1u);
}

// The Gram data of X = {p_0, ..., p_m}: edge vectors e_j = z_{j+1} - z_0,
// G_ij = e_i . e_j and r_j = |e_j|^2 + w_0 - w_{j+1} (papers/skin/skin_math.md
// §2.2: the focus is z_0 + E^T beta with 2 G beta = r).
template <class T>
struct Gram {
  int m = 0;
  std::array<std::array<T, 3>, 3> e;
  Matrix4<T> g;  // G in the top-left m x m block
  std::array<T, 3> r;

  explicit Gram(std::span<const WeightedPoint> x) : m(static_cast<int>(x.size()) - 1) {
    const WeightedPoint& p0 = x[0];
    for (int j = 0; j < m; ++j)
      for (int a = 0; a < 3; ++a) e[j][a] = T::diff(x[j + 1].z[a], p0.z[a]);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j <= i; ++j) {
        g[i][j] = dot(e[i], e[j]);
        g[j][i] = g[i][j];
      }
    for (int j = 0; j < m; ++j) r[j] = g[j][j] + T::diff(p0.w, x[j + 1].w);
  }

  static T dot(const std::array<T, 3>& a, const std::array<T, 3>& b) {
    return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
  }

  // det [[G, r], [r^T, 4 w_0]] = -4 det(G) w_X.
  T size_determinant(double w0) const {
    Matrix4<T> b = g;
    for (int i = 0; i < m; ++i) b[i][m] = b[m][i] = r[i];
    b[m][m] = T::of(4.0 * w0);  // exact: a power-of-two scaling
    return det(b, m + 1);
  }

  // det [[G, c], [r^T, s]] = det(G) (pi_k(z_X) - w_X), with f = z_k - z_0,
  // c_j = e_j . f, s = |f|^2 + w_0 - w_k.
  T attached_determinant(const WeightedPoint& p0, const WeightedPoint& k) const {
    std::array<T, 3> f;
    for (int a = 0; a < 3; ++a) f[a] = T::diff(k.z[a], p0.z[a]);
    Matrix4<T> b = g;
    for (int i = 0; i < m; ++i) {
      b[i][m] = dot(e[i], f);
      b[m][i] = r[i];
    }
    b[m][m] = dot(f, f) + T::diff(p0.w, k.w);
    return det(b, m + 1);
  }
};

template <class T>
Sign size_sign(std::span<const WeightedPoint> x) {
  return -Gram<T>(x).size_determinant(x[0].w).sign();
}

template <class T>
Sign attached_sign(std::span<const WeightedPoint> x, const WeightedPoint& k) {
  return Gram<T>(x).attached_determinant(x[0], k).sign();
}

}  // namespace

Sign focus_weight_sign_exact(std::span<const WeightedPoint> x) {
  SKINMESH_DEBUG_ASSERT(!x.empty() && x.size() <= 4);
  return size_sign<ENum>(x);
}

Sign orthosphere_power_sign_exact(std::span<const WeightedPoint> x, const WeightedPoint& k) {
  SKINMESH_DEBUG_ASSERT(!x.empty() && x.size() <= 3);
  return attached_sign<ENum>(x, k);
}

Sign focus_weight_sign(std::span<const WeightedPoint> x) {
  SKINMESH_DEBUG_ASSERT(!x.empty() && x.size() <= 4);
  const Sign s = size_sign<FNum>(x);
  if (s != Sign::Zero) return s;
  return size_sign<ENum>(x);
}

Sign orthosphere_power_sign(std::span<const WeightedPoint> x, const WeightedPoint& k) {
  SKINMESH_DEBUG_ASSERT(!x.empty() && x.size() <= 3);
  const Sign s = attached_sign<FNum>(x, k);
  if (s != Sign::Zero) return s;
  return attached_sign<ENum>(x, k);
}

}  // namespace skinmesh::geometry
