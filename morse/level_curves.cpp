// morse/level_curves.cpp: seeds from the Morse–Smale complex, a predictor–
// corrector on F ∩ {e·x = c}, and sampling by rho (papers/morse/level_curves.md).
#include "morse/level_curves.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
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
  curve.detour.assign(n, kInvalidIndex);  // a whole circle's caller names its ball
  return curve;
}

/// A point where a detour's circle crosses the plane: on F, on the sphere and
/// on the plane (a junction of the cut, where it turns between the two).
struct Junction {
  Vec3 p;
  Index cell = kInvalidIndex;
  double rho = 0;
  std::size_t after = 0;  ///< the crossing lies on the circle's fine edge (after, after + 1)
  bool rising = false;    ///< h - c goes from < 0 to >= 0 along the circle's orientation
};

/// Newton on the three equations f = 0, |y - q|² = R², e·y = c, from a point
/// next to their solution. False where the three gradients are nearly
/// dependent (the circle touches the plane) or it does not converge.
bool refine_junction(const skin::SkinSurface& skin, const Vec3& e, double c, const Vec3& q, double R, Junction& j) {
  const double tol = 1e-12 * skin.length_scale();
  Vec3 y = j.p;
  Index cell = j.cell;
  for (int it = 0; it < kMaxProjectionSteps; ++it) {
    const skin::SkinSample s = skin.sample(y, cell);
    cell = s.cell;
    const double gn = s.gradient.norm();
    const Vec3 r = y - q;
    const Vec3 F(s.f, r.squaredNorm() - R * R, e.dot(y) - c);
    if (std::abs(F[0]) <= tol * gn && std::abs(F[1]) <= tol * 2 * R && std::abs(F[2]) <= tol) {
      j.p = y, j.cell = cell, j.rho = s.rho;
      return true;
    }
    Mat3 J;
    J.row(0) = s.gradient.transpose(), J.row(1) = 2 * r.transpose(), J.row(2) = e.transpose();
    // Divided by the rows' lengths (e is a unit vector), the determinant
    // measures how transversally the three surfaces meet.
    if (!(gn > 0) || !(r.norm() > 0)) return false;
    if (std::abs(J.determinant()) < 1e-6 * gn * 2 * r.norm()) return false;
    y -= J.partialPivLu().solve(F);
  }
  return false;
}

/// One detour's circle traced whole, with its crossings of the plane in the
/// circle's order.
struct DetourCircle {
  Traced circle;                    ///< oriented by n × u (the ball on the left)
  std::vector<Junction> crossings;  ///< in the order of the circle
};

DetourCircle trace_detour_circle(const skin::SkinSurface& skin, const Vec3& e, double c, const CutDetour& d,
                                 const LevelCurveOptions& opt, std::size_t max_steps) {
  const CurveSet circle = CurveSet::sphere(skin, e, c, d.center, d.radius, +1);
  // Start where the tangent plane at the centre meets the sphere.
  Index cell = kInvalidIndex;
  const skin::SkinSample s0 = skin.sample(d.center, cell);
  const Vec3 n = s0.gradient.normalized();
  const Vec3 u = n.unitOrthogonal();
  Seed seed{d.center + d.radius * u, s0.cell, s0.rho};
  DetourCircle out;
  out.circle = trace_curve(circle, seed, opt, max_steps, [](const Vec3&, const Vec3&, double) {});
  const Traced& t = out.circle;
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
    if (!refine_junction(skin, e, c, d.center, d.radius, j))
      throw GeometryError(at_height(c) + "a detour's circle meets the plane too obliquely");
    out.crossings.push_back(j);
  }
  // Two crossings close together along the circle: the plane nearly touches
  // it there, and the level set grazes the ball (in and out within a step or
  // two of the tracer). Such a height is refused: the stretch between them
  // could not be sampled anyway.
  const std::size_t nc = out.crossings.size();
  for (std::size_t k = 0; k < nc && nc > 1; ++k) {
    const Junction& a = out.crossings[k];
    const Junction& b = out.crossings[(k + 1) % nc];
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
  return out;
}

/// A stretch of a cut between two junctions (or a whole closed curve): its
/// fine polyline, both ends included for a stretch, and the curve it lies on.
struct Piece {
  Traced fine;
  Index detour = kInvalidIndex;  ///< the circle it follows, kInvalidIndex on the level set
};

