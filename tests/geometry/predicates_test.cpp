// tests/geometry/predicates_test.cpp: tests of geometry/kernel/expansion and
// geometry/kernel/predicates. Exact references are computed with __int128 on integer
// (or dyadic, i.e. integer times 2^-k) coordinates, for which the determinants
// are exactly computable; adversarial inputs are nearly degenerate.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "geometry/kernel/expansion.h"
#include "geometry/kernel/predicates.h"

namespace sg = skinmesh::geometry;
using sg::WeightedPoint;
using skinmesh::Index;
using skinmesh::Sign;
using skinmesh::sign_of;
using skinmesh::Vec3;

namespace {

using i128 = __int128;

Sign sign128(i128 v) { return v > 0 ? Sign::Positive : (v < 0 ? Sign::Negative : Sign::Zero); }

// Integer point with integer weight; converted to doubles times 2^-shift
// (weights times 2^-2shift), which scales every determinant by a power of two.
struct IPoint {
  std::int64_t x, y, z, w;
};

WeightedPoint to_wp(const IPoint& p, int shift) {
  const double s = std::ldexp(1.0, -shift);
  return WeightedPoint{Vec3(double(p.x) * s, double(p.y) * s, double(p.z) * s), double(p.w) * s * s};
}
Vec3 to_vec(const IPoint& p, int shift) { return to_wp(p, shift).z; }

// orient3d reference: ((b-a) x (c-a)) . (d-a). Pre: |coordinates| < 2^39.
i128 orient3d_ref(const IPoint& a, const IPoint& b, const IPoint& c, const IPoint& d) {
  const i128 ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
  const i128 vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  const i128 wx = d.x - a.x, wy = d.y - a.y, wz = d.z - a.z;
  return ux * (vy * wz - vz * wy) + uy * (vz * wx - vx * wz) + uz * (vx * wy - vy * wx);
}

// Power test reference D = l_a det3(bcd) - l_b det3(acd) + l_c det3(abd) -
// l_d det3(abc), rows (p - e, |p - e|^2 - w_p + w_e). Pre: |coordinates| < 2^20,
// |weights| < 2^40.
i128 power_ref(const IPoint& a, const IPoint& b, const IPoint& c, const IPoint& d, const IPoint& e) {
  auto rel = [&](const IPoint& p) {
    std::array<i128, 4> r{p.x - e.x, p.y - e.y, p.z - e.z, 0};
    r[3] = r[0] * r[0] + r[1] * r[1] + r[2] * r[2] - (p.w - e.w);
    return r;
  };
  const auto A = rel(a), B = rel(b), C = rel(c), D = rel(d);
  auto det3 = [](const std::array<i128, 4>& p, const std::array<i128, 4>& q, const std::array<i128, 4>& s) {
    return p[0] * (q[1] * s[2] - q[2] * s[1]) - p[1] * (q[0] * s[2] - q[2] * s[0]) + p[2] * (q[0] * s[1] - q[1] * s[0]);
  };
  return A[3] * det3(B, C, D) - B[3] * det3(A, C, D) + C[3] * det3(A, B, D) - D[3] * det3(A, B, C);
}

Sign orient2d_ref(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by, std::int64_t cx,
                  std::int64_t cy) {
  return sign128(i128(bx - ax) * (cy - ay) - i128(by - ay) * (cx - ax));
}

}  // namespace

