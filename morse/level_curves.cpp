// morse/level_curves.cpp: seeds from the Morse–Smale complex, a predictor–
// corrector on F ∩ {e·x = c}, and sampling by rho (papers/morse/level_curves.md).
#include "morse/level_curves.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
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

/// The geometry of one level set F ∩ {e·x = c}.
class LevelSet {
 public:
  LevelSet(const skin::SkinSurface& skin, const Vec3& e, double c)
      : skin_(skin), e_(e), c_(c), tolerance_(1e-12 * skin.length_scale()) {}

  /// Moves y onto the curve: onto the plane, then Newton on f along the
  /// gradient's component in the plane (which keeps y on it). True if
  /// |f| / |grad_plane f| fell below the tolerance; `s` is then the sample at y
  /// and `cell` its cell.
  bool project(Vec3& y, Index& cell, skin::SkinSample& s) const {
    for (int it = 0; it < kMaxProjectionSteps; ++it) {
      y -= (e_.dot(y) - c_) * e_;
      s = skin_.sample(y, cell);
      cell = s.cell;
      const Vec3 gp = s.gradient - s.gradient.dot(e_) * e_;
      const double g2 = gp.squaredNorm();
      if (!(g2 > 0)) return false;
      if (std::abs(s.f) <= tolerance_ * std::sqrt(g2)) return true;
      y -= (s.f / g2) * gp;
    }
    return false;
  }

  /// Unit tangent n × e / |n × e| at a sample and sin(theta) = |n × e|.
  Vec3 tangent(const skin::SkinSample& s, double& sine) const {
    const Vec3 t = s.gradient.normalized().cross(e_);
    sine = t.norm();
    return sine > 0 ? Vec3(t / sine) : Vec3::Zero();
  }

  const skin::SkinSurface& skin() const { return skin_; }
  const Vec3& e() const { return e_; }
  double c() const { return c_; }

 private:
  const skin::SkinSurface& skin_;
  Vec3 e_;
  double c_;
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
Seed seed_on_segment(const LevelSet& ls, const Vec3& a, const Vec3& b, Index hint) {
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
bool ascend_to_level(const LevelSet& ls, const CriticalPoint& m, std::size_t max_steps, Seed& out) {
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

/// One closed curve traced from a seed: the points of the fine polyline and
/// their samples.
struct Traced {
  std::vector<Vec3> points;
  std::vector<double> rho;
  std::vector<Index> cells;
};

Traced trace_curve(const LevelSet& ls, const Seed& seed, const LevelCurveOptions& opt, std::size_t max_steps,
                   const std::function<void(const Vec3&, const Vec3&, double)>& on_segment) {
  Traced out;
  Vec3 x = seed.p;
  Index cell = seed.cell;
  skin::SkinSample sx;
  if (!ls.project(x, cell, sx)) throw GeometryError(at_height(ls.c()) + "a seed does not project onto the curve");
  const Vec3 x0 = x;
  double sine0 = 0;
  const Vec3 t0 = ls.tangent(sx, sine0);
  out.points.push_back(x), out.rho.push_back(sx.rho), out.cells.push_back(cell);
  double travelled = 0;
  for (std::size_t step = 0; step < max_steps; ++step) {
    double sine = 0;
    const Vec3 t1 = ls.tangent(sx, sine);
    if (sine < opt.min_sine)
      throw GeometryError(at_height(ls.c()) + "the curve passes next to a critical point (sin theta " +
                          std::to_string(sine) + "): the height is not a regular value");
    double h = opt.trace_step * sx.rho * sine;
    // Closed: the start lies ahead within this step, on the line of the
    // tangent, and the curve runs there as it started (after it went some way
    // round). Where one curve comes back close to itself (a neck near a
    // saddle) its strands run the other way, and lie off the tangent line.
    const Vec3 to_start = x0 - x;
    const double ahead = to_start.dot(t1);
    if (travelled > 4 * h && to_start.norm() <= 1.5 * h && ahead > 0 && t1.dot(t0) > 0 &&
        (to_start - ahead * t1).norm() <= 0.25 * h) {
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
      const Vec3 t2 = ls.tangent(sy, sine2);
      Vec3 xn = x + 0.5 * h * (t1 + t2);
      Index c3 = c2;
      skin::SkinSample sn;
      if (!ls.project(xn, c3, sn)) continue;
      // A step that went backwards or jumped to another curve is halved.
      if ((xn - x).dot(t1) <= 0 || (xn - (x + 0.5 * h * (t1 + t2))).norm() > 0.25 * h) continue;
      on_segment(x, xn, sx.rho);
      travelled += (xn - x).norm();
      x = xn, cell = c3, sx = sn, advanced = true;
    }
    if (!advanced)
      throw GeometryError(at_height(ls.c()) + "the tracer could not advance from (" + std::to_string(x.x()) + ", " +
                          std::to_string(x.y()) + ", " + std::to_string(x.z()) + ")");
    out.points.push_back(x), out.rho.push_back(sx.rho), out.cells.push_back(cell);
  }
  throw GeometryError(at_height(ls.c()) + "a curve did not close within " + std::to_string(max_steps) + " steps");
}

/// Samples a traced curve at spacings opt.spacing · rho: n = ceil(T) samples
/// at equal steps of tau = ∫ ds / (spacing · rho), T its total (at least 3).
LevelCurve sample_curve(const LevelSet& ls, const Traced& tr, const LevelCurveOptions& opt) {
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
  return curve;
}

}  // namespace

std::vector<LevelCurve> level_curves(const skin::SkinSurface& skin, const MorseSmaleComplex& ms, double c,
                                     const LevelCurveOptions& opt) {
  const Vec3 e = ms.height_direction.normalized();
  const LevelSet ls(skin, e, c);
  // Bounds tied to the input's size: a curve crosses the patches of at most
  // every atom, each in a bounded number of steps of the tracer.
  const std::size_t max_steps = 100000 + 4000 * skin.points().size();

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

  std::vector<Vec3> seed_points(seeds.size());
  geometry::LeveledPointGrid grid(opt.trace_step, kSeedGridOctaves, /*erasable=*/false);
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    seed_points[i] = seeds[i].p;
    grid.insert_for_queries(static_cast<Index>(i), seeds[i].p, 0.9 * seeds[i].rho, 1.1 * seeds[i].rho);
  }
  std::vector<char> consumed(seeds.size(), 0);
  std::vector<LevelCurve> curves;
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    if (consumed[i]) continue;
    consumed[i] = 1;
    // Every seed within seed_tolerance · rho of a segment of the curve lies on it.
    auto on_segment = [&](const Vec3& a, const Vec3& b, double rho) {
      const double tol = opt.seed_tolerance * rho;
      grid.for_each_near_at(0.5 * (a + b), 0.5 * (b - a).norm() + tol, rho, seed_points, [&](Index j, const Vec3& q) {
        if (!consumed[j] && segment_distance(q, a, b) <= tol) consumed[j] = 1;
      });
    };
    curves.push_back(sample_curve(ls, trace_curve(ls, seeds[i], opt, max_steps, on_segment), opt));
  }
  return curves;
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
