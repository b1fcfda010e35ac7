// geometry/kernel/predicates.cpp: filters, exact layers and SoS of geometry/kernel/predicates.h.
//
// Floating point: this file must be compiled without fused multiply-add
// (-ffp-contract=off, set for the whole library in CMakeLists.txt) and without
// -ffast-math: an FMA in a filter changes its rounding pattern (the error bounds
// below count roundings) and an FMA inside two_product() breaks the exact layer.
#include "geometry/kernel/predicates.h"

#include <algorithm>
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

// Error Bounds of the Filters -------------------------------------------------
//
// Notation (Higham, "Accuracy and Stability of Numerical Algorithms", §3.1):
// u = 2^-53 is the unit roundoff; gamma_k = k u / (1 - k u). Every rounded
// operation multiplies its exact result by (1 + delta), |delta| <= u.
//
// Lemma. Let a filter compute a polynomial P of the input differences as a
// tree of +, -, * in which every monomial of P (expanded, coefficients +-1)
// passes through at most k roundings, counting the rounding of each input
// difference once per occurrence in the monomial. Then
//     |fl(P) - P| <= gamma_k * Perm(P),
// where Perm(P) is the sum of the absolute values of the expanded monomials
// evaluated at the exact differences (Higham Lemma 3.1 applied monomial-wise).
// The filter also computes Perm in floating point, from the rounded differences,
// with the same tree on absolute values; if that computation has j roundings
// per monomial and the monomials have degree g in the differences, then
// Perm(P) <= (1 - u)^-(g + j) * fl(Perm). The bound used is therefore
//     B = c * fl(Perm),  c >= gamma_k * (1 - u)^-(g + j) * (1 + u),
// the last factor for the rounding of the product c * fl(Perm) itself; and
// |fl(P)| > B certifies sign(fl(P)) == sign(P). The constants below are
// first-order exact with a generous second-order term. The lemma assumes no
// underflow or overflow, which the admissible input range of predicates.h
// guarantees (products of up to five nonzero differences stay in [2^-925, 2^665]).
namespace {

constexpr double kU = DBL_EPSILON / 2;  // unit roundoff 2^-53

// orient2d: P = (bx-ax)(cy-ay) - (by-ay)(cx-ax). Per monomial: 2 differences,
// 1 product, 1 subtraction: k = 4. Perm: g = 2, j = 2 (product, sum).
// c >= 4u (1 + 4u)(1 + 4u)(1 + u) ~= 4u (1 + 9u).
constexpr double kOrient2dBound = (4.0 + 64.0 * kU) * kU;

// orient3d: with u = b-a, v = c-a, w = d-a,
//   P = ux (vy wz - vz wy) + uy (vz wx - vx wz) + uz (vx wy - vy wx),
// evaluated as (t1 + t2) + t3. Per monomial: 3 differences, 1 product in the
// minor, 1 subtraction, 1 product by ux, 2 additions: k = 8. Perm:
// g = 3, j = 5 (minor product, minor sum, product, 2 sums).
// c >= 8u (1 + 8u)(1 + 8u)(1 + u) ~= 8u (1 + 17u).
constexpr double kOrient3dBound = (8.0 + 256.0 * kU) * kU;

// power test (translated to e; see "Power Test Determinant" below):
//   l_p = ((px'^2 + py'^2) + pz'^2) - (w_p - w_e),      p' = p - e,
//   m_pq = px' qy' - qx' py',
//   det3(p,q,s) = (pz' m_qs - qz' m_ps) + sz' m_pq,
//   D = ((l_a det3(bcd) - l_b det3(acd)) + l_c det3(abd)) - l_d det3(abc).
// Per monomial: l contributes at most 6 roundings (2 differences, 1 square,
// 3 sums/subtractions; the weight term has 2), det3 at most 8 (1 difference for
// z, 2 differences + 1 product + 1 subtraction in the minor, 1 product, 2 sums),
// then 1 product l*det3 and 3 sums: k = 6 + 8 + 1 + 3 = 18. Perm: g = 5
// (two differences in l, three in det3), j = 13 (square + 3 sums in l; product
// + sum in the minor, product, 2 sums in det3; product; 3 sums).
// c >= 18u (1 + 18u)(1 + 18u)(1 + u) ~= 18u (1 + 37u).
constexpr double kPowerTestBound = (18.0 + 1024.0 * kU) * kU;

thread_local PredicateStats tl_stats;

}  // namespace

