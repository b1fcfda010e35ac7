// morse/level_curves.cpp: seeds from the Morse–Smale complex, a predictor–
// corrector on F ∩ {e·x = c}, and sampling by rho (papers/morse/level_curves.md).
#include "morse/level_curves.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>
#include <unordered_set>

#include "core/errors.h"
#include "geometry/triangulation/point_grid.h"

namespace skinmesh::morse {

namespace {

/// Octaves of rho per level of the seed grid (as the sweep's grids).
constexpr int kSeedGridOctaves = 2;
/// Newton steps of one projection onto the curve: it starts within a chord's
/// error of the curve and converges quadratically, so a few suffice.
constexpr int kMaxProjectionSteps = 50;
/// Halvings of a tracer or ascent step before giving up.
constexpr int kMaxHalvings = 30;

std::string at_height(double c) {
  std::ostringstream s;
  s.precision(10);
  s << "level curve at height " << c << " Å: ";
  return s.str();
}

/// The geometry of one curve on the skin traced by a predictor–corrector: a
/// level set F ∩ {e·x = c}, or the circle F ∩ S(q, R) along which a cut
/// detours around a protecting sphere (papers/morse/level_curves.md, "Cuts
/// that detour").
class CurveSet {
 public:
  /// The level set F ∩ {e·x = c}, oriented by n × e.
  static CurveSet plane(const skin::SkinSurface& skin, const Vec3& e, double c) {
    return CurveSet(skin, e, c, Vec3::Zero(), 0.0, 0);
  }
  /// The circle F ∩ S(q, R), oriented by sign · n × u, u the unit vector
  /// from q: sign +1 keeps the ball on the left seen from outside.
  static CurveSet sphere(const skin::SkinSurface& skin, const Vec3& e, double c, const Vec3& q, double R, int sign) {
    return CurveSet(skin, e, c, q, R, sign);
  }

  /// Moves y onto the curve. The level set: onto the plane, then Newton on f
  /// along the gradient's component in the plane (which keeps y on it). The
  /// circle: the same with the sphere, radially onto it and Newton along the
  /// gradient's component tangent to it. True if |f| / |grad_plane f| fell
  /// below the tolerance; `s` is then the sample at y and `cell` its cell.
  bool project(Vec3& y, Index& cell, skin::SkinSample& s) const {
    for (int it = 0; it < kMaxProjectionSteps; ++it) {
      Vec3 u = e_;
      if (sign_ == 0) {
        y -= (e_.dot(y) - c_) * e_;
      } else {
        const double len = (y - q_).norm();
        if (!(len > 0)) return false;
        y = q_ + (radius_ / len) * (y - q_);
        u = (y - q_) / radius_;
      }
      s = skin_.sample(y, cell);
      cell = s.cell;
      const Vec3 gp = s.gradient - s.gradient.dot(u) * u;
      const double g2 = gp.squaredNorm();
      if (!(g2 > 0)) return false;
      if (std::abs(s.f) <= tolerance_ * std::sqrt(g2)) return true;
      y -= (s.f / g2) * gp;
    }
    return false;
  }

  /// Unit tangent at a sample at y (n × e, or sign · n × u) and the sine of
  /// the angle between the normal and e (or u).
  Vec3 tangent(const skin::SkinSample& s, const Vec3& y, double& sine) const {
    const Vec3 t = sign_ == 0 ? Vec3(s.gradient.normalized().cross(e_))
                              : Vec3(sign_ * s.gradient.normalized().cross((y - q_) / radius_));
    sine = t.norm();
    return sine > 0 ? Vec3(t / sine) : Vec3::Zero();
  }

  /// The tracer's length unit at a point of local length scale rho: rho on
  /// the level set, at most the radius on the circle (whose curvature is at
  /// least 1 / R).
  double unit(double rho) const { return sign_ == 0 ? rho : std::min(rho, radius_); }

  const skin::SkinSurface& skin() const { return skin_; }
  const Vec3& e() const { return e_; }
  double c() const { return c_; }

 private:
  CurveSet(const skin::SkinSurface& skin, const Vec3& e, double c, const Vec3& q, double R, int sign)
      : skin_(skin), e_(e), c_(c), q_(q), radius_(R), sign_(sign), tolerance_(1e-12 * skin.length_scale()) {}