TEST_SUITE("geometry") {

// Expansion Arithmetic --------------------------------------------------------

TEST_CASE("expansion: two_sum, two_product and two_square are error-free") {
  const unsigned seed = 20240611u;
  INFO("seed " << seed);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::int64_t> mant(-(std::int64_t(1) << 52), std::int64_t(1) << 52);
  std::uniform_int_distribution<int> expo(0, 20);
  for (int t = 0; t < 2000; ++t) {
    // Integers m * 2^k (k <= 20): sums and products fit in __int128.
    // (Random draws are sequenced one per statement so that a seed gives the
    // same numbers with every compiler.)
    const double ma = double(mant(rng)), mb = double(mant(rng));
    const int ea = expo(rng), eb = expo(rng);
    const double a = std::ldexp(ma, ea), b = std::ldexp(mb, eb);
    double x, y;
    sg::two_sum(a, b, x, y);
    CHECK(i128(x) + i128(y) == i128(a) + i128(b));
    sg::two_diff(a, b, x, y);
    CHECK(i128(x) + i128(y) == i128(a) - i128(b));
    const double a2 = std::ldexp(double(mant(rng)), 0), b2 = std::ldexp(double(mant(rng)), 0);
    sg::two_product(a2, b2, x, y);
    CHECK(i128(x) + i128(y) == i128(a2) * i128(b2));
    sg::two_square(a2, x, y);
    CHECK(i128(x) + i128(y) == i128(a2) * i128(a2));
  }
}

TEST_CASE("expansion: sums, products and compression are exact") {
  const unsigned seed = 7u;
  INFO("seed " << seed);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::int64_t> mant(-(std::int64_t(1) << 30), std::int64_t(1) << 30);
  std::uniform_int_distribution<int> expo(0, 30);
  auto to_i128 = [](int n, const double* e) {
    i128 s = 0;
    for (int i = 0; i < n; ++i) s += i128(e[i]);
    return s;
  };
  for (int t = 0; t < 500; ++t) {
    // Two expansions grown from random integers m * 2^k (values < 2^64).
    double e[16], f[16], h[64], g[64], scratch[512];
    int el = 0, fl = 0;
    i128 ev = 0, fv = 0;
    for (int i = 0; i < 6; ++i) {
      const double mv = double(mant(rng));
      const double v = std::ldexp(mv, expo(rng));
      el = sg::grow_expansion(el, e, v, e);
      ev += i128(v);
      const double mu = double(mant(rng));
      const double u = std::ldexp(mu, expo(rng));
      fl = sg::grow_expansion(fl, f, u, f);
      fv += i128(u);
    }
    CHECK(to_i128(el, e) == ev);
    for (int i = 1; i < el; ++i) CHECK(std::abs(e[i - 1]) < std::abs(e[i]));
    int hl = sg::expansion_sum(el, e, fl, f, h);
    CHECK(to_i128(hl, h) == ev + fv);
    hl = sg::expansion_diff(el, e, fl, f, h);
    CHECK(to_i128(hl, h) == ev - fv);
    CHECK(sg::expansion_sign(hl, h) == sign128(ev - fv));
    const int cl = sg::compress_expansion(hl, h, h);
    CHECK(to_i128(cl, h) == ev - fv);
    CHECK(cl <= hl);
    // Product: the values are < 2^62, the product < 2^124.
    const double small = std::ldexp(double(mant(rng)), 2);
    const int sl = sg::scale_expansion(el, e, small, g);
    CHECK(to_i128(sl, g) == ev * i128(small));
    double e2[2], f2[3];
    const int e2l = sg::grow_expansion(0, e2, std::ldexp(double(mant(rng)), 20), e2);
    int f2l = sg::grow_expansion(0, f2, std::ldexp(double(mant(rng)), 30), f2);
    f2l = sg::grow_expansion(f2l, f2, double(mant(rng)), f2);
    const int pl = sg::expansion_product(e2l, e2, f2l, f2, g, scratch);
    CHECK(to_i128(pl, g) == to_i128(e2l, e2) * to_i128(f2l, f2));
  }
  double z[4];
  CHECK(sg::expansion_sign(0, z) == Sign::Zero);
  CHECK(sg::grow_expansion(0, z, 0.0, z) == 0);
}

// Orientation -----------------------------------------------------------------

TEST_CASE("orient2d: sign convention and symmetry") {
  CHECK(sg::orient2d(0, 0, 1, 0, 0, 1) == Sign::Positive);  // counter-clockwise
  CHECK(sg::orient2d(0, 0, 0, 1, 1, 0) == Sign::Negative);
  CHECK(sg::orient2d(0, 0, 1, 1, 2, 2) == Sign::Zero);
  CHECK(sg::orient2d(0.1, 0.1, 0.2, 0.2, 0.3, 0.3) == sg::orient2d_exact(0.1, 0.1, 0.2, 0.2, 0.3, 0.3));
}

TEST_CASE("orient2d: nearly collinear points on an ulp grid (Kettner et al.)") {
  // p = (0.5 + i u, 0.5 + j u), u = 2^-53, against the line through (12, 12)
  // and (24, 24). In units of 2^-53 all coordinates are integers < 2^58.
  const double u = std::ldexp(1.0, -53);
  const std::int64_t half = std::int64_t(1) << 52, k12 = 12 * (std::int64_t(1) << 53),
                     k24 = 24 * (std::int64_t(1) << 53);
  int fast_wrong = 0, total = 0;
  sg::reset_predicate_stats();
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const double px = 0.5 + i * u, py = 0.5 + j * u;
      const Sign ref = orient2d_ref(half + i, half + j, k12, k12, k24, k24);
      CHECK(sg::orient2d(px, py, 12, 12, 24, 24) == ref);
      CHECK(sg::orient2d(12, 12, 24, 24, px, py) == ref);   // cyclic
      CHECK(sg::orient2d(12, 12, px, py, 24, 24) == -ref);  // transposition
      if (sign_of(sg::orient2d_fast(px, py, 12, 12, 24, 24)) != ref) ++fast_wrong;
      ++total;
    }
  MESSAGE("orient2d_fast wrong on " << fast_wrong << " of " << total << " grid points");
  CHECK(fast_wrong > 0);  // the input is adversarial for plain double
  CHECK(sg::predicate_stats().orient2d.exact > 0);
}