/// Samples the pieces of one closed cut, joined end to start: each piece's
/// first point is a sample (the junction, exactly as refined), and its inside
/// gets ceil(T) - 1 more at equal steps of tau = ∫ ds / (spacing · rho).
LevelCurve sample_pieces(const skin::SkinSurface& skin, const Vec3& e, double c, const std::vector<CutDetour>& detours,
                         const std::vector<Piece>& pieces, const LevelCurveOptions& opt) {
  LevelCurve curve;
  for (const Piece& piece : pieces) {
    const Traced& tr = piece.fine;
    const CurveSet ls = piece.detour == kInvalidIndex ? CurveSet::plane(skin, e, c)
                                                      : CurveSet::sphere(skin, e, c, detours[piece.detour].center,
                                                                         detours[piece.detour].radius, +1);
    const std::size_t m = tr.points.size();
    std::vector<double> tau(m, 0.0);
    for (std::size_t i = 0; i + 1 < m; ++i) {
      const double d = (tr.points[i + 1] - tr.points[i]).norm();
      curve.length += d;
      tau[i + 1] = tau[i] + d / (opt.spacing * 0.5 * (tr.rho[i] + tr.rho[i + 1]));
    }
    const double total = tau[m - 1];
    if (total < 0.5)
      throw GeometryError(at_height(c) + "a stretch of the cut between two junctions is shorter than half a spacing");
    const std::size_t n = static_cast<std::size_t>(std::ceil(total - 1e-9));
    curve.points.push_back(tr.points[0]), curve.rho.push_back(tr.rho[0]), curve.cells.push_back(tr.cells[0]);
    curve.detour.push_back(piece.detour);
    std::size_t seg = 0;
    for (std::size_t k = 1; k < n; ++k) {
      const double target = total * static_cast<double>(k) / static_cast<double>(n);
      while (seg + 2 < m && tau[seg + 1] <= target) ++seg;
      const double span = tau[seg + 1] - tau[seg];
      const double w = span > 0 ? (target - tau[seg]) / span : 0.0;
      Vec3 y = tr.points[seg] + w * (tr.points[seg + 1] - tr.points[seg]);
      Index cell = tr.cells[seg];
      skin::SkinSample s;
      if (!ls.project(y, cell, s)) throw GeometryError(at_height(c) + "a sample does not project onto the cut");
      curve.points.push_back(y), curve.rho.push_back(s.rho), curve.cells.push_back(cell);
      curve.detour.push_back(piece.detour);
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
  auto in_disc = [&](const Vec3& p) {
    for (std::size_t d = 0; d < detours.size(); ++d)
      if ((p - detours[d].center).norm() < detours[d].radius) return static_cast<Index>(d);
    return kInvalidIndex;
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
    seeds.push_back(seed_on_segment(ls, p[a], p[b], kInvalidIndex));
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
  // The level set inside a detour's ball is not part of the cut.
  if (!detours.empty())
    seeds.erase(
        std::remove_if(seeds.begin(), seeds.end(), [&](const Seed& s) { return in_disc(s.p) != kInvalidIndex; }),
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

  // The detours: each circle whole, its crossings with the plane, and its
  // arcs on the cut (below the plane for a ball that goes up, above it for
  // one that goes down); a circle that does not meet the plane is a whole
  // cut if it lies on the cut's side.
  std::vector<DetourCircle> circles;
  std::vector<std::pair<Index, std::size_t>> exits;  // (detour, crossing) where the cut leaves a circle
  for (std::size_t d = 0; d < detours.size(); ++d) {
    circles.push_back(trace_detour_circle(skin, e, c, detours[d], opt, max_steps));
    const DetourCircle& dc = circles.back();
    if (dc.crossings.size() % 2)
      throw GeometryError(at_height(c) + "a detour's circle crosses the plane an odd number of times");
    if (dc.crossings.empty()) {
      const bool below = e.dot(dc.circle.points[0]) < c;
      if (below == detours[d].upper) {
        LevelCurve whole =
            sample_curve(CurveSet::sphere(skin, e, c, detours[d].center, detours[d].radius, detours[d].upper ? -1 : +1),
                         detours[d].upper ? Traced{{dc.circle.points.rbegin(), dc.circle.points.rend()},
                                                   {dc.circle.rho.rbegin(), dc.circle.rho.rend()},
                                                   {dc.circle.cells.rbegin(), dc.circle.cells.rend()}}
                                          : dc.circle,
                         opt);
        whole.detour.assign(whole.points.size(), static_cast<Index>(d));
        curves.push_back(std::move(whole));
      }
      continue;
    }
    // At a crossing, e·(n × u) = -(n × e)·u: where h rises along the circle
    // (the ball on its left), the level set's tangent n × e points into the
    // ball. So the cut enters a ball at its rising crossings and leaves it at
    // its falling ones, whichever way the ball goes. Along the circle, an arc
    // from a falling crossing to the next rising one lies below the plane: a
    // ball that goes up keeps those, run backwards (the ball on the cut's
    // right) from a rising crossing to the falling one before it; a ball
    // that goes down keeps the arcs above, run forwards from a rising
    // crossing to the next falling one.
    for (std::size_t k = 0; k < dc.crossings.size(); ++k)
      if (!dc.crossings[k].rising) exits.emplace_back(static_cast<Index>(d), k);
  }
  // The arc of detour d that starts at its crossing `entry` (where the
  // level set enters the ball), ending at the crossing where it leaves.
  auto arc_from = [&](Index d, std::size_t entry, std::size_t& exit) {
    const DetourCircle& dc = circles[d];
    const std::size_t nc = dc.crossings.size(), m = dc.circle.points.size();
    const bool up = detours[d].upper;
    exit = up ? (entry + nc - 1) % nc : (entry + 1) % nc;
    Piece piece;
    piece.detour = d;
    const Junction& a = dc.crossings[entry];
    const Junction& b = dc.crossings[exit];
    auto push = [&](const Vec3& p, double rho, Index cell) {
      piece.fine.points.push_back(p), piece.fine.rho.push_back(rho), piece.fine.cells.push_back(cell);
    };
    push(a.p, a.rho, a.cell);
    if (up) {
      // Backwards from the fine point a.after down to b.after + 1.
      for (std::size_t i = a.after; i != b.after; i = (i + m - 1) % m)
        push(dc.circle.points[i], dc.circle.rho[i], dc.circle.cells[i]);
    } else {
      // Forwards from the fine point a.after + 1 up to b.after.
      for (std::size_t i = a.after; i != b.after;) {
        i = (i + 1) % m;
        push(dc.circle.points[i], dc.circle.rho[i], dc.circle.cells[i]);
      }
    }
    push(b.p, b.rho, b.cell);
    return piece;
  };
  // Check the junctions' orientation: the level set's tangent n × e points
  // out of the ball where the cut leaves it.
  for (const auto& [d, k] : exits) {
    const Junction& j = circles[d].crossings[k];
    const skin::SkinSample s = skin.sample(j.p, j.cell);
    if ((s.gradient.normalized().cross(e)).dot(j.p - detours[d].center) <= 0)
      throw GeometryError(at_height(c) + "the level set does not leave a detour's ball where its circle says");
  }
  // The level stretches: from each crossing where the cut leaves a ball, along
  // n × e, until the tracer enters a ball; there the cut takes the crossing
  // where the level set enters that ball.
  std::map<std::pair<Index, std::size_t>, std::size_t> stretch_of_exit;
  std::vector<Piece> stretches;
  std::vector<std::pair<Index, std::size_t>> stretch_end;
  for (const auto& [d, k] : exits) {
    const Junction& j = circles[d].crossings[k];
    std::pair<Index, std::size_t> end{kInvalidIndex, 0};
    auto stop = [&](const Vec3& x, const Vec3& xn) {
      for (std::size_t b = 0; b < detours.size(); ++b) {
        if (segment_distance(detours[b].center, x, xn) >= detours[b].radius * (1 - 1e-9)) continue;
        // The entry crossing of ball b nearest to the step.
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < circles[b].crossings.size(); ++i) {
          const Junction& q = circles[b].crossings[i];
          if (!q.rising) continue;  // a crossing where the cut leaves
          if (const double dist = segment_distance(q.p, x, xn); dist < best)
            best = dist, end = {static_cast<Index>(b), i};
        }
        if (!(best <= 2 * (xn - x).norm() + 1e-9 * skin.length_scale()))
          throw GeometryError(at_height(c) + "the level set enters a detour's ball away from its crossings");
        return true;
      }
      return false;
    };
    Piece piece;
    piece.fine = trace_curve(ls, Seed{j.p, j.cell, j.rho}, opt, max_steps, on_segment, stop, /*stretch=*/true);
    const Junction& q = circles[end.first].crossings[end.second];
    piece.fine.points.push_back(q.p), piece.fine.rho.push_back(q.rho), piece.fine.cells.push_back(q.cell);
    stretch_of_exit[{d, k}] = stretches.size();
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
      std::size_t exit = 0;
      pieces.push_back(arc_from(stretch_end[s].first, stretch_end[s].second, exit));
      const auto it = stretch_of_exit.find({stretch_end[s].first, exit});
      if (it == stretch_of_exit.end())
        throw GeometryError(at_height(c) + "a detour's arc does not end where the cut leaves its ball");
      s = it->second;
      if (s != first && used[s]) throw GeometryError(at_height(c) + "two stretches of the cut end at one arc");
    }
    // Each stretch's last point is the next arc's first, and each arc's last
    // the next stretch's first: drop the duplicates.
    for (Piece& p : pieces) p.fine.points.pop_back(), p.fine.rho.pop_back(), p.fine.cells.pop_back();
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const Piece& next = pieces[(i + 1) % pieces.size()];
      Piece& p = pieces[i];
      p.fine.points.push_back(next.fine.points[0]), p.fine.rho.push_back(next.fine.rho[0]);
      p.fine.cells.push_back(next.fine.cells[0]);
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
        for (const CutDetour& d : detours)
          if (segment_distance(d.center, x, xn) < d.radius * (1 - 1e-9))
            throw GeometryError(at_height(c) + "a level curve enters a detour's ball but no crossing leads to it");
        return false;
      };
    curves.push_back(sample_curve(ls, trace_curve(ls, seeds[i], opt, max_steps, on_segment, stop), opt));
  }
  return curves;
}

bool cut_detours(const MorseSmaleComplex& ms, double c, const CutDetourOptions& opt, std::vector<CutDetour>& out) {
  out.clear();
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
  // The critical points whose heights lie in [lo, hi], by the sorted order.
  auto in_heights = [&](double lo, double hi, const std::function<void(std::size_t)>& fn) {
    auto first = std::lower_bound(by_height.begin(), by_height.end(), lo,
                                  [&](std::size_t i, double h) { return ms.critical[i].height < h; });
    for (auto it = first; it != by_height.end() && ms.critical[*it].height <= hi; ++it) fn(*it);
  };
  // A cluster's ball: about its member with the largest ball (the first on
  // ties), wide enough to hold every member's ball.
  struct Cluster {
    std::vector<Index> members;
    std::size_t center = 0;
    double radius = 0;
  };
  // A cluster's ball: about the member that needs the smallest ball to hold
  // every member's ball, relative to its rho (the first on ties).
  auto fit = [&](Cluster& k) {
    double best = std::numeric_limits<double>::infinity();
    for (Index q : k.members) {
      double r = 0;
      for (Index m : k.members)
        r = std::max(r, (ms.critical[m].position - ms.critical[q].position).norm() + ball_radius(m));
      if (r / ms.critical[q].rho < best) best = r / ms.critical[q].rho, k.center = q, k.radius = r;
    }
  };
  std::vector<Cluster> clusters;
  std::vector<std::size_t> cluster_of(n, std::numeric_limits<std::size_t>::max());
  in_heights(c - r_max, c + r_max, [&](std::size_t i) {
    if (ball_radius(i) > 0 && std::abs(ms.critical[i].height - c) < ball_radius(i)) {
      cluster_of[i] = clusters.size();
      clusters.push_back({{static_cast<Index>(i)}, i, ball_radius(i)});
    }
  });
  // Merge until no two balls overlap, and no ball overlaps a critical
  // point's ball outside every cluster.
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t a = 0; a < clusters.size(); ++a) {
      if (clusters[a].members.empty()) continue;
      const Vec3 q = ms.critical[clusters[a].center].position;
      const double h = ms.critical[clusters[a].center].height, R = clusters[a].radius;
      std::vector<std::size_t> absorb;
      in_heights(h - R - r_max, h + R + r_max, [&](std::size_t i) {
        if (cluster_of[i] == a || !(ball_radius(i) > 0)) return;
        if ((ms.critical[i].position - q).norm() < R + ball_radius(i)) absorb.push_back(i);
      });
      for (std::size_t i : absorb) {
        if (cluster_of[i] == a) continue;
        if (cluster_of[i] < clusters.size()) {
          Cluster& b = clusters[cluster_of[i]];
          for (Index m : b.members) cluster_of[m] = a, clusters[a].members.push_back(m);
          b.members.clear();
        } else {
          cluster_of[i] = a, clusters[a].members.push_back(static_cast<Index>(i));
        }
        changed = true;
      }
      if (changed) {
        std::sort(clusters[a].members.begin(), clusters[a].members.end());
        fit(clusters[a]);
        if (clusters[a].radius > opt.max_radius * ms.critical[clusters[a].center].rho) return false;
      }
    }
  }
  for (const Cluster& k : clusters) {
    if (k.members.empty()) continue;
    CutDetour d;
    d.center = ms.critical[k.center].position;
    d.radius = k.radius;
    d.upper = ms.critical[k.center].height > c;
    d.critical.push_back(static_cast<Index>(k.center));
    for (Index m : k.members)
      if (m != k.center) d.critical.push_back(m);
    out.push_back(std::move(d));
  }
  return true;
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