  const skin::SkinSurface& skin_;
  Vec3 e_;
  double c_;
  Vec3 q_;
  double radius_;
  int sign_;  ///< 0: the level set; ±1: the circle and its orientation
  double tolerance_;
};

/// A point of the level set from which a curve may be traced.
struct Seed {
  Vec3 p;
  Index cell;
  double rho;
};

/// The seed where the segment [a, b] (on or next to the skin, a below the
/// level and b above it or the reverse) crosses the plane, projected onto the
/// curve.
Seed seed_on_segment(const CurveSet& ls, const Vec3& a, const Vec3& b, Index hint) {
  const double ha = ls.e().dot(a) - ls.c(), hb = ls.e().dot(b) - ls.c();
  Vec3 y = a + (ha / (ha - hb)) * (b - a);
  Index cell = hint;
  skin::SkinSample s;
  if (!ls.project(y, cell, s))
    throw GeometryError(at_height(ls.c()) + "a seed on an integral line does not project onto the curve");
  return {y, cell, s.rho};
}

/// Ascends from minimum m by steps of 0.1 rho along the surface gradient of
/// the height (any monotone path stays on m's component) until it crosses the
/// level; false if it stops below it (at a maximum).
bool ascend_to_level(const CurveSet& ls, const CriticalPoint& m, std::size_t max_steps, Seed& out) {
  const skin::SkinSurface& skin = ls.skin();
  const Vec3& e = ls.e();
  // Leave the minimum sideways: its surface gradient is zero.
  Vec3 axis = Vec3::Zero();
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(e[i]) < std::abs(e[k])) k = i;
  axis[k] = 1;
  const Vec3 u = (axis - axis.dot(e) * e).normalized();
  Index cell = m.cell;
  skin::SkinSample s;
  Vec3 x = skin.pull_back(m.position + 0.05 * m.rho * u, cell, &s);
  for (std::size_t step = 0; step < max_steps; ++step) {
    if (e.dot(x) >= ls.c()) {
      out = seed_on_segment(ls, m.position, x, cell);
      return true;
    }
    const Vec3 n = s.gradient.normalized();
    const Vec3 a = e - n.dot(e) * n;
    if (!(a.norm() > 1e-9)) return false;
    double h = 0.1 * s.rho;
    bool advanced = false;
    for (int halve = 0; halve < kMaxHalvings && !advanced; ++halve, h *= 0.5) {
      Index c2 = cell;
      skin::SkinSample sn;
      const Vec3 xn = skin.pull_back(x + h * a.normalized(), c2, &sn);
      if (e.dot(xn) > e.dot(x)) {
        if (e.dot(xn) >= ls.c()) {
          out = seed_on_segment(ls, x, xn, c2);
          return true;
        }
        x = xn, cell = c2, s = sn, advanced = true;
      }
    }
    if (!advanced) return false;
  }
  throw GeometryError(at_height(ls.c()) + "an ascent from a minimum did not reach the level within " +
                      std::to_string(max_steps) + " steps");
}

/// Distance from p to the segment [a, b].
double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

/// One curve traced from a seed: the points of the fine polyline and their
/// samples.
struct Traced {
  std::vector<Vec3> points;
  std::vector<double> rho;
  std::vector<Index> cells;
};

/// Called after each accepted step from x to xn: true ends the trace there
/// (xn is not appended; the caller appends the piece's end).
using StopTest = std::function<bool(const Vec3& x, const Vec3& xn)>;

/// Traces from a seed until the curve closes. With a stop test, the test is
/// asked after every step; a `stretch` (a piece of a cut from one ball to the
/// next) must end by it, and coming back to its start is an error.
Traced trace_curve(const CurveSet& ls, const Seed& seed, const LevelCurveOptions& opt, std::size_t max_steps,
                   const std::function<void(const Vec3&, const Vec3&, double)>& on_segment,
                   const StopTest& stop = nullptr, bool stretch = false) {
  Traced out;
  Vec3 x = seed.p;
  Index cell = seed.cell;
  skin::SkinSample sx;
  if (!ls.project(x, cell, sx)) throw GeometryError(at_height(ls.c()) + "a seed does not project onto the curve");
  const Vec3 x0 = x;
  double sine0 = 0;
  const Vec3 t0 = ls.tangent(sx, x, sine0);
  out.points.push_back(x), out.rho.push_back(sx.rho), out.cells.push_back(cell);
  double travelled = 0;
  for (std::size_t step = 0; step < max_steps; ++step) {
    double sine = 0;
    const Vec3 t1 = ls.tangent(sx, x, sine);
    if (sine < opt.min_sine)
      throw GeometryError(at_height(ls.c()) + "the curve passes next to a critical point (sin theta " +
                          std::to_string(sine) + "): the height is not a regular value");
    double h = opt.trace_step * ls.unit(sx.rho) * sine;
    // Closed: the start lies ahead within this step, on the line of the
    // tangent, and the curve runs there as it started (after it went some way
    // round). Where one curve comes back close to itself (a neck near a
    // saddle) its strands run the other way, and lie off the tangent line.
    const Vec3 to_start = x0 - x;
    const double ahead = to_start.dot(t1);
    if (travelled > 4 * h && to_start.norm() <= 1.5 * h && ahead > 0 && t1.dot(t0) > 0 &&
        (to_start - ahead * t1).norm() <= 0.25 * h) {
      // A stretch ends in a ball: one that comes round instead grazed its
      // ball where it started.
      if (stretch)
        throw GeometryError(at_height(ls.c()) + "a stretch of the cut came back to its start outside every ball");
      on_segment(x, x0, sx.rho);
      return out;
    }
    bool advanced = false;
    for (int halve = 0; halve < kMaxHalvings && !advanced; ++halve, h *= 0.5) {
      // Heun: the tangent at the projected Euler point, then the mean step.
      Vec3 y = x + h * t1;
      Index c2 = cell;
      skin::SkinSample sy;
      if (!ls.project(y, c2, sy)) continue;
      double sine2 = 0;
      const Vec3 t2 = ls.tangent(sy, y, sine2);
      Vec3 xn = x + 0.5 * h * (t1 + t2);
      Index c3 = c2;
      skin::SkinSample sn;
      if (!ls.project(xn, c3, sn)) continue;
      // A step that went backwards or jumped to another curve is halved.
      if ((xn - x).dot(t1) <= 0 || (xn - (x + 0.5 * h * (t1 + t2))).norm() > 0.25 * h) continue;
      if (stop && stop(x, xn)) return out;
      on_segment(x, xn, sx.rho);
      travelled += (xn - x).norm();
      x = xn, cell = c3, sx = sn, advanced = true;
    }
    if (!advanced)
      throw GeometryError(at_height(ls.c()) + "the tracer could not advance from (" + std::to_string(x.x()) + ", " +
                          std::to_string(x.y()) + ", " + std::to_string(x.z()) + ")");
    out.points.push_back(x), out.rho.push_back(sx.rho), out.cells.push_back(cell);
  }
  throw GeometryError(at_height(ls.c()) + (stretch ? "a stretch of the cut did not end" : "a curve did not close") +
                      " within " + std::to_string(max_steps) + " steps");
}

/// Samples a traced closed curve at spacings opt.spacing · rho: n = ceil(T)
/// samples at equal steps of tau = ∫ ds / (spacing · rho), T its total (at
/// least 3).
LevelCurve sample_curve(const CurveSet& ls, const Traced& tr, const LevelCurveOptions& opt) {
  const std::size_t m = tr.points.size();
  std::vector<double> tau(m + 1, 0.0);
  double length = 0;
  for (std::size_t i = 0; i < m; ++i) {
    const std::size_t j = (i + 1) % m;
    const double d = (tr.points[j] - tr.points[i]).norm();
    length += d;
    tau[i + 1] = tau[i] + d / (opt.spacing * 0.5 * (tr.rho[i] + tr.rho[j]));
  }
  const double total = tau[m];
  const std::size_t n = std::max<std::size_t>(3, static_cast<std::size_t>(std::ceil(total - 1e-9)));
  LevelCurve curve;
  curve.length = length;
  curve.points.reserve(n), curve.rho.reserve(n), curve.cells.reserve(n);
  std::size_t seg = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double target = total * static_cast<double>(k) / static_cast<double>(n);
    while (seg + 1 < m && tau[seg + 1] <= target) ++seg;
    const std::size_t j = (seg + 1) % m;
    const double span = tau[seg + 1] - tau[seg];
    const double w = span > 0 ? (target - tau[seg]) / span : 0.0;
    Vec3 y = tr.points[seg] + w * (tr.points[j] - tr.points[seg]);
    Index cell = tr.cells[seg];
    skin::SkinSample s;
    if (!ls.project(y, cell, s)) throw GeometryError(at_height(ls.c()) + "a sample does not project onto the curve");
    curve.points.push_back(y), curve.rho.push_back(s.rho), curve.cells.push_back(cell);
  }
  curve.detour.assign(n, kInvalidIndex);  // a whole circle's caller names its detour and ball
  curve.ball.assign(n, kInvalidIndex);
  return curve;
}