TEST_CASE("orient3d: sign convention on the unit tetrahedron") {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
  CHECK(sg::orient3d(a, b, c, d) == Sign::Positive);
  CHECK(sg::orient3d(b, a, c, d) == Sign::Negative);
  CHECK(sg::orient3d(a, b, c, Vec3(0.3, 0.2, 0)) == Sign::Zero);
  CHECK(sg::orient3d(a, b, c, Vec3(5, 7, -1e-30)) == Sign::Negative);
  CHECK(sg::orient3d_fast(a, b, c, d) == doctest::Approx(1.0));
}

TEST_CASE("orient3d: nearly coplanar points against an exact integer reference") {
  const unsigned seed = 12345u;
  INFO("seed " << seed);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::int64_t> big(-(std::int64_t(1) << 37), std::int64_t(1) << 37);
  std::uniform_int_distribution<int> off(-1, 1);
  int fast_wrong = 0, zeros = 0;
  sg::reset_predicate_stats();
  for (int t = 0; t < 3000; ++t) {
    IPoint a{big(rng), big(rng), big(rng), 0}, b{big(rng), big(rng), big(rng), 0}, c{big(rng), big(rng), big(rng), 0};
    // d on (or next to) the plane abc: d = (a + b + 2c) / 4 when divisible,
    // then moved by at most one unit per axis.
    IPoint d{(a.x + b.x + 2 * c.x) / 4 + off(rng), (a.y + b.y + 2 * c.y) / 4 + off(rng),
             (a.z + b.z + 2 * c.z) / 4 + off(rng), 0};
    if (t % 3 == 0) {  // exactly coplanar: d = a + b - c
      d = IPoint{a.x + b.x - c.x, a.y + b.y - c.y, a.z + b.z - c.z, 0};
    }
    const int shift = t % 2 == 0 ? 0 : 40;  // integers, or dyadic fractions
    const Vec3 A = to_vec(a, shift), B = to_vec(b, shift), C = to_vec(c, shift), D = to_vec(d, shift);
    const Sign ref = sign128(orient3d_ref(a, b, c, d));
    if (ref == Sign::Zero) ++zeros;
    REQUIRE(sg::orient3d(A, B, C, D) == ref);
    CHECK(sg::orient3d_exact(A, B, C, D) == ref);
    // Even permutations keep the sign, odd ones flip it.
    CHECK(sg::orient3d(B, C, A, D) == ref);
    CHECK(sg::orient3d(B, A, C, D) == -ref);
    CHECK(sg::orient3d(A, B, D, C) == -ref);
    CHECK(sg::orient3d(D, A, B, C) == -ref);  // 4-cycle: odd
    if (sign_of(sg::orient3d_fast(A, B, C, D)) != ref) ++fast_wrong;
  }
  MESSAGE("orient3d_fast wrong on " << fast_wrong << " of 3000 (" << zeros << " coplanar)");
  CHECK(zeros >= 1000);
  CHECK(fast_wrong > 0);
  CHECK(sg::predicate_stats().orient3d.exact > 0);
}

TEST_CASE("orient3d: filtered result agrees with the exact layer on PDB-like input") {
  // Coordinates with 3 decimals (not dyadic): no integer reference, but the
  // filter must never disagree with the exact layer.
  const unsigned seed = 99u;
  INFO("seed " << seed);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> milli(-50000, 50000);
  auto coord = [&] { return milli(rng) / 1000.0; };
  auto point = [&] {
    const double x = coord(), y = coord(), z = coord();
    return Vec3(x, y, z);
  };
  for (int t = 0; t < 3000; ++t) {
    const Vec3 a = point(), b = point(), c = point();
    // d near the plane: a rounded affine combination.
    Vec3 d = (a + 2.0 * b - c) * 0.5;
    if (t % 2)
      d = Vec3(std::round(d.x() * 1000) / 1000, std::round(d.y() * 1000) / 1000, std::round(d.z() * 1000) / 1000);
    CHECK(sg::orient3d(a, b, c, d) == sg::orient3d_exact(a, b, c, d));
  }
}

