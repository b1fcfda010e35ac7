// skin/skin_measures.cpp: area and volume of the exact skin, patch by patch.
// papers/skin/skin_measures.md has the derivation; in short, every patch is a
// surface of revolution about an axis a through its focus z,
//   y = x - z = t a + r(t) u(θ),   r(t)² = σ t² + c,   u(θ) = cos θ e1 + sin θ e2,
// and in the coordinates (t, θ) the area element is ρ dt dθ (ρ = |y|) and the
// divergence-theorem integrand x·n dA is (-w/2 + z·g) dt dθ with g = ∇f/2.
// For a fixed θ the cell's planes cut the meridian t into intervals whose
// integrals are closed forms; the θ integral is numerical.
#include "skin/skin_measures.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "core/errors.h"
#include "core/parallel.h"

namespace skinmesh::skin {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// A cell's patch in its meridian frame. The signs (et, er) give
/// g = ∇f_X / 2 = et·t·a + er·r·u per dimension of X: (+,+) vertex sphere,
/// (-,+) edge hyperboloid, (+,-) triangle hyperboloid, (-,-) cavity sphere.
/// Then f = et t² + er r² + w/2, so the profile is r² = σ t² + c with
/// σ = -et·er and c = -er·w/2.
struct Frame {
  Vec3 z, a, e1, e2;
  double w = 0;  // focus weight (Å²)
  int sigma = 1;
  double c = 0;
  double et = 1, er = 1;
};

/// One plane n·x <= o of the cell in the frame: α t + β(θ) r <= γ with
/// β(θ) = n1 cos θ + n2 sin θ.
struct FramePlane {
  double alpha, n1, n2, gamma;
};

/// A few disjoint closed intervals of t, increasing.
struct IntervalSet {
  static constexpr int kMax = 16;
  std::array<double, 2 * kMax> ends{};
  int n = 0;
  void add(double lo, double hi) {
    if (n > 0 && ends[2 * n - 1] >= lo) {  // touches the last one: merge
      ends[2 * n - 1] = std::max(ends[2 * n - 1], hi);
      return;
    }
    if (n == kMax) throw GeometryError("skin measures: too many meridian intervals in one cell");
    ends[2 * n] = lo;
    ends[2 * n + 1] = hi;
    ++n;
  }
};

double profile_r(const Frame& f, double t) { return std::sqrt(std::max(0.0, f.sigma * t * t + f.c)); }

/// The base domain of the profile: where r² = σ t² + c >= 0.
IntervalSet base_domain(const Frame& f) {
  IntervalSet s;
  if (f.sigma < 0) {
    if (f.c > 0) s.add(-std::sqrt(f.c), std::sqrt(f.c));
  } else if (f.c >= 0) {
    s.add(-kInf, kInf);
  } else {
    s.add(-kInf, -std::sqrt(-f.c));
    s.add(std::sqrt(-f.c), kInf);
  }
  return s;
}

/// Candidate cut points for one plane: the roots t of
/// (γ - α t)² = β² (σ t² + c), which hold the roots of α t + β r(t) = γ on the
/// profile (r >= 0) and may hold those of the mirrored profile (r <= 0). The
/// caller classifies the pieces between cuts by their midpoints, so a spurious
/// cut costs a piece and never an error, while a root dropped by rounding
/// would (β (γ - α t) is zero to rounding for planes across the axis).
/// Returns their number, increasing.
int plane_roots(const Frame& f, double alpha, double beta, double gamma, double scale, double out[2]) {
  const double A = alpha * alpha - f.sigma * beta * beta;
  const double B = alpha * gamma;  // the equation is A t² - 2 B t + C = 0
  const double C = gamma * gamma - beta * beta * f.c;
  const double D = f.sigma * gamma * gamma + f.c * A;  // discriminant / β²
  if (D < 0) return 0;
  double cand[2];
  int k = 0;
  if (std::abs(A) <= 1e-15 * (alpha * alpha + beta * beta)) {
    if (B != 0) cand[k++] = C / (2.0 * B);
  } else {
    const double q = B + std::copysign(std::abs(beta) * std::sqrt(D), B);
    if (q != 0) {
      cand[k++] = q / A;
      cand[k++] = C / q;
    } else {
      cand[k++] = 0.0;  // B = 0 and a double root: C = 0
    }
  }
  int m = 0;
  for (int i = 0; i < k; ++i)
    if (std::isfinite(cand[i]) && std::abs(cand[i]) <= 1e6 * scale) out[m++] = cand[i];
  if (m == 2 && out[0] > out[1]) std::swap(out[0], out[1]);
  return m;
}

/// The set T(θ) of t in the base domain whose point lies in the cell.
IntervalSet meridian_set(const Frame& f, const std::vector<FramePlane>& planes, double theta, double scale) {
  IntervalSet cur = base_domain(f);
  const double ct = std::cos(theta), st = std::sin(theta);
  for (const FramePlane& p : planes) {
    if (cur.n == 0) break;
    const double beta = p.n1 * ct + p.n2 * st;
    double roots[2];
    const int nr = plane_roots(f, p.alpha, beta, p.gamma, scale, roots);
    IntervalSet next;
    for (int i = 0; i < cur.n; ++i) {
      const double lo = cur.ends[2 * i], hi = cur.ends[2 * i + 1];
      double cuts[4] = {lo, 0, 0, 0};
      int nc = 1;
      for (int j = 0; j < nr; ++j)
        if (roots[j] > lo && roots[j] < hi) cuts[nc++] = roots[j];
      cuts[nc++] = hi;
      for (int j = 0; j + 1 < nc; ++j) {
        const double a = cuts[j], b = cuts[j + 1];
        double mid;
        if (std::isinf(a) && std::isinf(b))
          mid = 0.0;
        else if (std::isinf(a))
          mid = b - scale;
        else if (std::isinf(b))
          mid = a + scale;
        else
          mid = 0.5 * (a + b);
        if (p.alpha * mid + beta * profile_r(f, mid) - p.gamma <= 0) next.add(a, b);
      }
    }
    cur = next;
  }
  return cur;
}

/// ∫ sqrt(k² t² + c) dt for k > 0 (an antiderivative; any constant).
double hyperbolic_root_integral(double k, double c, double t) {
  const double s = std::sqrt(std::max(0.0, k * k * t * t + c));
  double log_term = 0;
  if (c > 0)
    log_term = std::asinh(k * t / std::sqrt(c));
  else if (c < 0)
    log_term = std::copysign(std::acosh(std::max(1.0, k * std::abs(t) / std::sqrt(-c))), t);
  return 0.5 * t * s + c / (2.0 * k) * log_term;
}

/// ∫ sqrt(c - t²) dt for c > 0, |t| <= sqrt(c).
double circular_root_integral(double c, double t) {
  const double R = std::sqrt(c);
  const double x = std::clamp(t / R, -1.0, 1.0);
  return 0.5 * t * std::sqrt(std::max(0.0, c - t * t)) + 0.5 * c * std::asin(x);
}

/// Area and volume densities per unit θ at azimuth θ (the t integrals).
struct Density {
  double area = 0, volume = 0;
  bool empty = true;
};

Density density(const Frame& f, const std::vector<FramePlane>& planes, double theta, double scale, Index cell) {
  const IntervalSet set = meridian_set(f, planes, theta, scale);
  Density d;
  d.empty = set.n == 0;
  const double za = f.z.dot(f.a);
  const double zu = f.z.dot(std::cos(theta) * f.e1 + std::sin(theta) * f.e2);
  for (int i = 0; i < set.n; ++i) {
    const double lo = set.ends[2 * i], hi = set.ends[2 * i + 1];
    if (std::isinf(lo) || std::isinf(hi))
      throw GeometryError("skin measures: the planes of mixed cell " + std::to_string(cell) +
                          " do not bound its hyperboloid patch");
    double area, r_integral;
    if (f.sigma < 0) {
      area = std::sqrt(f.c) * (hi - lo);  // ρ = R on a sphere
      r_integral = circular_root_integral(f.c, hi) - circular_root_integral(f.c, lo);
    } else {
      area = hyperbolic_root_integral(std::numbers::sqrt2, f.c, hi) -
             hyperbolic_root_integral(std::numbers::sqrt2, f.c, lo);
      r_integral = hyperbolic_root_integral(1.0, f.c, hi) - hyperbolic_root_integral(1.0, f.c, lo);
    }
    d.area += area;
    d.volume += (-0.5 * f.w * (hi - lo) + f.et * za * 0.5 * (hi - lo) * (hi + lo) + f.er * zu * r_integral) / 3.0;
  }
  return d;
}

// Gauss–Kronrod (7, 15) on [-1, 1]: the 15 Kronrod abscissae ±x[i] (x[7] = 0)
// with weights wk; the 7 Gauss points are x[1], x[3], x[5], x[7] with weights wg.
constexpr std::array<double, 8> kXk = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                                       0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                                       0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                                       0.207784955007898467600689403773245, 0.0};
constexpr std::array<double, 8> kWk = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                                       0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                                       0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                                       0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr std::array<double, 4> kWg = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                                       0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