/// A plane {e·y = c} or a sphere {|y - q| = R}, as the second or third
/// equation of a junction.
struct Surface {
  bool sphere = false;
  Vec3 v;    ///< e, or the centre q
  double s;  ///< c, or the radius R
  double value(const Vec3& y) const { return sphere ? (y - v).squaredNorm() - s * s : v.dot(y) - s; }
  Vec3 gradient(const Vec3& y) const { return sphere ? Vec3(2 * (y - v)) : v; }
  /// The gradient's length at a point of the surface.
  double scale() const { return sphere ? 2 * s : 1.0; }
};

/// A point of F on two surfaces: where the cut turns from the plane to a
/// ball's circle, or from one ball's circle to another's.
struct Junction {
  Vec3 p;
  Index cell = kInvalidIndex;
  double rho = 0;
  std::size_t after = 0;  ///< it lies on its loop's fine edge (after, after + 1)
  bool rising = false;    ///< plane crossings: h - c goes from < 0 to >= 0 along the loop
};

/// Newton on the three equations f = 0, a = 0, b = 0 from a point next to
/// their solution. False where the three gradients are nearly dependent (the
/// surfaces meet nearly tangentially) or it does not converge.
bool refine_junction(const skin::SkinSurface& skin, const Surface& a, const Surface& b, Junction& j) {
  const double tol = 1e-12 * skin.length_scale();
  Vec3 y = j.p;
  Index cell = j.cell;
  for (int it = 0; it < kMaxProjectionSteps; ++it) {
    const skin::SkinSample s = skin.sample(y, cell);
    cell = s.cell;
    const double gn = s.gradient.norm();
    const Vec3 F(s.f, a.value(y), b.value(y));
    if (std::abs(F[0]) <= tol * gn && std::abs(F[1]) <= tol * a.scale() && std::abs(F[2]) <= tol * b.scale()) {
      j.p = y, j.cell = cell, j.rho = s.rho;
      return true;
    }
    Mat3 J;
    J.row(0) = s.gradient.transpose(), J.row(1) = a.gradient(y).transpose(), J.row(2) = b.gradient(y).transpose();
    // Divided by the rows' lengths, the determinant measures how
    // transversally the three surfaces meet.
    const double lengths = gn * J.row(1).norm() * J.row(2).norm();
    if (!(lengths > 0) || std::abs(J.determinant()) < 1e-6 * lengths) return false;
    y -= J.partialPivLu().solve(F);
  }
  return false;
}

Surface sphere_of(const DetourBall& b) { return {true, b.center, b.radius}; }

/// One closed curve of the boundary of a cluster's union of balls on F, with
/// the union on its left: arcs of the balls' circles joined at corners, and
/// its crossings of the plane in its order.
struct DetourLoop {
  Traced fine;
  std::vector<Index> ball;          ///< per fine edge (i, i + 1): the ball whose circle it follows
  std::vector<Junction> crossings;  ///< with the plane, in the loop's order
};

/// The circle F ∩ S(q, R) of one ball traced whole, the ball on its left.
Traced trace_ball_circle(const skin::SkinSurface& skin, const Vec3& e, double c, const DetourBall& b,
                         const LevelCurveOptions& opt, std::size_t max_steps) {
  const CurveSet circle = CurveSet::sphere(skin, e, c, b.center, b.radius, +1);
  // Start where the tangent plane at the centre meets the sphere.
  Index cell = kInvalidIndex;
  const skin::SkinSample s0 = skin.sample(b.center, cell);
  const Vec3 u = s0.gradient.normalized().unitOrthogonal();
  return trace_curve(circle, Seed{b.center + b.radius * u, s0.cell, s0.rho}, opt, max_steps,
                     [](const Vec3&, const Vec3&, double) {});
}