// Power Test --------------------------------------------------------------------

TEST_CASE("power_test: hand-computed signs on the unit tetrahedron") {
  // a = 0, b = e_x, c = e_y, d = e_z is positively oriented; with weights 0 the
  // orthosphere is the circumsphere: centre (1/2, 1/2, 1/2), w_T = 3/4.
  const WeightedPoint a{Vec3(0, 0, 0), 0}, b{Vec3(1, 0, 0), 0}, c{Vec3(0, 1, 0), 0}, d{Vec3(0, 0, 1), 0};
  REQUIRE(sg::orient3d(a.z, b.z, c.z, d.z) == Sign::Positive);
  // e at the circumcentre: pi_e(z_T) = 0 < 3/4: conflict.
  CHECK(sg::power_test(a, b, c, d, {Vec3(0.5, 0.5, 0.5), 0}) == Sign::Positive);
  // e far away: no conflict.
  CHECK(sg::power_test(a, b, c, d, {Vec3(10, 10, 10), 0}) == Sign::Negative);
  // e = (1,1,1) is on the circumsphere: Zero; a tiny weight decides.
  CHECK(sg::power_test(a, b, c, d, {Vec3(1, 1, 1), 0}) == Sign::Zero);
  CHECK(sg::power_test(a, b, c, d, {Vec3(1, 1, 1), 1e-300}) == Sign::Positive);
  CHECK(sg::power_test(a, b, c, d, {Vec3(1, 1, 1), -1e-300}) == Sign::Negative);
  // Far away but with a big weight: pi_e(z_T) = |(9.5,9.5,9.5)|^2 - w = 270.75 - w.
  CHECK(sg::power_test(a, b, c, d, {Vec3(10, 10, 10), 271.0}) == Sign::Positive);
  CHECK(sg::power_test(a, b, c, d, {Vec3(10, 10, 10), 270.0}) == Sign::Zero);
  CHECK(sg::power_test(a, b, c, d, {Vec3(10, 10, 10), 269.0}) == Sign::Negative);
  // A weight on a vertex moves the orthocentre: with w_a = 1/2, z_T = (3/4)(1,1,1),
  // w_T = 19/16 and pi_e(z_T) = 3/16 for e = (1,1,1): conflict. (Raising w_a
  // lowers the lifted a; e is across the plane bcd from a, so the hyperplane
  // pivoting about the lifted bcd rises above the lifted e.)
  const WeightedPoint a_heavy{Vec3(0, 0, 0), 0.5};
  CHECK(sg::power_test(a_heavy, b, c, d, {Vec3(1, 1, 1), 0}) == Sign::Positive);
  CHECK(sg::power_test(a_heavy, b, c, d, {Vec3(1, 1, 1), -1.0}) == Sign::Zero);
  // The value of the fast evaluation: D = (w_T - pi_e(z_T)) * orient3d = 3/4 * 1.
  CHECK(sg::power_test_fast(a, b, c, d, {Vec3(0.5, 0.5, 0.5), 0}) == doctest::Approx(0.75));
  // Reversed orientation reverses the sign.
  CHECK(sg::power_test(b, a, c, d, {Vec3(0.5, 0.5, 0.5), 0}) == Sign::Negative);
}