PredicateStats predicate_stats() { return tl_stats; }

void reset_predicate_stats() { tl_stats = PredicateStats{}; }

PredicateStats take_predicate_stats() {
  const PredicateStats s = tl_stats;
  tl_stats = PredicateStats{};
  return s;
}

void add_predicate_stats(const PredicateStats& d) {
  auto add = [](PredicateCounters& a, const PredicateCounters& b) {
    a.calls += b.calls;
    a.exact += b.exact;
    a.sos += b.sos;
  };
  add(tl_stats.orient2d, d.orient2d);
  add(tl_stats.orient3d, d.orient3d);
  add(tl_stats.power_test, d.power_test);
}

// Floating-Point Filters ------------------------------------------------------
namespace {

// Each filter returns the certified sign, or Zero if it cannot certify one.

Sign orient2d_filter(double ax, double ay, double bx, double by, double cx, double cy) {
  const double left = (bx - ax) * (cy - ay);
  const double right = (by - ay) * (cx - ax);
  const double det = left - right;
  const double bound = kOrient2dBound * (std::abs(left) + std::abs(right));
  if (det > bound) return Sign::Positive;
  if (-det > bound) return Sign::Negative;
  return Sign::Zero;
}

Sign orient3d_filter(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double ux = b.x() - a.x(), uy = b.y() - a.y(), uz = b.z() - a.z();
  const double vx = c.x() - a.x(), vy = c.y() - a.y(), vz = c.z() - a.z();
  const double wx = d.x() - a.x(), wy = d.y() - a.y(), wz = d.z() - a.z();
  const double p1 = vy * wz, q1 = vz * wy;
  const double p2 = vz * wx, q2 = vx * wz;
  const double p3 = vx * wy, q3 = vy * wx;
  const double det = (ux * (p1 - q1) + uy * (p2 - q2)) + uz * (p3 - q3);
  const double perm = (std::abs(ux) * (std::abs(p1) + std::abs(q1)) + std::abs(uy) * (std::abs(p2) + std::abs(q2))) +
                      std::abs(uz) * (std::abs(p3) + std::abs(q3));
  const double bound = kOrient3dBound * perm;
  if (det > bound) return Sign::Positive;
  if (-det > bound) return Sign::Negative;
  return Sign::Zero;
}

// Power test filter: returns Sign of D (Positive = conflict for positively
// oriented abcd), Zero if uncertain. `value` receives fl(D).
Sign power_test_filter(const WeightedPoint& a, const WeightedPoint& b, const WeightedPoint& c, const WeightedPoint& d,
                       const WeightedPoint& e, double* value = nullptr) {
  const Vec3& ez = e.z;
  const double ax = a.z.x() - ez.x(), ay = a.z.y() - ez.y(), az = a.z.z() - ez.z();
  const double bx = b.z.x() - ez.x(), by = b.z.y() - ez.y(), bz = b.z.z() - ez.z();
  const double cx = c.z.x() - ez.x(), cy = c.z.y() - ez.y(), cz = c.z.z() - ez.z();
  const double dx = d.z.x() - ez.x(), dy = d.z.y() - ez.y(), dz = d.z.z() - ez.z();
  const double wa = a.w - e.w, wb = b.w - e.w, wc = c.w - e.w, wd = d.w - e.w;

  // Lifted coordinates relative to e and their permanents.
  const double sa = (ax * ax + ay * ay) + az * az;
  const double sb = (bx * bx + by * by) + bz * bz;
  const double sc = (cx * cx + cy * cy) + cz * cz;
  const double sd = (dx * dx + dy * dy) + dz * dz;
  const double la = sa - wa, lb = sb - wb, lc = sc - wc, ld = sd - wd;
  const double pla = sa + std::abs(wa), plb = sb + std::abs(wb);
  const double plc = sc + std::abs(wc), pld = sd + std::abs(wd);

  // 2x2 minors in (x, y) and their permanents.
  const double ab1 = ax * by, ab2 = bx * ay;
  const double ac1 = ax * cy, ac2 = cx * ay;
  const double ad1 = ax * dy, ad2 = dx * ay;
  const double bc1 = bx * cy, bc2 = cx * by;
  const double bd1 = bx * dy, bd2 = dx * by;
  const double cd1 = cx * dy, cd2 = dx * cy;
  const double mab = ab1 - ab2, mac = ac1 - ac2, mad = ad1 - ad2;
  const double mbc = bc1 - bc2, mbd = bd1 - bd2, mcd = cd1 - cd2;
  const double pab = std::abs(ab1) + std::abs(ab2), pac = std::abs(ac1) + std::abs(ac2);
  const double pad = std::abs(ad1) + std::abs(ad2), pbc = std::abs(bc1) + std::abs(bc2);
  const double pbd = std::abs(bd1) + std::abs(bd2), pcd = std::abs(cd1) + std::abs(cd2);

  // 3x3 determinants det3(p,q,s) = pz m_qs - qz m_ps + sz m_pq.
  const double bcd = (bz * mcd - cz * mbd) + dz * mbc;
  const double acd = (az * mcd - cz * mad) + dz * mac;
  const double abd = (az * mbd - bz * mad) + dz * mab;
  const double abc = (az * mbc - bz * mac) + cz * mab;
  const double aaz = std::abs(az), abz = std::abs(bz), acz = std::abs(cz), adz = std::abs(dz);
  const double pbcd = (abz * pcd + acz * pbd) + adz * pbc;
  const double pacd = (aaz * pcd + acz * pad) + adz * pac;
  const double pabd = (aaz * pbd + abz * pad) + adz * pab;
  const double pabc = (aaz * pbc + abz * pac) + acz * pab;

  const double det = ((la * bcd - lb * acd) + lc * abd) - ld * abc;
  const double perm = ((pla * pbcd + plb * pacd) + plc * pabd) + pld * pabc;
  if (value) *value = det;
  const double bound = kPowerTestBound * perm;
  if (det > bound) return Sign::Positive;
  if (-det > bound) return Sign::Negative;
  return Sign::Zero;
}

}  // namespace