/// The boundary of the union of a cluster's balls on F (each ball meets F
/// in one disc): every circle traced whole; the runs of each circle outside
/// the other balls, from the corner where it leaves one to the corner where it
/// enters the next (Newton on f and the two spheres); the runs joined at
/// their corners into loops, and each loop's crossings of the plane.
std::vector<DetourLoop> trace_cluster_boundary(const skin::SkinSurface& skin, const Vec3& e, double c,
                                               const CutDetour& d, const LevelCurveOptions& opt,
                                               std::size_t max_steps) {
  const std::size_t nb = d.balls.size();
  const double tol = 1e-7 * skin.length_scale();
  auto inside_other = [&](std::size_t i, const Vec3& x) {
    for (std::size_t j = 0; j < nb; ++j)
      if (j != i && (x - d.balls[j].center).norm() < d.balls[j].radius) return static_cast<Index>(j);
    return kInvalidIndex;
  };
  // A run of circle i outside every other ball: its fine points, both ends
  // exact (a corner, or none for a whole circle).
  struct Run {
    std::size_t ball = 0;
    Traced fine;
    bool closed = false;  ///< the whole circle
  };
  std::vector<Run> runs;
  for (std::size_t i = 0; i < nb; ++i) {
    const Traced circle = trace_ball_circle(skin, e, c, d.balls[i], opt, max_steps);
    const std::size_t m = circle.points.size();
    std::vector<Index> in(m);
    bool any_in = false, any_out = false;
    for (std::size_t k = 0; k < m; ++k) {
      in[k] = inside_other(i, circle.points[k]);
      (in[k] == kInvalidIndex ? any_out : any_in) = true;
    }
    if (!any_out) continue;
    if (!any_in) {
      runs.push_back({i, circle, true});
      continue;
    }
    // Start just after a point inside another ball, at the first corner.
    std::size_t start = 0;
    while (!(in[start] != kInvalidIndex && in[(start + 1) % m] == kInvalidIndex)) ++start;
    Run* run = nullptr;
    for (std::size_t n = 0; n < m; ++n) {
      const std::size_t k = (start + n) % m, k1 = (k + 1) % m;
      // The corner on the edge (k, k1) where the circle leaves the union
      // (the last crossing of another ball's sphere along the edge) or enters
      // it (the first): with several balls at one end, the right one is the
      // one crossed last, or first.
      auto corner = [&](bool leaving) {
        Junction j;
        Index other = kInvalidIndex;
        double t = leaving ? -1.0 : 2.0;
        for (std::size_t b = 0; b < nb; ++b) {
          if (b == i) continue;
          const double da = (circle.points[k] - d.balls[b].center).norm() - d.balls[b].radius;
          const double db = (circle.points[k1] - d.balls[b].center).norm() - d.balls[b].radius;
          if ((da < 0) == (db < 0)) continue;
          const double tb = da / (da - db);
          if (leaving ? tb > t : tb < t) t = tb, other = static_cast<Index>(b);
        }
        if (other == kInvalidIndex) throw GeometryError(at_height(c) + "a corner of a detour's balls was not found");
        j.p = circle.points[k] + std::clamp(t, 0.0, 1.0) * (circle.points[k1] - circle.points[k]);
        j.cell = circle.cells[k];
        if (!refine_junction(skin, sphere_of(d.balls[i]), sphere_of(d.balls[other]), j))
          throw GeometryError(at_height(c) + "two balls of a detour meet on the skin too obliquely");
        return j;
      };
      if (in[k] != kInvalidIndex && in[k1] == kInvalidIndex) {
        // Leaves the union of the other balls: a run starts.
        const Junction j = corner(true);
        run = &runs.emplace_back();
        run->ball = i;
        run->fine.points.push_back(j.p), run->fine.rho.push_back(j.rho), run->fine.cells.push_back(j.cell);
      }
      if (run && in[k1] == kInvalidIndex && n + 1 < m) {
        run->fine.points.push_back(circle.points[k1]), run->fine.rho.push_back(circle.rho[k1]);
        run->fine.cells.push_back(circle.cells[k1]);
      }
      if (run && in[k] == kInvalidIndex && in[k1] != kInvalidIndex) {
        // Enters the union of the other balls: the run ends.
        const Junction j = corner(false);
        run->fine.points.push_back(j.p), run->fine.rho.push_back(j.rho), run->fine.cells.push_back(j.cell);
        run = nullptr;
      }
    }
  }
  // Join the runs end to start: a run that ends entering ball k continues
  // along k's circle from the same corner, where it leaves the first ball.
  std::vector<DetourLoop> loops;
  std::vector<char> used(runs.size(), 0);
  for (std::size_t first = 0; first < runs.size(); ++first) {
    if (used[first]) continue;
    DetourLoop loop;
    if (runs[first].closed) {
      used[first] = 1;
      loop.fine = runs[first].fine;
      loop.ball.assign(loop.fine.points.size(), static_cast<Index>(runs[first].ball));
      loops.push_back(std::move(loop));
      continue;
    }
    for (std::size_t r = first;;) {
      used[r] = 1;
      const Run& run = runs[r];
      for (std::size_t k = 0; k + 1 < run.fine.points.size(); ++k) {
        loop.fine.points.push_back(run.fine.points[k]), loop.fine.rho.push_back(run.fine.rho[k]);
        loop.fine.cells.push_back(run.fine.cells[k]), loop.ball.push_back(static_cast<Index>(run.ball));
      }
      const Vec3& end = run.fine.points.back();
      std::size_t next = runs.size();
      double best = tol;
      for (std::size_t q = 0; q < runs.size(); ++q)
        if (!runs[q].closed && (!used[q] || q == first))
          if (const double dist = (runs[q].fine.points.front() - end).norm(); dist <= best) best = dist, next = q;
      if (next == runs.size())
        throw GeometryError(at_height(c) + "the arcs of a detour's balls do not join up at a corner");
      if (next == first) break;
      r = next;
    }
    loops.push_back(std::move(loop));
  }
  // The crossings of the plane, along each loop.
  for (DetourLoop& loop : loops) {
    const Traced& t = loop.fine;
    const std::size_t m = t.points.size();
    for (std::size_t i = 0; i < m; ++i) {
      const std::size_t k = (i + 1) % m;
      const double a = e.dot(t.points[i]) - c, b = e.dot(t.points[k]) - c;
      if ((a < 0) == (b < 0)) continue;
      Junction j;
      j.p = t.points[i] + (a / (a - b)) * (t.points[k] - t.points[i]);
      j.cell = t.cells[i];
      j.after = i;
      j.rising = a < 0;
      if (!refine_junction(skin, sphere_of(d.balls[loop.ball[i]]), Surface{false, e, c}, j))
        throw GeometryError(at_height(c) + "a detour's circle meets the plane too obliquely");
      loop.crossings.push_back(j);
    }
    // Two crossings close together along the loop: the plane nearly touches
    // it there, and the level set grazes the union (in and out within a step
    // or two of the tracer). Such a height is refused: the stretch between
    // them could not be sampled anyway.
    const std::size_t nc = loop.crossings.size();
    for (std::size_t k = 0; k < nc && nc > 1; ++k) {
      const Junction& a = loop.crossings[k];
      const Junction& b = loop.crossings[(k + 1) % nc];
      // The arc from a to b along the fine polyline: a, the fine points
      // a.after + 1 … b.after, b.
      double arc = 0, rho = a.rho;
      Vec3 last = a.p;
      for (std::size_t i = a.after; i != b.after;) {
        i = (i + 1) % m;
        arc += (t.points[i] - last).norm(), last = t.points[i], rho = std::min(rho, t.rho[i]);
      }
      arc += (b.p - last).norm();
      if (arc < 0.5 * opt.spacing * std::min(rho, b.rho))
        throw GeometryError(at_height(c) + "the plane nearly touches a detour's circle");
    }
  }
  return loops;
}