/// Absolute error floors per radian of θ: area (Å²) and volume (Å³).
struct Tolerance {
  double area, volume;
};

/// Relative tolerance of a panel's integrals, against QUADPACK's error
/// estimate. The estimate is pessimistic for these integrands: on crambin at
/// probe 0, tolerances from 1e-4 down to 1e-13 change the skin's area and
/// volume by less than 1e-11 relative (papers/skin/skin_measures.md).
constexpr double kRelativeTolerance = 1e-6;

struct PanelSum {
  double area = 0, volume = 0;
};

/// One Gauss–Kronrod estimate with its error (Kronrod minus Gauss).
struct Piece {
  double s0, s1;
  double area, volume, area_error, volume_error;
};

/// The densities integrated over θ in [t0, t0 + h], substituting
/// θ = t0 + h (1 - cos πs) / 2 for s in [s0, s1] (it smooths the square-root
/// behaviour of the densities at the panel's ends, where a plane turns).
Piece gauss_kronrod(const Frame& f, const std::vector<FramePlane>& planes, double t0, double h, double s0, double s1,
                    double scale, Index cell) {
  const double half = 0.5 * (s1 - s0), mid = 0.5 * (s0 + s1);
  double ka = 0, kv = 0, ga = 0, gv = 0, ma = 0, mv = 0;
  for (int j = 0; j < 8; ++j)
    for (int side = j == 7 ? 1 : 0; side < 2; ++side) {  // ±x[j]; the centre x[7] = 0 once
      const double s = mid + half * (side == 0 ? -kXk[j] : kXk[j]);
      const double theta = t0 + 0.5 * h * (1.0 - std::cos(std::numbers::pi * s));
      const double jac = 0.5 * h * std::numbers::pi * std::sin(std::numbers::pi * s) * half;
      const Density d = density(f, planes, theta, scale, cell);
      ka += kWk[j] * d.area * jac;
      kv += kWk[j] * d.volume * jac;
      ma += kWk[j] * std::abs(d.area * jac);
      mv += kWk[j] * std::abs(d.volume * jac);
      if (j % 2 == 1) {  // a Gauss point too
        ga += kWg[j / 2] * d.area * jac;
        gv += kWg[j / 2] * d.volume * jac;
      }
    }
  // The error of the Kronrod value, estimated from the difference to the
  // Gauss value as QUADPACK's qk15 does: M min(1, (200 |K - G| / M)^1.5),
  // M = ∫ |integrand|. |K - G| itself is about the Gauss rule's error, far
  // above the Kronrod rule's for the smooth integrands between events.
  const auto error = [](double diff, double m) {
    return m > 0 ? m * std::min(1.0, std::pow(200.0 * diff / m, 1.5)) : diff;
  };
  return {s0, s1, ka, kv, error(std::abs(ka - ga), ma), error(std::abs(kv - gv), mv)};
}