// Exact Layer -----------------------------------------------------------------
//
// The exact layer works on the raw input coordinates (no translation, whose
// differences would not be exact doubles). With M_pq = px qy - qx py (exact,
// <= 4 components), the 3x3 minor
//   N(p,q,s) = det[[px, py, 1], [qx, qy, 1], [sx, sy, 1]] = M_qs - M_ps + M_pq
// (<= 12 components) is orient2d(p, q, s), and expanding
// det[[p, 1], [q, 1], [s, 1], [t, 1]] (rows (x, y, z, 1)) along the z column gives
//   det[[p,1],[q,1],[s,1],[t,1]] = pz N(qst) - qz N(pst) + sz N(pqt) - tz N(pqs).
// Subtracting row p from the others shows det[[p,1],...] = -det[b-a; c-a; d-a]
// for (p,q,s,t) = (a,b,c,d), hence
//   orient3d(p,q,s,t) = -pz N(qst) + qz N(pst) - sz N(pqt) + tz N(pqs)
// (<= 96 components). Check: p = 0, q = e_x, s = e_y, t = e_z gives N(pqs) = 1, 1.
namespace {

// Exact orient2d/orient3d minors of up to five points, shared between the five
// 4-subsets of the power test.
class ExactMinors {
 public:
  ExactMinors(const Vec3* const* p, int n) : p_(p) {
    for (int i = 0; i < n; ++i) {
      for (int j = i + 1; j < n; ++j) {
        double x1, x0, y1, y0;
        two_product(p[i]->x(), p[j]->y(), x1, x0);
        two_product(p[j]->x(), p[i]->y(), y1, y0);
        const double e[2] = {x0, x1};
        const double f[2] = {y0, y1};
        mlen_[i][j] = expansion_diff(2, e, 2, f, m_[i][j]);
      }
    }
    for (int k = 2; k < n; ++k)
      for (int j = 1; j < k; ++j)
        for (int i = 0; i < j; ++i) {
          // N(i,j,k) = M_jk - M_ik + M_ij
          double t[8];
          const int tl = expansion_diff(mlen_[j][k], m_[j][k], mlen_[i][k], m_[i][k], t);
          const int id = triple_id(i, j, k);
          nlen_[id] = expansion_sum(tl, t, mlen_[i][j], m_[i][j], nm_[id]);
        }
  }

