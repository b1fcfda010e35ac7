// tests/geometry/orthosphere_predicates_test.cpp: the exact size and attached
// tests of geometry/kernel/orthosphere_predicates.h against an independent exact
// reference: the focus z_X and weight w_X computed from their definition
// (papers/skin/skin_math.md §2.2: solve 2 G beta = r) in exact big-integer dyadic
// arithmetic (Cramer's rule), on random, cospherical, coplanar, rotated and
// translated inputs.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "geometry/kernel/orthosphere_predicates.h"

using namespace skinmesh;
using geometry::WeightedPoint;

namespace {

// Big integers and dyadic numbers (test reference only) --------------------------

/// Signed integer of arbitrary size: sign and magnitude in base 2^32.
struct BigInt {
  bool neg = false;
  std::vector<std::uint32_t> mag;  // little endian, no leading zero limbs

  static BigInt from_u64(std::uint64_t v, bool negative) {
    BigInt r;
    while (v) r.mag.push_back(static_cast<std::uint32_t>(v)), v >>= 32;
    r.neg = negative && !r.mag.empty();
    return r;
  }
  int sign() const { return mag.empty() ? 0 : (neg ? -1 : 1); }
  void trim() {
    while (!mag.empty() && mag.back() == 0) mag.pop_back();
    if (mag.empty()) neg = false;
  }
  static int cmp_mag(const BigInt& a, const BigInt& b) {
    if (a.mag.size() != b.mag.size()) return a.mag.size() < b.mag.size() ? -1 : 1;
    for (std::size_t i = a.mag.size(); i-- > 0;)
      if (a.mag[i] != b.mag[i]) return a.mag[i] < b.mag[i] ? -1 : 1;
    return 0;
  }
  static BigInt add_mag(const BigInt& a, const BigInt& b) {
    BigInt r;
    std::uint64_t carry = 0;
    for (std::size_t i = 0; i < std::max(a.mag.size(), b.mag.size()) || carry; ++i) {
      const std::uint64_t s = carry + (i < a.mag.size() ? a.mag[i] : 0) + (i < b.mag.size() ? b.mag[i] : 0);
      r.mag.push_back(static_cast<std::uint32_t>(s));
      carry = s >> 32;
    }
    r.trim();
    return r;
  }
  static BigInt sub_mag(const BigInt& a, const BigInt& b) {  // |a| >= |b|
    BigInt r;
    std::int64_t borrow = 0;
    for (std::size_t i = 0; i < a.mag.size(); ++i) {
      std::int64_t d = static_cast<std::int64_t>(a.mag[i]) - borrow - (i < b.mag.size() ? b.mag[i] : 0);
      borrow = d < 0 ? 1 : 0;
      if (d < 0) d += (std::int64_t{1} << 32);
      r.mag.push_back(static_cast<std::uint32_t>(d));
    }
    r.trim();
    return r;
  }
  friend BigInt operator+(const BigInt& a, const BigInt& b) {
    BigInt r;
    if (a.neg == b.neg) {
      r = add_mag(a, b);
      r.neg = a.neg;
    } else if (cmp_mag(a, b) >= 0) {
      r = sub_mag(a, b);
      r.neg = a.neg;
    } else {
      r = sub_mag(b, a);
      r.neg = b.neg;
    }
    r.trim();
    return r;
  }
  friend BigInt operator-(const BigInt& a) {
    BigInt r = a;
    r.neg = !r.neg;
    r.trim();
    return r;
  }
  friend BigInt operator-(const BigInt& a, const BigInt& b) { return a + (-b); }
  friend BigInt operator*(const BigInt& a, const BigInt& b) {
    BigInt r;
    r.mag.assign(a.mag.size() + b.mag.size(), 0);
    for (std::size_t i = 0; i < a.mag.size(); ++i) {
      std::uint64_t carry = 0;
      for (std::size_t j = 0; j < b.mag.size() || carry; ++j) {
        const std::uint64_t cur = r.mag[i + j] + carry + (j < b.mag.size() ? std::uint64_t{a.mag[i]} * b.mag[j] : 0);
        r.mag[i + j] = static_cast<std::uint32_t>(cur);
        carry = cur >> 32;
      }
    }
    r.neg = a.neg != b.neg;
    r.trim();
    return r;
  }
  BigInt shifted(int bits) const {  // * 2^bits, bits >= 0
    BigInt r = *this;
    for (; bits >= 32; bits -= 32) r.mag.insert(r.mag.begin(), 0u);
    if (bits > 0) {
      std::uint32_t carry = 0;
      for (auto& limb : r.mag) {
        const std::uint32_t next = limb >> (32 - bits);
        limb = (limb << bits) | carry;
        carry = next;
      }
      if (carry) r.mag.push_back(carry);
    }
    r.trim();
    return r;
  }
};

/// Exact dyadic number mant * 2^exp (every finite double is one; closed under
/// +, -, *).
struct Dyadic {
  BigInt mant;
  int exp = 0;
  int sign() const { return mant.sign(); }
  static Dyadic align_add(const Dyadic& a, const Dyadic& b, bool subtract) {
    const int e = std::min(a.exp, b.exp);
    const BigInt am = a.mant.shifted(a.exp - e), bm = b.mant.shifted(b.exp - e);
    return {subtract ? am - bm : am + bm, e};
  }
  friend Dyadic operator+(const Dyadic& a, const Dyadic& b) { return align_add(a, b, false); }
  friend Dyadic operator-(const Dyadic& a, const Dyadic& b) { return align_add(a, b, true); }
  friend Dyadic operator*(const Dyadic& a, const Dyadic& b) { return {a.mant * b.mant, a.exp + b.exp}; }
};

/// The exact value of a finite double.
Dyadic exact(double x) {
  if (x == 0.0) return {};
  int e = 0;
  const double m = std::frexp(std::abs(x), &e);  // |x| = m 2^e, m in [0.5, 1)
  return {BigInt::from_u64(static_cast<std::uint64_t>(std::ldexp(m, 53)), x < 0), e - 53};
}

using Mat = std::array<std::array<Dyadic, 3>, 3>;

Dyadic det_n(const Mat& a, int n) {
  if (n == 1) return a[0][0];
  if (n == 2) return a[0][0] * a[1][1] - a[0][1] * a[1][0];
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

/// Reference: the focus of X from its definition (papers/skin/skin_math.md
/// §2.2), z_X = z_0 + E^T beta with 2 G beta = r, solved by Cramer's rule:
/// beta_j = N_j / D with D = det(2G). Returns D and P = D (z_X - z_0) exactly;
/// false if X is affinely dependent (D = 0).
bool reference_focus(const std::vector<WeightedPoint>& x, Dyadic& D, std::array<Dyadic, 3>& P) {
  const int m = static_cast<int>(x.size()) - 1;
  P = {};
  D = exact(1.0);
  if (m == 0) return true;
  Dyadic e[3][3], r[3];
  Mat g2;
  for (int j = 0; j < m; ++j)
    for (int c = 0; c < 3; ++c) e[j][c] = exact(x[j + 1].z[c]) - exact(x[0].z[c]);
  for (int i = 0; i < m; ++i) {
    r[i] = exact(x[0].w) - exact(x[i + 1].w);
    for (int c = 0; c < 3; ++c) r[i] = r[i] + e[i][c] * e[i][c];
    for (int j = 0; j < m; ++j) {
      Dyadic g;
      for (int c = 0; c < 3; ++c) g = g + e[i][c] * e[j][c];
      g2[i][j] = g + g;
    }
  }
  D = det_n(g2, m);
  if (D.sign() == 0) return false;
  for (int j = 0; j < m; ++j) {
    Mat a = g2;
    for (int i = 0; i < m; ++i) a[i][j] = r[i];
    const Dyadic nj = det_n(a, m);
    for (int c = 0; c < 3; ++c) P[c] = P[c] + nj * e[j][c];
  }
  return true;
}

Sign to_sign(int s) { return s > 0 ? Sign::Positive : (s < 0 ? Sign::Negative : Sign::Zero); }

/// Sign of w_X = |P/D|^2 - w_0, i.e. of |P|^2 - w_0 D^2; Zero also for a
/// degenerate X (callers check degenerate() first).
Sign reference_weight_sign(const std::vector<WeightedPoint>& x) {
  Dyadic D;
  std::array<Dyadic, 3> P;
  if (!reference_focus(x, D, P)) return Sign::Zero;
  const Dyadic v = ((P[0] * P[0] + P[1] * P[1]) + P[2] * P[2]) - exact(x[0].w) * D * D;
  return to_sign(v.sign());
}

bool degenerate(const std::vector<WeightedPoint>& x) {
  Dyadic D;
  std::array<Dyadic, 3> P;
  return !reference_focus(x, D, P);
}

/// Sign of pi_k(z_X) - w_X, times D^2: |D (z_0 - z_k) + P|^2 - w_k D^2 - |P|^2 + w_0 D^2.
Sign reference_power_sign(const std::vector<WeightedPoint>& x, const WeightedPoint& k) {
  Dyadic D;
  std::array<Dyadic, 3> P;
  if (!reference_focus(x, D, P)) return Sign::Zero;
  Dyadic v = (exact(x[0].w) - exact(k.w)) * D * D;
  for (int c = 0; c < 3; ++c) {
    const Dyadic q = D * (exact(x[0].z[c]) - exact(k.z[c])) + P[c];
    v = v + q * q - P[c] * P[c];
  }
  return to_sign(v.sign());
}

/// Checks both predicates (filtered and exact-only) against the reference on
/// X and every given further point k (when X has at most 3 points). Returns
/// false without checking if X is affinely dependent (outside the predicates'
/// precondition: rounding can make a lifted corner exactly coplanar).
bool check_against_reference(const std::vector<WeightedPoint>& x, const std::vector<WeightedPoint>& others) {
  if (degenerate(x)) return false;
  const Sign ref_w = reference_weight_sign(x);
  CHECK(geometry::focus_weight_sign(x) == ref_w);
  CHECK(geometry::focus_weight_sign_exact(x) == ref_w);
  if (x.size() > 3) return true;
  for (const WeightedPoint& k : others) {
    const Sign ref_p = reference_power_sign(x, k);
    CHECK(geometry::orthosphere_power_sign(x, k) == ref_p);
    CHECK(geometry::orthosphere_power_sign_exact(x, k) == ref_p);
  }
  return true;
}

Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> g(0, 1);
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  return q.normalized().toRotationMatrix();
}

std::vector<WeightedPoint> moved(std::vector<WeightedPoint> pts, const Eigen::Matrix3d& rot, const Vec3& shift) {
  for (auto& p : pts) p.z = rot * p.z + shift;
  return pts;
}

}  // namespace