TEST_CASE("power_test: nearly degenerate inputs against an exact integer reference") {
  const unsigned seed = 4242u;
  INFO("seed " << seed);
  std::mt19937_64 rng(seed);
  // Integer points on the sphere x^2 + y^2 + z^2 = 50^2 * 9 = 22500 (many
  // lattice points: e.g. permutations of (0, 90, 120), (50, 100, 100), ...).
  std::vector<IPoint> sphere;
  for (std::int64_t x = -150; x <= 150; ++x)
    for (std::int64_t y = -150; y <= 150; ++y) {
      const std::int64_t r2 = 22500 - x * x - y * y;
      if (r2 < 0) continue;
      const auto z = std::int64_t(std::llround(std::sqrt(double(r2))));
      if (z * z == r2) {
        sphere.push_back({x, y, z, 0});
        if (z) sphere.push_back({x, y, -z, 0});
      }
    }
  REQUIRE(sphere.size() > 50);
  std::uniform_int_distribution<std::size_t> pick(0, sphere.size() - 1);
  std::uniform_int_distribution<std::int64_t> trans(-(std::int64_t(1) << 18), std::int64_t(1) << 18);
  std::uniform_int_distribution<int> nudge(-1, 1);
  int zeros = 0, fast_wrong = 0, done = 0;
  sg::reset_predicate_stats();
  while (done < 3000) {
    IPoint p[5];
    for (auto& q : p) q = sphere[pick(rng)];
    if (orient3d_ref(p[0], p[1], p[2], p[3]) <= 0) std::swap(p[0], p[1]);
    if (orient3d_ref(p[0], p[1], p[2], p[3]) <= 0) continue;
    // Translate (the lift changes, the predicate must not), then nudge e by
    // one unit or its weight by one unit in some trials; weights may be equal
    // nonzero values (still cospherical in the power sense).
    // Scaling by an odd K keeps the points cospherical and makes the
    // translated lifts (~2^40) and 3x3 minors (~2^60) round in double.
    const IPoint t{trans(rng), trans(rng), trans(rng), 0};
    const std::int64_t w0 = done % 4 == 0 ? 1000 : 0, K = done % 5 == 0 ? 1 : 4097;
    for (auto& q : p) q = IPoint{K * q.x + t.x, K * q.y + t.y, K * q.z + t.z, w0};
    if (done % 3 == 1) p[4].w += nudge(rng);
    if (done % 3 == 2) p[4].x += nudge(rng);
    const Sign ref = sign128(power_ref(p[0], p[1], p[2], p[3], p[4]));
    if (ref == Sign::Zero) ++zeros;
    const int shift = done % 2 == 0 ? 0 : 30;
    WeightedPoint w[5];
    for (int i = 0; i < 5; ++i) w[i] = to_wp(p[i], shift);
    REQUIRE(sg::power_test(w[0], w[1], w[2], w[3], w[4]) == ref);
    CHECK(sg::power_test_exact(w[0], w[1], w[2], w[3], w[4]) == ref);
    // Antisymmetry under swapping two of a, b, c, d; invariance under even permutations.
    CHECK(sg::power_test(w[1], w[0], w[2], w[3], w[4]) == -ref);
    CHECK(sg::power_test(w[1], w[2], w[0], w[3], w[4]) == ref);
    if (sign_of(sg::power_test_fast(w[0], w[1], w[2], w[3], w[4])) != ref) ++fast_wrong;
    ++done;
  }
  MESSAGE("power_test_fast wrong on " << fast_wrong << " of 3000 (" << zeros << " exactly cospherical)");
  CHECK(zeros > 500);
  CHECK(fast_wrong > 0);
  CHECK(sg::predicate_stats().power_test.exact > 0);
}

TEST_CASE("power_test: filter agrees with the exact layer on random and PDB-like input") {
  const unsigned seed = 31337u;
  INFO("seed " << seed);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> milli(-30000, 30000);
  std::uniform_real_distribution<double> radius(1.0, 2.0);
  auto coord = [&] { return milli(rng) / 1000.0; };
  for (int t = 0; t < 3000; ++t) {
    WeightedPoint p[5];
    for (auto& q : p) {
      const double r = radius(rng);
      const double x = coord(), y = coord(), z = coord();
      q = WeightedPoint{Vec3(x, y, z), r * r};
    }
    if (sg::orient3d(p[0].z, p[1].z, p[2].z, p[3].z) == Sign::Negative) std::swap(p[0], p[1]);
    if (t % 2 == 0) p[4].z = (p[0].z + p[1].z + p[2].z + p[3].z) * 0.25;
    CHECK(sg::power_test(p[0], p[1], p[2], p[3], p[4]) == sg::power_test_exact(p[0], p[1], p[2], p[3], p[4]));
  }
}

// Simulation of Simplicity ----------------------------------------------------