/// A stretch of a cut between two junctions: its fine polyline, both ends
/// included, and per fine edge the ball whose circle it follows
/// (kInvalidIndex on the level set), in detour `detour`.
struct Piece {
  Traced fine;
  std::vector<Index> ball;
  Index detour = kInvalidIndex;
};

/// Samples the pieces of one closed cut, joined end to start. The pieces are
/// cut further where the ball changes (a corner); each part's first point is
/// a sample (a junction or corner, exactly as refined), and its inside gets
/// ceil(T) - 1 more at equal steps of tau = ∫ ds / (spacing · rho), projected
/// onto the plane or the part's sphere.
LevelCurve sample_pieces(const skin::SkinSurface& skin, const Vec3& e, double c, const std::vector<CutDetour>& detours,
                         const std::vector<Piece>& pieces, const LevelCurveOptions& opt) {
  LevelCurve curve;
  for (const Piece& piece : pieces) {
    const Traced& tr = piece.fine;
    const std::size_t m = tr.points.size();
    for (std::size_t from = 0; from + 1 < m;) {
      std::size_t to = from + 1;
      while (to + 1 < m && piece.ball[to] == piece.ball[from]) ++to;
      const Index ball = piece.ball[from];
      const CurveSet ls = ball == kInvalidIndex ? CurveSet::plane(skin, e, c)
                                                : CurveSet::sphere(skin, e, c, detours[piece.detour].balls[ball].center,
                                                                   detours[piece.detour].balls[ball].radius, +1);
      std::vector<double> tau(to - from + 1, 0.0);
      for (std::size_t i = from; i < to; ++i) {
        const double d = (tr.points[i + 1] - tr.points[i]).norm();
        curve.length += d;
        tau[i - from + 1] = tau[i - from] + d / (opt.spacing * 0.5 * (tr.rho[i] + tr.rho[i + 1]));
      }
      const double total = tau.back();
      if (total < 0.5)
        throw GeometryError(at_height(c) + "a stretch of the cut between two junctions is shorter than half a spacing");
      const std::size_t n = static_cast<std::size_t>(std::ceil(total - 1e-9));
      curve.points.push_back(tr.points[from]), curve.rho.push_back(tr.rho[from]), curve.cells.push_back(tr.cells[from]);
      curve.detour.push_back(ball == kInvalidIndex ? kInvalidIndex : piece.detour), curve.ball.push_back(ball);
      std::size_t seg = 0;
      for (std::size_t k = 1; k < n; ++k) {
        const double target = total * static_cast<double>(k) / static_cast<double>(n);
        while (seg + 2 < tau.size() && tau[seg + 1] <= target) ++seg;
        const double span = tau[seg + 1] - tau[seg];
        const double w = span > 0 ? (target - tau[seg]) / span : 0.0;
        Vec3 y = tr.points[from + seg] + w * (tr.points[from + seg + 1] - tr.points[from + seg]);
        Index cell = tr.cells[from + seg];
        skin::SkinSample s;
        if (!ls.project(y, cell, s)) throw GeometryError(at_height(c) + "a sample does not project onto the cut");
        curve.points.push_back(y), curve.rho.push_back(s.rho), curve.cells.push_back(cell);
        curve.detour.push_back(ball == kInvalidIndex ? kInvalidIndex : piece.detour), curve.ball.push_back(ball);
      }
      from = to;
    }
  }
  if (curve.points.size() < 3) throw GeometryError(at_height(c) + "a cut with a detour has fewer than three samples");
  return curve;
}

}  // namespace

std::vector<LevelCurve> level_curves(const skin::SkinSurface& skin, const MorseSmaleComplex& ms, double c,
                                     const LevelCurveOptions& opt) {
  return cut_curves(skin, ms, c, {}, opt);
}