/// The panel [t0, t0 + h] integrated adaptively: the piece with the largest
/// error (relative to its share of the tolerance) is halved until the summed
/// errors meet the tolerance (relative 1e-10, with absolute floors per radian)
/// or the panel has 64 pieces.
PanelSum integrate_panel(const Frame& f, const std::vector<FramePlane>& planes, double t0, double h, double scale,
                         const Tolerance& quad, Index cell) {
  std::vector<Piece> pieces{gauss_kronrod(f, planes, t0, h, 0.0, 1.0, scale, cell)};
  for (;;) {
    PanelSum sum;
    double area_error = 0, volume_error = 0;
    for (const Piece& p : pieces) {
      sum.area += p.area, sum.volume += p.volume;
      area_error += p.area_error, volume_error += p.volume_error;
    }
    const double tol_area = std::max(kRelativeTolerance * std::abs(sum.area), quad.area * h);
    const double tol_volume = std::max(kRelativeTolerance * std::abs(sum.volume), quad.volume * h);
    if ((area_error <= tol_area && volume_error <= tol_volume) || pieces.size() >= 64) return sum;
    std::size_t worst = 0;
    double worst_error = -1;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const double e = std::max(pieces[i].area_error / tol_area, pieces[i].volume_error / tol_volume);
      if (e > worst_error) worst_error = e, worst = i;
    }
    const Piece p = pieces[worst];
    const double mid = 0.5 * (p.s0 + p.s1);
    pieces[worst] = gauss_kronrod(f, planes, t0, h, p.s0, mid, scale, cell);
    pieces.push_back(gauss_kronrod(f, planes, t0, h, mid, p.s1, scale, cell));
  }
}