TEST_SUITE("geometry") {

TEST_CASE("orthosphere predicates: the reference itself on hand-computed cases") {
  // Two balls of radii 2 and 3 at distance 5 are tangent: w_X = 0; at distance
  // 4 they overlap (w_X < 0), at distance 6 they are apart (w_X > 0).
  for (const auto& [d, expect] :
       {std::pair{5.0, Sign::Zero}, std::pair{4.0, Sign::Negative}, std::pair{6.0, Sign::Positive}}) {
    const std::vector<WeightedPoint> x = {{Vec3(0, 0, 0), 4.0}, {Vec3(d, 0, 0), 9.0}};
    CHECK(reference_weight_sign(x) == expect);
    CHECK(geometry::focus_weight_sign(x) == expect);
  }
  // Unit weights at the corners of a unit square: the edge's focus is its
  // midpoint with w = 1/4 - 1; the opposite corners have pi = 1 + 1/4 - 1 > w,
  // a point at the midpoint with weight 1 has pi = -1 < w.
  const std::vector<WeightedPoint> edge = {{Vec3(0, 0, 0), 1.0}, {Vec3(1, 0, 0), 1.0}};
  CHECK(reference_power_sign(edge, {Vec3(0, 1, 0), 1.0}) == Sign::Positive);
  CHECK(reference_power_sign(edge, {Vec3(0.5, 0, 0), 1.0}) == Sign::Negative);
  CHECK(geometry::orthosphere_power_sign(edge, {Vec3(0, 1, 0), 1.0}) == Sign::Positive);
  CHECK(geometry::orthosphere_power_sign(edge, {Vec3(0.5, 0, 0), 1.0}) == Sign::Negative);
}

TEST_CASE("orthosphere predicates agree with exact rational arithmetic on random inputs") {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> coord(-3, 3), weight(-1, 6);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 1 + trial % 4;
    std::vector<WeightedPoint> x, others;
    for (int i = 0; i < n; ++i) x.push_back({Vec3(coord(rng), coord(rng), coord(rng)), weight(rng)});
    for (int i = 0; i < 3; ++i) others.push_back({Vec3(coord(rng), coord(rng), coord(rng)), weight(rng)});
    check_against_reference(x, others);
  }
}