std::vector<LevelCurve> cut_curves(const skin::SkinSurface& skin, const MorseSmaleComplex& ms, double c,
                                   const std::vector<CutDetour>& detours, const LevelCurveOptions& opt) {
  const Vec3 e = ms.height_direction.normalized();
  const CurveSet ls = CurveSet::plane(skin, e, c);
  // Bounds tied to the input's size: a curve crosses the patches of at most
  // every atom, each in a bounded number of steps of the tracer.
  const std::size_t max_steps = 100000 + 4000 * skin.points().size();
  // The first detour (in the detours' order) one of whose balls, shrunk by
  // `shrink`, meets the segment x xn, or kInvalidIndex. Every step of the
  // tracer asks: the balls are gridded by radius, so a step reads the balls
  // near it, not every ball of the cut.
  std::vector<Vec3> ball_center;
  std::vector<double> ball_radius;
  std::vector<Index> ball_detour;
  for (std::size_t d = 0; d < detours.size(); ++d)
    for (const DetourBall& b : detours[d].balls)
      ball_center.push_back(b.center), ball_radius.push_back(b.radius), ball_detour.push_back(static_cast<Index>(d));
  geometry::SizedItemGrid ball_grid;
  ball_grid.build(ball_center, ball_radius, 0);
  auto in_detour = [&](const Vec3& x, const Vec3& xn, double shrink) {
    Index first = kInvalidIndex;
    ball_grid.for_each_near(0.5 * (x + xn), 0.5 * (xn - x).norm(), [&](Index i) {
      if (ball_detour[i] < first && segment_distance(ball_center[i], x, xn) < ball_radius[i] * shrink)
        first = ball_detour[i];
    });
    return first;
  };

  // Seeds: every integral line that spans the level crosses it once (the
  // lines are monotone in h); bisect for its crossing segment.
  std::vector<Seed> seeds;
  for (const IntegralLine& line : ms.lines) {
    const auto& p = line.points;
    if (p.size() < 2) continue;
    const bool lo_below = e.dot(p.front()) < c, hi_below = e.dot(p.back()) < c;
    if (lo_below == hi_below) continue;
    std::size_t a = 0, b = p.size() - 1;
    while (b - a > 1) {
      const std::size_t mid = a + (b - a) / 2;
      ((e.dot(p[mid]) < c) == lo_below ? a : b) = mid;
    }
    // The cell of the line's point below the crossing: locating from
    // there is a short walk, from no cell a walk across the triangulation.
    seeds.push_back(seed_on_segment(ls, p[a], p[b], a < line.cells.size() ? line.cells[a] : kInvalidIndex));
  }
  // Minima at which no descending line ends: the components without saddles.
  std::unordered_set<Index> reached;
  for (const IntegralLine& line : ms.lines)
    if (line.direction < 0 && line.end != kInvalidIndex) reached.insert(line.end);
  for (std::size_t i = 0; i < ms.critical.size(); ++i) {
    const CriticalPoint& m = ms.critical[i];
    if (m.kind != CriticalKind::Minimum || m.height >= c || reached.count(static_cast<Index>(i))) continue;
    Seed s;
    if (ascend_to_level(ls, m, max_steps, s)) seeds.push_back(s);
  }
  // The level set inside a detour's balls is not part of the cut.
  if (!detours.empty())
    seeds.erase(std::remove_if(seeds.begin(), seeds.end(),
                               [&](const Seed& s) { return in_detour(s.p, s.p, 1.0) != kInvalidIndex; }),
                seeds.end());

  std::vector<Vec3> seed_points(seeds.size());
  geometry::LeveledPointGrid grid(opt.trace_step, kSeedGridOctaves, /*erasable=*/false);
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    seed_points[i] = seeds[i].p;
    grid.insert_for_queries(static_cast<Index>(i), seeds[i].p, 0.9 * seeds[i].rho, 1.1 * seeds[i].rho);
  }
  std::vector<char> consumed(seeds.size(), 0);
  // Every seed within seed_tolerance · rho of a segment of a traced curve lies on it.
  auto on_segment = [&](const Vec3& a, const Vec3& b, double rho) {
    const double tol = opt.seed_tolerance * rho;
    grid.for_each_near_at(0.5 * (a + b), 0.5 * (b - a).norm() + tol, rho, seed_points, [&](Index j, const Vec3& q) {
      if (!consumed[j] && segment_distance(q, a, b) <= tol) consumed[j] = 1;
    });
  };
  std::vector<LevelCurve> curves;

  // The detours: the boundary loops of each union of balls, their crossings
  // with the plane, and their arcs on the cut (below the plane for a detour
  // that goes up, above it for one that goes down); a loop that does not
  // meet the plane is a whole cut if it lies on the cut's side.
  struct Crossing {
    Index detour;
    std::size_t loop, k;
    bool operator<(const Crossing& o) const { return std::tie(detour, loop, k) < std::tie(o.detour, o.loop, o.k); }
  };
  std::vector<std::vector<DetourLoop>> loops(detours.size());
  std::vector<Crossing> exits;  // where the cut leaves a union of balls
  // A whole loop (or a run of it from a junction) as a piece: forwards keeps
  // the union on the left.
  auto loop_piece = [&](Index d, std::size_t l, std::size_t from, std::size_t count, bool forwards) {
    const DetourLoop& loop = loops[d][l];
    const std::size_t m = loop.fine.points.size();
    Piece piece;
    piece.detour = d;
    for (std::size_t n = 0; n < count; ++n) {
      const std::size_t i = forwards ? (from + n) % m : (from + m - n % m) % m;
      piece.fine.points.push_back(loop.fine.points[i]), piece.fine.rho.push_back(loop.fine.rho[i]);
      piece.fine.cells.push_back(loop.fine.cells[i]);
      // The edge from fine point i to the next one along the piece.
      piece.ball.push_back(forwards ? loop.ball[i] : loop.ball[(i + m - 1) % m]);
    }
    return piece;
  };
  for (std::size_t d = 0; d < detours.size(); ++d) {
    loops[d] = trace_cluster_boundary(skin, e, c, detours[d], opt, max_steps);
    for (std::size_t l = 0; l < loops[d].size(); ++l) {
      const DetourLoop& loop = loops[d][l];
      if (loop.crossings.size() % 2)
        throw GeometryError(at_height(c) + "a detour's boundary crosses the plane an odd number of times");
      if (loop.crossings.empty()) {
        if ((e.dot(loop.fine.points[0]) < c) != detours[d].upper) continue;
        // A whole loop: its pieces between corners, closed.
        const std::size_t m = loop.fine.points.size();
        const bool forwards = !detours[d].upper;
        Piece whole = loop_piece(static_cast<Index>(d), l, 0, m + 1, forwards);
        // Start at a corner, so that every part between corners is whole.
        std::size_t start = 0;
        for (std::size_t i = 0; i < m; ++i)
          if (whole.ball[i] != whole.ball[(i + m - 1) % m]) {
            start = i;
            break;
          }
        Piece rotated;
        rotated.detour = whole.detour;
        for (std::size_t n = 0; n <= m; ++n) {
          const std::size_t i = (start + n) % m;
          rotated.fine.points.push_back(whole.fine.points[i]), rotated.fine.rho.push_back(whole.fine.rho[i]);
          rotated.fine.cells.push_back(whole.fine.cells[i]), rotated.ball.push_back(whole.ball[i]);
        }
        bool corners = false;
        for (std::size_t i = 1; i < m; ++i) corners |= rotated.ball[i] != rotated.ball[0];
        if (!corners) {
          // One circle: sampled as a closed curve.
          const DetourBall& b = detours[d].balls[rotated.ball[0]];
          rotated.fine.points.pop_back(), rotated.fine.rho.pop_back(), rotated.fine.cells.pop_back();
          LevelCurve circle =
              sample_curve(CurveSet::sphere(skin, e, c, b.center, b.radius, forwards ? +1 : -1), rotated.fine, opt);
          circle.detour.assign(circle.points.size(), static_cast<Index>(d));
          circle.ball.assign(circle.points.size(), rotated.ball[0]);
          curves.push_back(std::move(circle));
        } else {
          curves.push_back(sample_pieces(skin, e, c, detours, {rotated}, opt));
        }
        continue;
      }
      // At a crossing on ball b's arc, e·(n × u_b) = -(n × e)·u_b: where h
      // rises along the loop (the union on its left), the level set's
      // tangent n × e points into the union. So the cut enters a union at its
      // rising crossings and leaves it at its falling ones, whichever way it
      // goes. Along the loop, an arc from a falling crossing to the next
      // rising one lies below the plane: a detour that goes up keeps those,
      // run backwards (the union on the cut's right) from a rising crossing
      // to the falling one before it; one that goes down keeps the arcs
      // above, run forwards from a rising crossing to the next falling one.
      for (std::size_t k = 0; k < loop.crossings.size(); ++k)
        if (!loop.crossings[k].rising) exits.push_back({static_cast<Index>(d), l, k});
    }
  }
  // The arc of a detour's loop from its crossing `entry` (where the level
  // set enters the union) to the crossing where it leaves, both included.
  auto arc_from = [&](const Crossing& entry, Crossing& exit) {
    const DetourLoop& loop = loops[entry.detour][entry.loop];
    const std::size_t nc = loop.crossings.size(), m = loop.fine.points.size();
    const bool up = detours[entry.detour].upper;
    exit = entry;
    exit.k = up ? (entry.k + nc - 1) % nc : (entry.k + 1) % nc;
    const Junction& a = loop.crossings[entry.k];
    const Junction& b = loop.crossings[exit.k];
    Piece piece;
    piece.detour = entry.detour;
    auto push = [&](const Vec3& p, double rho, Index cell, Index ball) {
      piece.fine.points.push_back(p), piece.fine.rho.push_back(rho), piece.fine.cells.push_back(cell);
      piece.ball.push_back(ball);
    };
    // Edge (i, i + 1) of the loop follows loop.ball[i]; run backwards, the
    // piece's edge from fine point i to i - 1 follows loop.ball[i - 1].
    if (up) {
      push(a.p, a.rho, a.cell, loop.ball[a.after]);
      for (std::size_t i = a.after; i != b.after; i = (i + m - 1) % m)
        push(loop.fine.points[i], loop.fine.rho[i], loop.fine.cells[i], loop.ball[(i + m - 1) % m]);
    } else {
      push(a.p, a.rho, a.cell, loop.ball[a.after]);
      for (std::size_t i = a.after; i != b.after;) {
        i = (i + 1) % m;
        push(loop.fine.points[i], loop.fine.rho[i], loop.fine.cells[i], loop.ball[i]);
      }
    }
    push(b.p, b.rho, b.cell, kInvalidIndex);
    return piece;
  };
  // Check the junctions' orientation: the level set's tangent n × e points
  // out of the union where the cut leaves it.
  for (const Crossing& x : exits) {
    const DetourLoop& loop = loops[x.detour][x.loop];
    const Junction& j = loop.crossings[x.k];
    const Vec3 q = detours[x.detour].balls[loop.ball[j.after]].center;
    const skin::SkinSample s = skin.sample(j.p, j.cell);
    if ((s.gradient.normalized().cross(e)).dot(j.p - q) <= 0)
      throw GeometryError(at_height(c) + "the level set does not leave a detour's ball where its circle says");
  }
  // The level stretches: from each crossing where the cut leaves a union,
  // along n × e, until the tracer enters a union; there the cut takes the
  // crossing where the level set enters it.
  std::map<Crossing, std::size_t> stretch_of_exit;
  std::vector<Piece> stretches;
  std::vector<Crossing> stretch_end;
  for (const Crossing& x : exits) {
    const Junction& j = loops[x.detour][x.loop].crossings[x.k];
    Crossing end{kInvalidIndex, 0, 0};
    auto stop = [&](const Vec3& p, const Vec3& pn) {
      const Index d = in_detour(p, pn, 1 - 1e-9);
      if (d == kInvalidIndex) return false;
      // The entry crossing of that union nearest to the step.
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t l = 0; l < loops[d].size(); ++l)
        for (std::size_t k = 0; k < loops[d][l].crossings.size(); ++k) {
          const Junction& q = loops[d][l].crossings[k];
          if (!q.rising) continue;  // a crossing where the cut leaves
          if (const double dist = segment_distance(q.p, p, pn); dist < best) best = dist, end = {d, l, k};
        }
      if (!(best <= 2 * (pn - p).norm() + 1e-9 * skin.length_scale()))
        throw GeometryError(at_height(c) + "the level set enters a detour's ball away from its crossings");
      return true;
    };
    Piece piece;
    piece.fine = trace_curve(ls, Seed{j.p, j.cell, j.rho}, opt, max_steps, on_segment, stop, /*stretch=*/true);
    const Junction& q = loops[end.detour][end.loop].crossings[end.k];
    piece.fine.points.push_back(q.p), piece.fine.rho.push_back(q.rho), piece.fine.cells.push_back(q.cell);
    piece.ball.assign(piece.fine.points.size(), kInvalidIndex);
    stretch_of_exit[x] = stretches.size();
    stretches.push_back(std::move(piece));
    stretch_end.push_back(end);
  }
  // Join stretches and arcs into closed cuts, each from its first exit.
  std::vector<char> used(stretches.size(), 0);
  for (std::size_t first = 0; first < stretches.size(); ++first) {
    if (used[first]) continue;
    std::vector<Piece> pieces;
    for (std::size_t s = first; !used[s];) {
      used[s] = 1;
      pieces.push_back(stretches[s]);
      Crossing exit{};
      pieces.push_back(arc_from(stretch_end[s], exit));
      const auto it = stretch_of_exit.find(exit);
      if (it == stretch_of_exit.end())
        throw GeometryError(at_height(c) + "a detour's arc does not end where the cut leaves its ball");
      s = it->second;
      if (s != first && used[s]) throw GeometryError(at_height(c) + "two stretches of the cut end at one arc");
    }
    // Each stretch's last point is the next arc's first, and each arc's last
    // the next stretch's first: drop the duplicates.
    for (Piece& p : pieces) p.fine.points.pop_back(), p.fine.rho.pop_back(), p.fine.cells.pop_back(), p.ball.pop_back();
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const Piece& next = pieces[(i + 1) % pieces.size()];
      Piece& p = pieces[i];
      p.fine.points.push_back(next.fine.points[0]), p.fine.rho.push_back(next.fine.rho[0]);
      p.fine.cells.push_back(next.fine.cells[0]), p.ball.push_back(kInvalidIndex);
    }
    curves.push_back(sample_pieces(skin, e, c, detours, pieces, opt));
  }

  // The level curves that meet no ball.
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    if (consumed[i]) continue;
    consumed[i] = 1;
    StopTest stop = nullptr;
    if (!detours.empty())
      stop = [&](const Vec3& x, const Vec3& xn) -> bool {
        if (in_detour(x, xn, 1 - 1e-9) != kInvalidIndex)
          throw GeometryError(at_height(c) + "a level curve enters a detour's ball but no crossing leads to it");
        return false;
      };
    curves.push_back(sample_curve(ls, trace_curve(ls, seeds[i], opt, max_steps, on_segment, stop), opt));
  }
  return curves;
}

