// decompose/band.cpp: the max-min-angle strip between two closed polylines
// (decompose/band.h). A strip is a monotone path through the grid of states
// (i, j): the triangle fan so far ends at the connecting edge from rim vertex
// i to the j-th curve vertex met walking the curve backwards from the start.
// Each step adds one triangle (a rim edge or a curve edge with the current
// vertex of the other side), so the best smallest angle of a path to (i, j)
// is a bottleneck recurrence over its two predecessors, and the least sum
// above a floor a shortest-path one: two passes per start.
// Notes: papers/decompose/README.md ("The band's strip")
#include "decompose/band.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "geometry/check/mesh_checks.h"

namespace skinmesh::decompose {
namespace {

/// Curve vertices tried on each side of the one nearest to rim vertex 0 as
/// the strip's start. [measured] 2: in a standing ring's band (stress case
/// ring/torus/n12/p1.4) the nearest start forced a 5° first triangle, the
/// next sample an 18° one.
constexpr std::size_t kStartReach = 2;

/// Cumulative arc length of a closed polyline walked through `order`, as
/// fractions of its length: t[0] = 0, t[k] = 1.
std::vector<double> arc_fractions(const std::vector<Vec3>& p, const std::vector<std::size_t>& order) {
  const std::size_t k = order.size();
  std::vector<double> t(k + 1, 0.0);
  for (std::size_t i = 0; i < k; ++i) t[i + 1] = t[i] + (p[order[(i + 1) % k]] - p[order[i]]).norm();
  const double total = t[k];
  for (double& x : t) x = total > 0 ? x / total : 0;
  t[k] = 1;
  return t;
}

/// The smallest angle (radians) of triangle (a, b, c) if it faces outwards at
/// its three corners, else -1.
double outward_quality(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& na, const Vec3& nb, const Vec3& nc) {
  const Vec3 nt = (b - a).cross(c - a);
  if (!(nt.dot(na) > 0 && nt.dot(nb) > 0 && nt.dot(nc) > 0)) return -1;
  return geometry::min_angle(a, b, c);
}

/// The strips' objectives: the bottleneck (largest smallest angle), then,
/// among the strips that reach a given floor everywhere, the smallest sum
/// of 1 / sin² of each triangle's smallest angle — so that the triangles
/// away from the bottleneck are good too, not merely above it.
enum class Objective : unsigned char { Bottleneck, Sum };

/// The states of one start's search: the curve walked backwards from curve
/// vertex `start` (walk[j] is its j-th vertex; `shift` is start - nearest,
/// -kStartReach..kStartReach, for QualityCache) and, per rim row i (0..n),
/// the states (i, j) whose arc-length fractions differ by at most delta: an
/// interval [lo[i], hi[i]] of j since they increase along both polylines,
/// numbered from offset[i].
struct Corridor {
  std::ptrdiff_t shift = 0;
  std::vector<std::size_t> walk, lo, hi, offset;
  std::ptrdiff_t at(std::size_t i, std::size_t j) const {
    if (j < lo[i] || j > hi[i]) return -1;
    return static_cast<std::ptrdiff_t>(offset[i] + (j - lo[i]));
  }
};

Corridor make_corridor(const std::vector<Vec3>& rim, const std::vector<Vec3>& curve, std::size_t start,
                       std::ptrdiff_t shift, double delta) {
  const std::size_t n = rim.size(), m = curve.size();
  Corridor c;
  c.shift = shift;
  c.walk.resize(m);
  std::vector<std::size_t> forward(n);
  for (std::size_t j = 0; j < m; ++j) c.walk[j] = (start + m - j) % m;
  for (std::size_t i = 0; i < n; ++i) forward[i] = i;
  const std::vector<double> ta = arc_fractions(rim, forward), tb = arc_fractions(curve, c.walk);
  c.lo.resize(n + 1), c.hi.resize(n + 1), c.offset.assign(n + 2, 0);
  for (std::size_t i = 0; i <= n; ++i) {
    c.lo[i] = static_cast<std::size_t>(std::lower_bound(tb.begin(), tb.end(), ta[i] - delta) - tb.begin());
    c.hi[i] = static_cast<std::size_t>(std::upper_bound(tb.begin(), tb.end(), ta[i] + delta) - tb.begin());
    if (i == 0) c.lo[i] = 0;
    if (i == n) c.hi[i] = m + 1;
    c.hi[i] = std::max(c.hi[i], c.lo[i] + 1) - 1;  // inclusive
    c.hi[i] = std::min(c.hi[i], m);
    c.offset[i + 1] = c.offset[i] + (c.hi[i] >= c.lo[i] ? c.hi[i] - c.lo[i] + 1 : 0);
  }
  return c;
}

/// outward_quality() of the strips' candidate triangles, each computed once
/// for every start and both objectives of best_strip() (the same call on the
/// same corners, so the same value). State (i, j) of a start shifted by d
/// from the nearest curve vertex s0 has the curve vertex b = s0 + d - j (mod
/// m), so with u = j - d its rim-step triangle (rim i, rim i+1, curve b) and
/// its curve-step triangle (curve b-1, curve b, rim i mod n) depend on (i, u)
/// only. Each row keeps the u of every corridor's states in that row, up to
/// kMaxCachedStates in all: beyond (the whole-annulus fallback of a long
/// band, whose states alone take 9 bytes each) every value is computed
/// where it is needed, as without the cache, so the cache never doubles a
/// large search's memory.
class QualityCache {
 public:
  QualityCache(const std::vector<Vec3>& rim, const std::vector<Vec3>& rim_normals, const std::vector<Vec3>& curve,
               const std::vector<Vec3>& curve_normals, const std::vector<Corridor>& corridors)
      : rim_(rim), rim_normals_(rim_normals), curve_(curve), curve_normals_(curve_normals) {
    const std::size_t n = rim.size();
    first_.assign(n + 1, std::numeric_limits<std::ptrdiff_t>::max());
    start_.assign(n + 2, 0);
    std::vector<std::ptrdiff_t> last(n + 1, std::numeric_limits<std::ptrdiff_t>::min());
    for (const Corridor& c : corridors)
      for (std::size_t i = 0; i <= n; ++i)
        if (c.hi[i] >= c.lo[i]) {
          first_[i] = std::min(first_[i], static_cast<std::ptrdiff_t>(c.lo[i]) - c.shift);
          last[i] = std::max(last[i], static_cast<std::ptrdiff_t>(c.hi[i]) - c.shift);
        }
    for (std::size_t i = 0; i <= n; ++i)
      start_[i + 1] = start_[i] + (last[i] >= first_[i] ? static_cast<std::size_t>(last[i] - first_[i] + 1) : 0);
    if (start_[n + 1] > kMaxCachedStates) return;  // computed where needed
    constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
    rim_step_.assign(start_[n + 1], kUnknown);
    curve_step_.assign(start_[n + 1], kUnknown);
  }
  /// Quality of the rim-step triangle of state (i, j) of corridor c (i < n).
  double rim_step(const Corridor& c, std::size_t i, std::size_t j) {
    auto make = [&] {
      const std::size_t n = rim_.size(), a0 = i, a1 = (i + 1) % n, b = c.walk[j % curve_.size()];
      return outward_quality(rim_[a0], rim_[a1], curve_[b], rim_normals_[a0], rim_normals_[a1], curve_normals_[b]);
    };
    if (rim_step_.empty()) return make();
    double& q = rim_step_[slot(c, i, j)];
    if (std::isnan(q)) q = make();
    return q;
  }
  /// Quality of the curve-step triangle of state (i, j) of corridor c (j < m).
  double curve_step(const Corridor& c, std::size_t i, std::size_t j) {
    auto make = [&] {
      const std::size_t m = curve_.size(), b = c.walk[j % m], b1 = c.walk[(j + 1) % m], a = i % rim_.size();
      return outward_quality(curve_[b1], curve_[b], rim_[a], curve_normals_[b1], curve_normals_[b], rim_normals_[a]);
    };
    if (curve_step_.empty()) return make();
    double& q = curve_step_[slot(c, i, j)];
    if (std::isnan(q)) q = make();
    return q;
  }
  /// Values kept at most (two doubles each: 64 MiB). [chosen] far above a
  /// band's corridor (maltoporin's: about 30,000), far below the whole
  /// annulus of curves of thousands of samples.
  static constexpr std::size_t kMaxCachedStates = std::size_t{1} << 22;