TEST_CASE("orthosphere predicates: exact ties on cospherical, concyclic and tangent inputs") {
  // Integer points on the sphere |z| = 5 with equal weights: the focus of every
  // subset is in the plane of the subset, and a further point on the same
  // circle is orthogonal to it (sign Zero).
  const std::vector<Vec3> circle = {Vec3(5, 0, 0),  Vec3(3, 4, 0),  Vec3(0, 5, 0), Vec3(-4, 3, 0),
                                    Vec3(-5, 0, 0), Vec3(0, -5, 0), Vec3(4, -3, 0)};
  std::vector<WeightedPoint> pts;
  for (const Vec3& c : circle) pts.push_back({c, 2.0});
  for (std::size_t a = 0; a < pts.size(); ++a)
    for (std::size_t b = a + 1; b < pts.size(); ++b)
      for (std::size_t c = b + 1; c < pts.size(); ++c) {
        const std::vector<WeightedPoint> x = {pts[a], pts[b], pts[c]};
        for (std::size_t k = 0; k < pts.size(); ++k) {
          if (k == a || k == b || k == c) continue;
          CHECK(reference_power_sign(x, pts[k]) == Sign::Zero);
          CHECK(geometry::orthosphere_power_sign(x, pts[k]) == Sign::Zero);
        }
      }
  // A tetrahedron of cospherical integer points (|z| = 5) with weight 25: the
  // orthosphere is centred at the origin with weight 25 - 25 = 0.
  const std::vector<WeightedPoint> tet = {
      {Vec3(5, 0, 0), 25.0}, {Vec3(0, 3, 4), 25.0}, {Vec3(-3, 0, 4), 25.0}, {Vec3(0, 0, -5), 25.0}};
  CHECK(reference_weight_sign(tet) == Sign::Zero);
  CHECK(geometry::focus_weight_sign(tet) == Sign::Zero);
  // Three balls meeting in exactly one point: radii 5 from (5,0,0), (0,5,0),
  // (0,0,5)... shifted so that the common point is the origin of the triangle
  // plane only if it is the focus: centres (3,4,0), (-3,4,0), (0,-5,0) on
  // |z| = 5 with weight 25 meet exactly at the origin, their plane's focus.
  const std::vector<WeightedPoint> tri = {{Vec3(3, 4, 0), 25.0}, {Vec3(-3, 4, 0), 25.0}, {Vec3(0, -5, 0), 25.0}};
  CHECK(reference_weight_sign(tri) == Sign::Zero);
  CHECK(geometry::focus_weight_sign(tri) == Sign::Zero);
  // Perturbing one weight by one ulp breaks the tie, in the right direction.
  std::vector<WeightedPoint> tri_up = tri, tri_down = tri;
  tri_up[2].w = std::nextafter(25.0, 30.0);
  tri_down[2].w = std::nextafter(25.0, 0.0);
  CHECK(reference_weight_sign(tri_up) == Sign::Negative);
  CHECK(geometry::focus_weight_sign(tri_up) == Sign::Negative);
  CHECK(reference_weight_sign(tri_down) == Sign::Positive);
  CHECK(geometry::focus_weight_sign(tri_down) == Sign::Positive);
}