std::vector<CutDetour> cut_detours(const MorseSmaleComplex& ms, double c, const CutDetourOptions& opt) {
  const std::size_t n = ms.critical.size();
  auto ball_radius = [&](std::size_t i) {
    return (1 + opt.margin) * (i < ms.protect_radius.size() ? ms.protect_radius[i] : 0.0);
  };
  double r_max = 0;
  std::vector<std::size_t> by_height(n);
  for (std::size_t i = 0; i < n; ++i) by_height[i] = i, r_max = std::max(r_max, ball_radius(i));
  std::sort(by_height.begin(), by_height.end(), [&](std::size_t a, std::size_t b) {
    return ms.critical[a].height < ms.critical[b].height || (ms.critical[a].height == ms.critical[b].height && a < b);
  });
  // Visits the critical points whose heights lie in [lo, hi].
  auto in_heights = [&](double lo, double hi, const std::function<void(std::size_t)>& fn) {
    auto first = std::lower_bound(by_height.begin(), by_height.end(), lo,
                                  [&](std::size_t i, double h) { return ms.critical[i].height < h; });
    for (auto it = first; it != by_height.end() && ms.critical[*it].height <= hi; ++it) fn(*it);
  };
  // Union–find over the critical points; a breadth-first growth from the
  // balls that meet the plane adds every ball that overlaps one in the set.
  std::vector<std::size_t> parent(n);
  for (std::size_t i = 0; i < n; ++i) parent[i] = i;
  std::function<std::size_t(std::size_t)> find = [&](std::size_t a) {
    return parent[a] == a ? a : parent[a] = find(parent[a]);
  };
  std::vector<char> in_set(n, 0);
  std::vector<std::size_t> queue;
  in_heights(c - r_max, c + r_max, [&](std::size_t i) {
    if (ball_radius(i) > 0 && std::abs(ms.critical[i].height - c) < ball_radius(i)) in_set[i] = 1, queue.push_back(i);
  });
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::size_t a = queue[head];
    const CriticalPoint& p = ms.critical[a];
    const double R = ball_radius(a);
    in_heights(p.height - R - r_max, p.height + R + r_max, [&](std::size_t b) {
      if (b == a || !(ball_radius(b) > 0) || (ms.critical[b].position - p.position).norm() >= R + ball_radius(b))
        return;
      parent[find(a)] = find(b);
      if (!in_set[b]) in_set[b] = 1, queue.push_back(b);
    });
  }
  std::vector<CutDetour> out;
  std::vector<std::size_t> cluster_of(n, std::numeric_limits<std::size_t>::max());
  std::vector<double> height_sum;
  for (std::size_t i = 0; i < n; ++i) {
    if (!in_set[i]) continue;
    std::size_t& k = cluster_of[find(i)];
    if (k == std::numeric_limits<std::size_t>::max()) k = out.size(), out.emplace_back(), height_sum.push_back(0);
    out[k].balls.push_back({ms.critical[i].position, ball_radius(i), static_cast<Index>(i)});
    height_sum[k] += ms.critical[i].height;
  }
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k].upper = height_sum[k] / static_cast<double>(out[k].balls.size()) > c;
  return out;
}

double cut_clearance(const MorseSmaleComplex& ms, double c) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < ms.critical.size(); ++i) {
    const CriticalPoint& p = ms.critical[i];
    const double s = i < ms.protect_radius.size() ? ms.protect_radius[i] : 0.0;
    if (p.rho > 0) best = std::min(best, (std::abs(p.height - c) - s) / p.rho);
  }
  return best;
}

}  // namespace skinmesh::morse