 private:
  std::size_t slot(const Corridor& c, std::size_t i, std::size_t j) const {
    return start_[i] + static_cast<std::size_t>(static_cast<std::ptrdiff_t>(j) - c.shift - first_[i]);
  }
  const std::vector<Vec3>&rim_, &rim_normals_, &curve_, &curve_normals_;
  std::vector<std::ptrdiff_t> first_;  ///< per row, the smallest u kept
  std::vector<std::size_t> start_;     ///< per row, where its values start
  std::vector<double> rim_step_, curve_step_;
};

/// The best strip from the connecting edge (rim vertex 0, curve vertex
/// c.walk[0]) in corridor c, by `objective` (Sum: only triangles of quality
/// >= floor); `value` gets its bottleneck angle (radians) or its sum. Empty
/// if none exists.
std::vector<StripTriangle> strip_in_corridor(std::size_t n, std::size_t m, const Corridor& c, QualityCache& quality,
                                             Objective objective, double floor, double& value) {
  // best: the bottleneck so far (larger is better; < 0: unreached or only
  // through inward triangles), or the sum so far (smaller is better;
  // infinity: unreached).
  const bool sum = objective == Objective::Sum;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  constexpr double kUnreached = -2;
  std::vector<double> best(c.offset[n + 1], sum ? kInf : kUnreached);
  std::vector<std::uint8_t> from_rim(c.offset[n + 1], 0);  // 1: reached by a rim step, 0: by a curve step
  // Relaxes state k by a triangle of quality q from a state of value v0.
  auto relax = [&](std::ptrdiff_t k, double v0, double q, std::uint8_t rim_step) {
    if (k < 0) return;
    double& b = best[static_cast<std::size_t>(k)];
    if (sum) {
      if (q < floor || q <= 0) return;
      const double s = std::sin(q), v = v0 + 1 / (s * s);
      if (v < b) b = v, from_rim[static_cast<std::size_t>(k)] = rim_step;
    } else {
      const double v = std::min(v0, q);
      if (v > b) b = v, from_rim[static_cast<std::size_t>(k)] = rim_step;
    }
  };
  best[static_cast<std::size_t>(c.at(0, 0))] = sum ? 0.0 : kInf;
  for (std::size_t i = 0; i <= n; ++i)
    for (std::size_t j = c.lo[i]; j <= c.hi[i]; ++j) {
      const double v0 = best[static_cast<std::size_t>(c.at(i, j))];
      if (sum ? v0 == kInf : v0 < 0) continue;
      // Only states of the corridor are relaxed, so only their triangles are made.
      if (i < n) {  // rim edge i -> i+1 with curve vertex walk[j]
        const std::ptrdiff_t k = c.at(i + 1, j);
        if (k >= 0) relax(k, v0, quality.rim_step(c, i, j), 1);
      }
      if (j < m) {  // curve edge walk[j+1] -> walk[j] (its own orientation) with rim vertex i
        const std::ptrdiff_t k = c.at(i, j + 1);
        if (k >= 0) relax(k, v0, quality.curve_step(c, i, j), 0);
      }
    }
  const std::ptrdiff_t end = c.at(n, m);
  if (end < 0) return {};
  value = best[static_cast<std::size_t>(end)];
  if (sum ? value == kInf : value < 0) return {};
  std::vector<StripTriangle> out;
  out.reserve(n + m);
  for (std::size_t i = n, j = m; i > 0 || j > 0;) {
    const std::size_t k = static_cast<std::size_t>(c.at(i, j));
    if (from_rim[k]) {
      --i;
      out.push_back({static_cast<Index>(i), static_cast<Index>((i + 1) % n), static_cast<Index>(n + c.walk[j % m])});
    } else {
      --j;
      out.push_back(
          {static_cast<Index>(n + c.walk[(j + 1) % m]), static_cast<Index>(n + c.walk[j]), static_cast<Index>(i % n)});
    }
  }
  std::reverse(out.begin(), out.end());
  return out;
}

/// The best strip over the starts (curve vertex nearest + shifts[k]) in the
/// corridor `delta`: the largest bottleneck, then the smallest sum at that
/// bottleneck; ties: the earlier start. Empty if no start has a strip.
std::vector<StripTriangle> best_strip(const std::vector<Vec3>& rim, const std::vector<Vec3>& rim_normals,
                                      const std::vector<Vec3>& curve, const std::vector<Vec3>& curve_normals,
                                      std::size_t nearest, const std::vector<std::ptrdiff_t>& shifts, double delta) {
  const std::size_t n = rim.size(), m = curve.size();
  std::vector<Corridor> corridors;
  for (std::ptrdiff_t d : shifts)
    corridors.push_back(make_corridor(
        rim, curve, (nearest + static_cast<std::size_t>(d + static_cast<std::ptrdiff_t>(m))) % m, d, delta));
  QualityCache quality(rim, rim_normals, curve, curve_normals, corridors);
  std::vector<double> bottleneck(corridors.size(), -1);
  double top = -1;
  for (std::size_t k = 0; k < corridors.size(); ++k) {
    double v = -1;
    if (!strip_in_corridor(n, m, corridors[k], quality, Objective::Bottleneck, 0, v).empty())
      bottleneck[k] = v, top = std::max(top, v);
  }
  if (top < 0) return {};
  std::vector<StripTriangle> out;
  double best_sum = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < corridors.size(); ++k) {
    if (bottleneck[k] != top) continue;
    double v = 0;
    std::vector<StripTriangle> s = strip_in_corridor(n, m, corridors[k], quality, Objective::Sum, top, v);
    if (!s.empty() && v < best_sum) best_sum = v, out = std::move(s);
  }
  return out;
}

}  // namespace