  // orient3d(p[i0], p[i1], p[i2], p[i3]) exactly, i0 < i1 < i2 < i3; returns the
  // length (<= 96) of the expansion written to out.
  int orient3d(int i0, int i1, int i2, int i3, double* out) const {
    double s0[24], s1[24], s2[24], s3[24], u[48], v[48];
    const int n0 = scale(triple_id(i1, i2, i3), p_[i0]->z(), s0);  // pz N(qst)
    const int n1 = scale(triple_id(i0, i2, i3), p_[i1]->z(), s1);  // qz N(pst)
    const int n2 = scale(triple_id(i0, i1, i3), p_[i2]->z(), s2);  // sz N(pqt)
    const int n3 = scale(triple_id(i0, i1, i2), p_[i3]->z(), s3);  // tz N(pqs)
    const int nu = expansion_diff(n1, s1, n0, s0, u);              // qz N(pst) - pz N(qst)
    const int nv = expansion_diff(n3, s3, n2, s2, v);              // tz N(pqs) - sz N(pqt)
    return expansion_sum(nu, u, nv, v, out);
  }

  // orient2d of p[i0], p[i1], p[i2] in (x, y), i0 < i1 < i2.
  Sign orient2d_sign(int i0, int i1, int i2) const {
    const int id = triple_id(i0, i1, i2);
    return expansion_sign(nlen_[id], nm_[id]);
  }

 private:
  // Combinatorial number system: a bijection from {i < j < k} within 0..4 to 0..9.
  static int triple_id(int i, int j, int k) { return k * (k - 1) * (k - 2) / 6 + j * (j - 1) / 2 + i; }
  int scale(int id, double z, double* h) const { return scale_expansion(nlen_[id], nm_[id], z, h); }