TEST_CASE("orthosphere predicates: rotated and translated flat and cospherical configurations") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-1e-3, 1e-3);
  // A planar ring of 6 concyclic centres (radius 2) with radius-sqrt(w) balls
  // near the threshold where the ring closes: rotated, its tetrahedra are
  // slivers whose focus is ill-conditioned, and the triangles' further vertices
  // are nearly orthogonal to their orthospheres.
  for (int trial = 0; trial < 40; ++trial) {
    const Eigen::Matrix3d rot = random_rotation(rng);
    const Vec3 shift = (trial % 2 == 0) ? Vec3(1e6, -1e6, 1e6) : Vec3::Zero();
    std::vector<WeightedPoint> ring;
    const double w = 4.0 * (1.0 + jitter(rng));
    for (int i = 0; i < 6; ++i) {
      const double t = 2 * M_PI * i / 6;
      ring.push_back({Vec3(2 * std::cos(t), 2 * std::sin(t), 0), w});
    }
    ring = moved(ring, rot, shift);
    check_against_reference({ring[0], ring[1], ring[3], ring[4]}, {});
    check_against_reference({ring[0], ring[2], ring[4], ring[5]}, {});
    check_against_reference({ring[0], ring[2], ring[4]}, {ring[1], ring[3], ring[5]});
    check_against_reference({ring[0], ring[3]}, {ring[1], ring[2], ring[4]});
    check_against_reference({ring[1]}, {ring[0], ring[4]});
  }
  // Integer cospherical points rotated: the tie is lost to rounding, but the
  // predicates must still give the sign of the rounded input exactly.
  for (int trial = 0; trial < 40; ++trial) {
    const Eigen::Matrix3d rot = random_rotation(rng);
    const Vec3 shift = (trial % 2 == 0) ? Vec3(-1e6, 3e5, 1e6) : Vec3(0.5, 0.25, 0);
    const std::vector<WeightedPoint> sphere = moved({{Vec3(5, 0, 0), 25.0},
                                                     {Vec3(0, 3, 4), 25.0},
                                                     {Vec3(-3, 0, 4), 25.0},
                                                     {Vec3(0, 0, -5), 25.0},
                                                     {Vec3(0, -4, 3), 25.0},
                                                     {Vec3(4, 3, 0), 25.0}},
                                                    rot, shift);
    check_against_reference({sphere[0], sphere[1], sphere[2], sphere[3]}, {});
    check_against_reference({sphere[0], sphere[1], sphere[2]}, {sphere[3], sphere[4], sphere[5]});
    check_against_reference({sphere[3], sphere[4]}, {sphere[0], sphere[5]});
  }
  // Coplanar: a square's corners with a nearly flat tetrahedron (one corner
  // lifted by 1e-12 Å), rotated; far from the origin rounding may make it
  // exactly flat (then it is skipped), near the origin it stays a sliver.
  int slivers = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d rot = random_rotation(rng);
    const std::vector<WeightedPoint> sq =
        moved({{Vec3(0, 0, 0), 0.5}, {Vec3(1, 0, 0), 0.5}, {Vec3(1, 1, 1e-12), 0.5}, {Vec3(0, 1, 0), 0.5}}, rot,
              trial % 2 == 0 ? Vec3(1e6, 1e6, 1e6) : Vec3::Zero());
    slivers += check_against_reference(sq, {}) ? 1 : 0;
    check_against_reference({sq[0], sq[1], sq[2]}, {sq[3]});
    check_against_reference({sq[0], sq[2]}, {sq[1], sq[3]});
  }
  CHECK(slivers >= 10);
}

}  // TEST_SUITE