std::vector<StripTriangle> strip_triangulation(const std::vector<Vec3>& rim, const std::vector<Vec3>& rim_normals,
                                               const std::vector<Vec3>& curve, const std::vector<Vec3>& curve_normals,
                                               double corridor) {
  if (rim.size() < 3 || curve.size() < 3)
    throw std::invalid_argument("strip_triangulation: each polyline needs at least three vertices");
  if (rim_normals.size() != rim.size() || curve_normals.size() != curve.size())
    throw std::invalid_argument("strip_triangulation: one normal per vertex is needed");
  const std::size_t m = curve.size();
  std::size_t nearest = 0;
  double d_start = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < m; ++j)
    if (const double d = (curve[j] - rim[0]).squaredNorm(); d < d_start) d_start = d, nearest = j;
  // The connecting edge at rim vertex 0 is in the strip's first and last
  // triangles whatever the path: a poor one would set the bottleneck for
  // the whole strip, so the curve vertices next to the nearest are tried too.
  std::vector<std::ptrdiff_t> shifts{0};
  for (std::size_t d = 1; d <= kStartReach && 2 * d < m; ++d)
    shifts.push_back(static_cast<std::ptrdiff_t>(d)), shifts.push_back(-static_cast<std::ptrdiff_t>(d));
  if (corridor < 1) {
    auto out = best_strip(rim, rim_normals, curve, curve_normals, nearest, shifts, corridor);
    if (!out.empty()) return out;
  }
  return best_strip(rim, rim_normals, curve, curve_normals, nearest, shifts, 1.0);
}

}  // namespace skinmesh::decompose