  const Vec3* const* p_;
  double m_[5][5][4];  // M_ij, i < j
  int mlen_[5][5] = {};
  double nm_[10][12];  // N(i,j,k) by triple_id
  int nlen_[10] = {};
};

// Scratch for the exact power test: the products lift * orient3d can be long
// in the worst case (7 * 96 * 2 components each), so they live on the heap,
// allocated once per thread, not on the stack.
struct PowerScratch {
  std::vector<double> product, work, acc0, acc1;
  PowerScratch() : product(2 * 7 * 96), work(4 * 7 * 96), acc0(5 * 2 * 7 * 96), acc1(5 * 2 * 7 * 96) {}
};

// Exact lift h = x^2 + y^2 + z^2 - w (<= 7 components), compressed.
int exact_lift(const WeightedPoint& p, double* h) {
  double x1, x0, y1, y0, z1, z0;
  two_square(p.z.x(), x1, x0);
  two_square(p.z.y(), y1, y0);
  two_square(p.z.z(), z1, z0);
  const double ex[2] = {x0, x1}, ey[2] = {y0, y1}, ez[2] = {z0, z1};
  double t[4], s[6];
  const int tl = expansion_sum(2, ex, 2, ey, t);
  const int sl = expansion_sum(tl, t, 2, ez, s);
  const int hl = grow_expansion(sl, s, -p.w, h);
  return compress_expansion(hl, h, h);
}

// Power Test Determinant ------------------------------------------------------
//
// Rows r = 0..4 are the points a, b, c, d, e, with lift h_r = |z_r|^2 - w_r.
// Let det5 = det[[x_r, y_r, z_r, h_r, 1]]. Expanding along the h column,
//   det5 = sum_r (-1)^(r+1+4) h_r det[[x,y,z,1] of the other rows]
//        = sum_r (-1)^r h_r orient3d(others in order) =: sum_r (-1)^r h_r O_r
// (using det[[p,1],...] = -orient3d(p,...) from the exact-layer comment; the
// rows are numbered from 0 here). The power-test value is D = -det5.
// Meaning: det5 is unchanged by adding to the h column any affine function of
// the (x, y, z) columns (column operations with the x, y, z and 1 columns).
// Subtract H_T, the affine function whose graph is the hyperplane through the
// lifted a, b, c, d: the h column becomes (0, 0, 0, 0, h_e - H_T(z_e)), so
//   det5 = (h_e - H_T(z_e)) O_4 = (h_e - H_T(z_e)) orient3d(a, b, c, d).
// With H_T(x) = 2 z_T.x + w_T - |z_T|^2 (the lift of a point p satisfies
// h_p = H_T(z_p) iff pi_p(z_T) = w_T), h_e - H_T(z_e) = pi_e(z_T) - w_T, so
//   D = (w_T - pi_e(z_T)) orient3d(a, b, c, d):
// Positive iff e is in conflict with a positively oriented abcd.
// The filter evaluates the same determinant translated to e (subtract z_e from
// the x, y, z columns and the affine function 2 z_e.x - |z_e|^2 - w_e from the
// h column): the e row becomes (0, 0, 0, 0, 1) and det5 = det4 of the rows
// (p - e, l_p), l_p = |p - e|^2 - w_p + w_e; expanding det4 along the l column,
//   D = -det4 = l_a det3(bcd) - l_b det3(acd) + l_c det3(abd) - l_d det3(abc).
//
// Simulation of Simplicity on the weights: w_r -> w_r + eps_r, i.e.
// h_r -> h_r - eps_r, with eps_r >> eps_s iff index_r > index_s. det5 is linear
// in the h column, so exactly (no higher-order terms in the eps_r)
//   D(eps) = -sum_r (-1)^r (h_r - eps_r) O_r = D + sum_r (-1)^r eps_r O_r.
// If D = 0 the sign of D(eps) is that of (-1)^r O_r for the row r of largest
// index with O_r != 0: + O_a, - O_b, + O_c, - O_d, + O_e. The e term is
// O_e = orient3d(a, b, c, d) > 0 (precondition), so the cascade always stops
// and never returns Zero. Checks by hand: if e has the largest index it wins
// the tie (Positive: a larger weight of e puts e in conflict). If a has the
// largest index, the sign is that of orient3d(b, c, d, e): e on the same side
// of bcd as a means orient3d(b, c, d, e) has the sign of orient3d(b, c, d, a)
// = -orient3d(a, b, c, d) < 0, i.e. Negative: raising w_a lowers the
// hyperplane near e, so e leaves the conflict. Both as expected.
struct ExactPower {
  Sign d_sign;            // sign of D (exact)
  std::array<Sign, 5> o;  // signs of O_r (exact)
};

ExactPower exact_power(const WeightedPoint* const* pts) {
  const Vec3* z[5] = {&pts[0]->z, &pts[1]->z, &pts[2]->z, &pts[3]->z, &pts[4]->z};
  const ExactMinors minors(z, 5);
  thread_local PowerScratch scratch;
  double* acc = scratch.acc0.data();
  double* next = scratch.acc1.data();
  int acc_len = 0;
  ExactPower result;
  for (int r = 0; r < 5; ++r) {
    int others[4];
    for (int i = 0, k = 0; i < 5; ++i)
      if (i != r) others[k++] = i;
    double o[96];
    int ol = minors.orient3d(others[0], others[1], others[2], others[3], o);
    ol = compress_expansion(ol, o, o);
    result.o[r] = expansion_sign(ol, o);
    double h[7];
    const int hl = exact_lift(*pts[r], h);
    // Term t_r = (-1)^(r+1) h_r O_r (so that D = sum_r t_r).
    const int pl = (hl <= ol) ? expansion_product(ol, o, hl, h, scratch.product.data(), scratch.work.data())
                              : expansion_product(hl, h, ol, o, scratch.product.data(), scratch.work.data());
    if (r % 2 == 1) {
      acc_len = expansion_sum(acc_len, acc, pl, scratch.product.data(), next);
    } else {
      acc_len = expansion_diff(acc_len, acc, pl, scratch.product.data(), next);
    }
    std::swap(acc, next);
  }
  result.d_sign = expansion_sign(acc_len, acc);
  return result;
}

}  // namespace

// Orientation Predicate Definitions -------------------------------------------

Sign orient2d_exact(double ax, double ay, double bx, double by, double cx, double cy) {
  const Vec3 a(ax, ay, 0.0), b(bx, by, 0.0), c(cx, cy, 0.0);
  const Vec3* p[3] = {&a, &b, &c};
  const ExactMinors minors(p, 3);
  return minors.orient2d_sign(0, 1, 2);
}