double wrap_angle(double t) {
  t = std::fmod(t, kTwoPi);
  return t < 0 ? t + kTwoPi : t;
}

/// A ball (centre, radius) holding mixed cell c. With s = 1/2 the cell is
/// (X + ν_X)/2, so its vertices are the midpoints of a vertex of X and the
/// focus of a tetrahedron containing X; the tetrahedra are found by climbing
/// the coface graph (the neighbours across the cell planes, one dimension up).
std::pair<Vec3, double> bounding_ball(const MixedComplex& mc, Index c) {
  std::vector<Index> tets{c};
  for (int d = mc.simplex(c).dim; d < 3; ++d) {
    std::vector<Index> up;
    for (Index x : tets)
      for (const Index nb : mc.neighbors(x))
        if (mc.simplex(nb).dim == d + 1) up.push_back(nb);
    std::sort(up.begin(), up.end());
    up.erase(std::unique(up.begin(), up.end()), up.end());
    tets.swap(up);
  }
  const CellSimplex& m = mc.simplex(c);
  const auto& rt = mc.triangulation();
  Vec3 lo = Vec3::Constant(kInf), hi = Vec3::Constant(-kInf);
  std::vector<Vec3> foci;  // the tetrahedra's, made and not kept (as the cells below)
  for (Index t : tets) foci.push_back(mc.cell_value(t).focus);
  std::vector<Vec3> corners;
  for (int i = 0; i <= m.dim; ++i)
    for (const Vec3& z : foci) corners.push_back(0.5 * (rt.point(m.vertices[i]).z + z));
  for (const Vec3& p : corners) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Vec3 centre = 0.5 * (lo + hi);
  double radius = 0;
  for (const Vec3& p : corners) radius = std::max(radius, (p - centre).norm());
  return {centre, radius};
}

/// False if f_X has one sign on the ball: then the patch piece is empty.
bool may_hold_patch(const MixedComplex& mc, const Frame& f, const Vec3& centre, double radius) {
  const double margin = 1e-9 * mc.length_scale() + 1e-12 * radius;
  const Vec3 y = centre - f.z;
  const double ya = y.dot(f.a);
  const double yr = (y - ya * f.a).norm();
  const double R = radius + margin;
  // Ranges of t² and r² over the ball.
  const double t_lo = std::max(0.0, std::abs(ya) - R), t_hi = std::abs(ya) + R;
  const double r_lo = std::max(0.0, yr - R), r_hi = yr + R;
  const auto range = [](double s, double lo, double hi) {
    return s > 0 ? std::pair{s * lo * lo, s * hi * hi} : std::pair{s * hi * hi, s * lo * lo};
  };
  const auto [tl, th] = range(f.et, t_lo, t_hi);
  const auto [rl, rh] = range(f.er, r_lo, r_hi);
  const double f_lo = tl + rl + 0.5 * f.w, f_hi = th + rh + 0.5 * f.w;
  return f_lo <= 0 && f_hi >= 0;
}

