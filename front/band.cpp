// front/band.cpp: the max-min-angle strip between two closed polylines
// (front/band.h). A strip is a monotone path through the grid of states
// (i, j): the triangle fan so far ends at the connecting edge from rim vertex
// i to the j-th curve vertex met walking the curve backwards from the start.
// Each step adds one triangle (a rim edge or a curve edge with the current
// vertex of the other side), so the best smallest angle of a path to (i, j)
// is a bottleneck recurrence over its two predecessors, and the least sum
// above a floor a shortest-path one: two passes per start.
// Notes: papers/mesher/decomposition.md ("Increments", 4)
#include "front/band.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "geometry/check/mesh_checks.h"

namespace skinmesh::front {
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

/// The best strip from the connecting edge (rim vertex 0, curve vertex
/// `start`) in the corridor `delta`, by `objective` (Sum: only triangles of
/// quality >= floor); `value` gets its bottleneck angle (radians) or its sum.
/// Empty if none exists.
std::vector<StripTriangle> strip_in_corridor(const std::vector<Vec3>& rim, const std::vector<Vec3>& rim_normals,
                                             const std::vector<Vec3>& curve, const std::vector<Vec3>& curve_normals,
                                             std::size_t start, double delta, Objective objective, double floor,
                                             double& value) {
  const std::size_t n = rim.size(), m = curve.size();
  // The curve walked backwards from `start`: walk[j] is its j-th vertex.
  std::vector<std::size_t> walk(m), forward(n);
  for (std::size_t j = 0; j < m; ++j) walk[j] = (start + m - j) % m;
  for (std::size_t i = 0; i < n; ++i) forward[i] = i;
  const std::vector<double> ta = arc_fractions(rim, forward), tb = arc_fractions(curve, walk);
  // Row i of the corridor: the states (i, j) with |ta[i] - tb[j]| <= delta,
  // an interval of j since tb increases.
  std::vector<std::size_t> lo(n + 1), hi(n + 1), offset(n + 2, 0);
  for (std::size_t i = 0; i <= n; ++i) {
    lo[i] = static_cast<std::size_t>(std::lower_bound(tb.begin(), tb.end(), ta[i] - delta) - tb.begin());
    hi[i] = static_cast<std::size_t>(std::upper_bound(tb.begin(), tb.end(), ta[i] + delta) - tb.begin());
    if (i == 0) lo[i] = 0;
    if (i == n) hi[i] = m + 1;
    hi[i] = std::max(hi[i], lo[i] + 1) - 1;  // inclusive
    hi[i] = std::min(hi[i], m);
    offset[i + 1] = offset[i] + (hi[i] >= lo[i] ? hi[i] - lo[i] + 1 : 0);
  }
  // best: the bottleneck so far (larger is better; < 0: unreached or only
  // through inward triangles), or the sum so far (smaller is better;
  // infinity: unreached).
  const bool sum = objective == Objective::Sum;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  constexpr double kUnreached = -2;
  std::vector<double> best(offset[n + 1], sum ? kInf : kUnreached);
  std::vector<std::uint8_t> from_rim(offset[n + 1], 0);  // 1: reached by a rim step, 0: by a curve step
  auto at = [&](std::size_t i, std::size_t j) -> std::ptrdiff_t {
    if (j < lo[i] || j > hi[i]) return -1;
    return static_cast<std::ptrdiff_t>(offset[i] + (j - lo[i]));
  };
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
  best[static_cast<std::size_t>(at(0, 0))] = sum ? 0.0 : kInf;
  for (std::size_t i = 0; i <= n; ++i)
    for (std::size_t j = lo[i]; j <= hi[i]; ++j) {
      const double v0 = best[static_cast<std::size_t>(at(i, j))];
      if (sum ? v0 == kInf : v0 < 0) continue;
      const std::size_t b = walk[j % m];
      if (i < n) {  // rim edge i -> i+1 with curve vertex b
        const std::size_t a0 = i, a1 = (i + 1) % n;
        relax(at(i + 1, j), v0,
              outward_quality(rim[a0], rim[a1], curve[b], rim_normals[a0], rim_normals[a1], curve_normals[b]), 1);
      }
      if (j < m) {  // curve edge b' -> b (its own orientation) with rim vertex i
        const std::size_t b1 = walk[(j + 1) % m], a = i % n;
        relax(at(i, j + 1), v0,
              outward_quality(curve[b1], curve[b], rim[a], curve_normals[b1], curve_normals[b], rim_normals[a]), 0);
      }
    }
  const std::ptrdiff_t end = at(n, m);
  if (end < 0) return {};
  value = best[static_cast<std::size_t>(end)];
  if (sum ? value == kInf : value < 0) return {};
  std::vector<StripTriangle> out;
  out.reserve(n + m);
  for (std::size_t i = n, j = m; i > 0 || j > 0;) {
    const std::size_t k = static_cast<std::size_t>(at(i, j));
    if (from_rim[k]) {
      --i;
      out.push_back({static_cast<Index>(i), static_cast<Index>((i + 1) % n), static_cast<Index>(n + walk[j % m])});
    } else {
      --j;
      out.push_back(
          {static_cast<Index>(n + walk[(j + 1) % m]), static_cast<Index>(n + walk[j]), static_cast<Index>(i % n)});
    }
  }
  std::reverse(out.begin(), out.end());
  return out;
}

/// The best strip over the starts `starts` in the corridor `delta`: the
/// largest bottleneck, then the smallest sum at that bottleneck; ties: the
/// earlier start. Empty if no start has a strip.
std::vector<StripTriangle> best_strip(const std::vector<Vec3>& rim, const std::vector<Vec3>& rim_normals,
                                      const std::vector<Vec3>& curve, const std::vector<Vec3>& curve_normals,
                                      const std::vector<std::size_t>& starts, double delta) {
  std::vector<double> bottleneck(starts.size(), -1);
  double top = -1;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    double v = -1;
    if (!strip_in_corridor(rim, rim_normals, curve, curve_normals, starts[k], delta, Objective::Bottleneck, 0, v)
             .empty())
      bottleneck[k] = v, top = std::max(top, v);
  }
  if (top < 0) return {};
  std::vector<StripTriangle> out;
  double best_sum = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < starts.size(); ++k) {
    if (bottleneck[k] != top) continue;
    double v = 0;
    std::vector<StripTriangle> s =
        strip_in_corridor(rim, rim_normals, curve, curve_normals, starts[k], delta, Objective::Sum, top, v);
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
  std::vector<std::size_t> starts{nearest};
  for (std::size_t d = 1; d <= kStartReach && 2 * d < m; ++d)
    starts.push_back((nearest + d) % m), starts.push_back((nearest + m - d) % m);
  if (corridor < 1) {
    auto out = best_strip(rim, rim_normals, curve, curve_normals, starts, corridor);
    if (!out.empty()) return out;
  }
  return best_strip(rim, rim_normals, curve, curve_normals, starts, 1.0);
}

}  // namespace skinmesh::front