Sign orient2d(double ax, double ay, double bx, double by, double cx, double cy) {
  ++tl_stats.orient2d.calls;
  const Sign s = orient2d_filter(ax, ay, bx, by, cx, cy);
  if (s != Sign::Zero) return s;
  ++tl_stats.orient2d.exact;
  return orient2d_exact(ax, ay, bx, by, cx, cy);
}

double orient2d_fast(double ax, double ay, double bx, double by, double cx, double cy) {
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

Sign orient3d_exact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3* p[4] = {&a, &b, &c, &d};
  const ExactMinors minors(p, 4);
  double o[96];
  const int ol = minors.orient3d(0, 1, 2, 3, o);
  return expansion_sign(ol, o);
}

Sign orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  ++tl_stats.orient3d.calls;
  const Sign s = orient3d_filter(a, b, c, d);
  if (s != Sign::Zero) return s;
  ++tl_stats.orient3d.exact;
  return orient3d_exact(a, b, c, d);
}

double orient3d_fast(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double ux = b.x() - a.x(), uy = b.y() - a.y(), uz = b.z() - a.z();
  const double vx = c.x() - a.x(), vy = c.y() - a.y(), vz = c.z() - a.z();
  const double wx = d.x() - a.x(), wy = d.y() - a.y(), wz = d.z() - a.z();
  return (ux * (vy * wz - vz * wy) + uy * (vz * wx - vx * wz)) + uz * (vx * wy - vy * wx);
}

// Power Test Definitions ------------------------------------------------------

Sign power_test_exact(const WeightedPoint& a, const WeightedPoint& b, const WeightedPoint& c, const WeightedPoint& d,
                      const WeightedPoint& e) {
  const WeightedPoint* p[5] = {&a, &b, &c, &d, &e};
  return exact_power(p).d_sign;
}

Sign power_test(const WeightedPoint& a, const WeightedPoint& b, const WeightedPoint& c, const WeightedPoint& d,
                const WeightedPoint& e) {
  ++tl_stats.power_test.calls;
  const Sign s = power_test_filter(a, b, c, d, e);
  if (s != Sign::Zero) return s;
  ++tl_stats.power_test.exact;
  return power_test_exact(a, b, c, d, e);
}

double power_test_fast(const WeightedPoint& a, const WeightedPoint& b, const WeightedPoint& c, const WeightedPoint& d,
                       const WeightedPoint& e) {
  double value = 0.0;
  power_test_filter(a, b, c, d, e, &value);
  return value;
}

Sign power_test_sos(const WeightedPoint& a, const WeightedPoint& b, const WeightedPoint& c, const WeightedPoint& d,
                    const WeightedPoint& e, Index ia, Index ib, Index ic, Index id, Index ie) {
  ++tl_stats.power_test.calls;
  const Sign s = power_test_filter(a, b, c, d, e);
  if (s != Sign::Zero) return s;
  ++tl_stats.power_test.exact;
  const WeightedPoint* p[5] = {&a, &b, &c, &d, &e};
  const ExactPower ex = exact_power(p);
  if (ex.d_sign != Sign::Zero) return ex.d_sign;

  // SoS cascade (derivation above): rows by decreasing index; the first row r
  // with O_r != 0 decides, with sign (-1)^r.
  ++tl_stats.power_test.sos;
  SKINMESH_DEBUG_ASSERT(ia != ib && ia != ic && ia != id && ia != ie && ib != ic && ib != id && ib != ie && ic != id &&
                        ic != ie && id != ie);
  std::array<int, 5> rows = {0, 1, 2, 3, 4};
  const Index idx[5] = {ia, ib, ic, id, ie};
  std::sort(rows.begin(), rows.end(), [&](int r, int q) { return idx[r] > idx[q]; });
  for (const int r : rows) {
    if (ex.o[r] != Sign::Zero) return (r % 2 == 0) ? ex.o[r] : -ex.o[r];
  }
  // Only reachable if abcd is flat (precondition violated).
  SKINMESH_ASSERT_MSG(false, "power_test_sos: flat tetrahedron abcd");
  return Sign::Zero;
}

}  // namespace skinmesh::geometry