Frame make_frame(const MixedCell& m) {
  Frame f;
  f.z = m.focus;
  f.w = m.focus_weight;
  static const Vec3 kGeneric = Vec3(0.31415926535, 0.57721566490, 0.75497399958).normalized();
  f.a = (m.dim == 1 || m.dim == 2) ? Vec3(m.axis.normalized()) : kGeneric;
  const Vec3 helper = std::abs(f.a.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
  f.e1 = (helper - helper.dot(f.a) * f.a).normalized();
  f.e2 = f.a.cross(f.e1);
  f.et = (m.dim == 0 || m.dim == 2) ? 1.0 : -1.0;
  f.er = (m.dim <= 1) ? 1.0 : -1.0;
  f.sigma = f.et * f.er > 0 ? -1 : 1;
  f.c = -f.er * 0.5 * f.w;
  return f;
}

/// What every piece of cell c's patch shares: the cell, its frame, a ball
/// holding it and its planes; `empty` if the patch piece is empty.
struct PatchSetup {
  MixedCell m;
  Frame f;
  Vec3 centre = Vec3::Zero();
  double radius = 0;
  std::vector<CellPlane> planes;
  bool empty = true;
};

PatchSetup patch_setup(const MixedComplex& mc, Index c) {
  // The cell and its planes made and not kept (bit for bit those of cell()
  // and planes()): the integration reads every cell once, and keeping them
  // made the geometry of the whole complex at once (papers/decompose/
  // history.md, "The made cells between the stages").
  PatchSetup s;
  s.m = mc.cell_value(c);
  if (s.m.bounding) return s;
  s.f = make_frame(s.m);
  if (s.f.sigma < 0 && s.f.c <= 0) return s;  // a sphere of no radius
  std::tie(s.centre, s.radius) = bounding_ball(mc, c);
  if (!may_hold_patch(mc, s.f, s.centre, s.radius)) return s;
  mc.planes_into(c, s.planes);
  s.empty = false;
  return s;
}

/// The piece of the patch of s in the half-spaces n·x <= offset of `half_spaces`
/// (the cell's planes, and any further ones), integrated.
PatchMeasure integrate_piece(const MixedComplex& mc, Index c, const PatchSetup& s,
                             const std::vector<CellPlane>& half_spaces) {
  PatchMeasure out;
  const Frame& f = s.f;
  const MixedCell& m = s.m;
  const Vec3& centre = s.centre;
  // The cell's size sets the tolerances; the volume integrand also grows with
  // the distance from the origin.
  const double scale = std::max(s.radius, 1e-6 * mc.length_scale());
  const double tol = 1e-9 * mc.length_scale();
  const Tolerance quad{1e-12 * scale * scale, 1e-12 * scale * scale * (scale + centre.norm())};

  std::vector<FramePlane> planes;
  std::vector<CellPlane> raw;
  for (const CellPlane& p : half_spaces) {
    const double gamma = p.offset - p.normal.dot(f.z);  // the focus' distance inside the plane
    if (f.sigma < 0) {                                  // a sphere of radius sqrt(c) about the focus
      const double R = std::sqrt(f.c);
      if (gamma <= -R) return out;            // wholly outside the plane
      if (gamma >= R * (1 + 1e-9)) continue;  // wholly inside: the plane cuts nothing
    }
    raw.push_back(p);
    planes.push_back({p.normal.dot(f.a), p.normal.dot(f.e1), p.normal.dot(f.e2), gamma});
  }

  const auto in_cell = [&](const Vec3& x) {
    for (const CellPlane& p : raw)
      if (p.normal.dot(x) - p.offset > tol) return false;
    return true;
  };
  // Azimuths where the piece's boundary turns (a plane's curve on the patch
  // is tangent to a meridian) or has a corner (two planes meet on the patch).
  // Only those on the piece's boundary (in the cell) change the shape of T(θ).
  std::vector<double> events;
  for (const FramePlane& p : planes) {
    const double nu = std::hypot(p.n1, p.n2);
    if (f.c == 0 || nu == 0) continue;
    const double beta2 = (f.sigma * p.gamma * p.gamma + f.c * p.alpha * p.alpha) / (f.sigma * f.c);
    if (beta2 < 0 || beta2 > nu * nu) continue;
    {  // the plane's curve turns at φ ± ang and φ + π ± ang
      const double phi = std::atan2(p.n2, p.n1);
      const double ang = std::acos(std::min(1.0, std::sqrt(beta2) / nu));
      for (double v : {phi + ang, phi - ang, phi + std::numbers::pi + ang, phi + std::numbers::pi - ang}) {
        // The double root of the plane's equation at this azimuth.
        const double beta = p.n1 * std::cos(v) + p.n2 * std::sin(v);
        const double A = p.alpha * p.alpha - f.sigma * beta * beta;
        const double t = A != 0 ? p.alpha * p.gamma / A : 0.0;
        const Vec3 y = t * f.a + profile_r(f, t) * (std::cos(v) * f.e1 + std::sin(v) * f.e2);
        if (A == 0 || in_cell(f.z + y)) events.push_back(wrap_angle(v));
      }
    }
  }
  const Mat3 Q = MixedComplex::quadric_matrix(m);
  for (std::size_t i = 0; i < raw.size(); ++i)
    for (std::size_t j = i + 1; j < raw.size(); ++j) {
      const Vec3& ni = raw[i].normal;
      const Vec3& nj = raw[j].normal;
      const Vec3 d = ni.cross(nj);
      const double dd = d.squaredNorm();
      if (dd < 1e-20) continue;  // parallel planes
      // The line's point z + a ni + b nj.
      const double gi = raw[i].offset - ni.dot(f.z), gj = raw[j].offset - nj.dot(f.z);
      const double nn = ni.dot(nj);
      const double det = 1.0 - nn * nn;
      const Vec3 p0 = ((gi - gj * nn) * ni + (gj - gi * nn) * nj) / det;  // relative to z
      const Vec3 qd = Q * d;
      const double qa = d.dot(qd), qb = p0.dot(qd), qc = p0.dot(Q * p0) + 0.5 * f.w;
      double ss[2];
      int ns = 0;
      if (std::abs(qa) < 1e-15 * dd) {
        if (qb != 0) ss[ns++] = -qc / (2.0 * qb);
      } else {
        const double disc = qb * qb - qa * qc;
        if (disc < 0) continue;
        const double q = -(qb + std::copysign(std::sqrt(disc), qb));
        if (q != 0)
          ss[ns++] = q / qa, ss[ns++] = qc / q;
        else
          ss[ns++] = 0;
      }
      for (int k = 0; k < ns; ++k) {
        const Vec3 y = p0 + ss[k] * d;
        if (in_cell(f.z + y)) events.push_back(wrap_angle(std::atan2(y.dot(f.e2), y.dot(f.e1))));
      }
    }
  std::sort(events.begin(), events.end());
  std::vector<double> cuts;
  for (double e : events)
    if (cuts.empty() || e - cuts.back() > 1e-13) cuts.push_back(e);
  if (cuts.size() > 1 && cuts.front() + kTwoPi - cuts.back() <= 1e-13) cuts.pop_back();
  if (cuts.empty()) cuts.push_back(0.0);

  for (std::size_t k = 0; k < cuts.size(); ++k) {
    const double t0 = cuts[k];
    const double t1 = k + 1 < cuts.size() ? cuts[k + 1] : cuts.front() + kTwoPi;
    const double h = t1 - t0;
    // Between two events the set T(θ) keeps its shape: it is empty on the
    // whole panel if it is empty at the panel's middle.
    if (density(f, planes, t0 + 0.5 * h, scale, c).empty) continue;
    const PanelSum p = integrate_panel(f, planes, t0, h, scale, quad, c);
    out.area += p.area;
    out.volume += p.volume;
    out.nonempty = true;
  }
  return out;
}

}  // namespace