TEST_CASE("power_test_sos: ties broken by index, equal to an explicit perturbation") {
  // Cube corners are cospherical: every 5-subset has D = 0 with weights 0.
  std::vector<IPoint> cube;
  for (int i = 0; i < 8; ++i) cube.push_back({(i & 1) * 2 - 1, ((i >> 1) & 1) * 2 - 1, ((i >> 2) & 1) * 2 - 1, 0});
  // Large translation so that the lifts are not small integers.
  for (auto& q : cube) q = IPoint{q.x + 1000, q.y - 700, q.z + 300, 0};
  const unsigned seed = 5u;
  INFO("seed " << seed);
  std::mt19937_64 rng(seed);
  std::vector<Index> ids = {3, 17, 4, 250, 11, 9, 100, 42};
  int tested = 0;
  for (int a = 0; a < 8; ++a)
    for (int b = 0; b < 8; ++b)
      for (int c = 0; c < 8; ++c)
        for (int d = 0; d < 8; ++d)
          for (int e = 0; e < 8; ++e) {
            const int v[5] = {a, b, c, d, e};
            bool distinct = true;
            for (int i = 0; i < 5; ++i)
              for (int j = i + 1; j < 5; ++j) distinct = distinct && v[i] != v[j];
            if (!distinct) continue;
            if (orient3d_ref(cube[a], cube[b], cube[c], cube[d]) <= 0) continue;
            REQUIRE(power_ref(cube[a], cube[b], cube[c], cube[d], cube[e]) == 0);
            WeightedPoint w[5];
            for (int i = 0; i < 5; ++i) w[i] = to_wp(cube[v[i]], 0);
            const Sign s = sg::power_test_sos(w[0], w[1], w[2], w[3], w[4], ids[a], ids[b], ids[c], ids[d], ids[e]);
            REQUIRE(s != Sign::Zero);
            // Explicit perturbation: weight + 2^(rank of the index * 8); the
            // cofactors here are at most 48 in absolute value, so each rank
            // dominates the sum of all lower ones (D(eps) is linear in eps).
            IPoint q[5];
            for (int i = 0; i < 5; ++i) {
              int rank = 0;
              for (int j = 0; j < 8; ++j) rank += ids[j] < ids[v[i]];
              q[i] = cube[v[i]];
              q[i].w += std::int64_t(1) << (8 * rank);
            }
            CHECK(s == sign128(power_ref(q[0], q[1], q[2], q[3], q[4])));
            // Antisymmetry (swap a and b) and even permutations.
            CHECK(sg::power_test_sos(w[1], w[0], w[2], w[3], w[4], ids[b], ids[a], ids[c], ids[d], ids[e]) == -s);
            CHECK(sg::power_test_sos(w[1], w[2], w[0], w[3], w[4], ids[b], ids[c], ids[a], ids[d], ids[e]) == s);
            ++tested;
          }
  MESSAGE(tested << " cospherical configurations");
  CHECK(tested > 1000);
  CHECK(sg::predicate_stats().power_test.sos > 0);
}

TEST_CASE("power_test_sos: duplicate centres, the larger weight or index wins") {
  const WeightedPoint a{Vec3(0, 0, 0), 0}, b{Vec3(1, 0, 0), 0}, c{Vec3(0, 1, 0), 0}, d{Vec3(0, 0, 1), 0.3};
  const WeightedPoint e_same = d;
  const WeightedPoint e_heavier{d.z, 0.4}, e_lighter{d.z, 0.2};
  // Equal weights: index order. e has the larger index: e wins (conflict).
  CHECK(sg::power_test_sos(a, b, c, d, e_same, 0, 1, 2, 3, 4) == Sign::Positive);
  CHECK(sg::power_test_sos(a, b, c, d, e_same, 0, 1, 2, 4, 3) == Sign::Negative);
  CHECK(sg::power_test_sos(a, b, c, d, e_same, 4, 1, 2, 3, 0) == Sign::Negative);
  // Different weights: the weight decides whatever the indices.
  CHECK(sg::power_test_sos(a, b, c, d, e_heavier, 0, 1, 2, 4, 3) == Sign::Positive);
  CHECK(sg::power_test_sos(a, b, c, d, e_lighter, 0, 1, 2, 3, 4) == Sign::Negative);
  // A coplanar e on the circumsphere of a coplanar-free tetrahedron: nonzero.
  CHECK(sg::power_test_sos(a, b, c, {Vec3(0, 0, 1), 0}, {Vec3(1, 1, 0), 0}, 0, 1, 2, 3, 4) == Sign::Positive);
  CHECK(sg::power_test_sos(a, b, c, {Vec3(0, 0, 1), 0}, {Vec3(1, 1, 0), 0}, 4, 1, 2, 3, 0) ==
        sg::orient3d(b.z, c.z, Vec3(0, 0, 1), Vec3(1, 1, 0)));
}

}  // TEST_SUITE