PatchMeasure patch_measure(const MixedComplex& mc, Index c) {
  const PatchSetup s = patch_setup(mc, c);
  return s.empty ? PatchMeasure{} : integrate_piece(mc, c, s, s.planes);
}

std::array<double, 4> patch_atom_areas(const MixedComplex& mc, Index c) {
  std::array<double, 4> areas{0, 0, 0, 0};
  const PatchSetup s = patch_setup(mc, c);
  if (s.empty) return areas;
  const CellSimplex& x = mc.simplex(c);
  if (x.dim == 0) {  // an atom's own sphere patch
    areas[0] = integrate_piece(mc, c, s, s.planes).area;
    return areas;
  }
  const auto& rt = mc.triangulation();
  std::vector<CellPlane> half_spaces;
  for (int i = 0; i <= x.dim; ++i) {
    // The points of the cell no farther from vertex i, in power distance,
    // than from the simplex's other vertices (SkinSurface::atom_of's rule):
    // power(y, i) <= power(y, j) is 2 y·(z_j - z_i) <= |z_j|² - |z_i|² - w_j + w_i.
    half_spaces = s.planes;
    const WeightedPoint& pi = rt.point(x.vertices[i]);
    for (int j = 0; j <= x.dim; ++j) {
      if (j == i) continue;
      const WeightedPoint& pj = rt.point(x.vertices[j]);
      const Vec3 d = pj.z - pi.z;
      const double len = d.norm();
      const Vec3 n = d / len;
      half_spaces.push_back({n, n.dot(0.5 * (pi.z + pj.z)) + (pi.w - pj.w) / (2.0 * len)});
    }
    areas[i] = integrate_piece(mc, c, s, half_spaces).area;
  }
  return areas;
}

namespace {

/// skin_measures() over windows of consecutive cells: each window's patches
/// on the threads, then summed in cell order, so the sums are those of one
/// loop over every cell, bit for bit, for every window and thread count, and
/// the patches' results take one window's memory, not one entry per cell.
SkinMeasures measure_in_windows(const SkinSurface& skin, int threads) {
  const MixedComplex& mc = skin.mixed_complex();
  const auto n = static_cast<std::size_t>(mc.num_cells());
  constexpr std::size_t kWindow = std::size_t{1} << 16;  // [chosen] 1.5 MB of results, 256 blocks of 256 cells
  std::vector<PatchMeasure> cells(std::min(n, kWindow));
  SkinMeasures s;
  for (std::size_t w = 0; w < n; w += kWindow) {
    const std::size_t k = std::min(kWindow, n - w);
    parallel_for(k, thread_count(threads), 256,
                 [&](std::size_t i) { cells[i] = patch_measure(mc, static_cast<Index>(w + i)); });
    for (std::size_t i = 0; i < k; ++i) {
      s.area += cells[i].area;
      s.volume += cells[i].volume;
      s.patch_cells += cells[i].nonempty ? 1 : 0;
    }
  }
  return s;
}

}  // namespace

SkinMeasures skin_measures(const SkinSurface& skin, int threads) { return measure_in_windows(skin, threads); }

std::vector<double> atom_areas(const SkinSurface& skin, int threads) {
  // As measure_in_windows(): each window's cells on the threads, then added
  // to their atoms in cell order, so the sums do not depend on `threads`.
  const MixedComplex& mc = skin.mixed_complex();
  const auto& rt = mc.triangulation();
  std::vector<double> areas(static_cast<std::size_t>(rt.num_input_points()), 0.0);
  const auto n = static_cast<std::size_t>(mc.num_cells());
  constexpr std::size_t kWindow = std::size_t{1} << 16;  // [chosen] 2 MB of results
  std::vector<std::array<double, 4>> cells(std::min(n, kWindow));
  for (std::size_t w = 0; w < n; w += kWindow) {
    const std::size_t k = std::min(kWindow, n - w);
    parallel_for(k, thread_count(threads), 256,
                 [&](std::size_t i) { cells[i] = patch_atom_areas(mc, static_cast<Index>(w + i)); });
    for (std::size_t i = 0; i < k; ++i) {
      const CellSimplex& x = mc.simplex(static_cast<Index>(w + i));
      for (int j = 0; j <= x.dim; ++j)
        if (!rt.is_bounding(x.vertices[j])) areas[x.vertices[j]] += cells[i][j];
    }
  }
  return areas;
}

SkinMeasures skin_measures(const std::vector<geometry::WeightedPoint>& points, int threads) {
  const SkinSurface skin(translated(points, local_frame_centre(points)), threads);
  return measure_in_windows(skin, threads);
}

std::vector<double> atom_areas(const std::vector<geometry::WeightedPoint>& points, int threads) {
  const SkinSurface skin(translated(points, local_frame_centre(points)), threads);
  return atom_areas(skin, threads);
}

}  // namespace skinmesh::skin
