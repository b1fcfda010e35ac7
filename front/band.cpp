// front/band.cpp: the max-min-angle strip between two closed polylines
// (front/band.h). A strip is a monotone path through the grid of states
// (i, j): the triangle fan so far ends at the connecting edge from rim vertex
// i to the j-th curve vertex met walking the curve backwards from the one
// nearest to rim vertex 0. Each step adds one triangle (a rim edge or a curve
// edge with the current vertex of the other side), so the best smallest
// angle of a path to (i, j) is a bottleneck recurrence over its two
// predecessors.
// Notes: papers/mesher/decomposition.md ("Increments", 4)
#include "front/band.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "geometry/check/mesh_checks.h"

namespace skinmesh::front {
namespace {

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

std::vector<StripTriangle> strip_in_corridor(const std::vector<Vec3>& rim, const std::vector<Vec3>& rim_normals,
                                             const std::vector<Vec3>& curve, const std::vector<Vec3>& curve_normals,
                                             std::size_t start, double delta) {
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
  constexpr double kUnreached = -2;
  std::vector<double> best(offset[n + 1], kUnreached);
  std::vector<std::uint8_t> from_rim(offset[n + 1], 0);  // 1: reached by a rim step, 0: by a curve step
  auto at = [&](std::size_t i, std::size_t j) -> std::ptrdiff_t {
    if (j < lo[i] || j > hi[i]) return -1;
    return static_cast<std::ptrdiff_t>(offset[i] + (j - lo[i]));
  };
  best[static_cast<std::size_t>(at(0, 0))] = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i <= n; ++i)
    for (std::size_t j = lo[i]; j <= hi[i]; ++j) {
      const double q0 = best[static_cast<std::size_t>(at(i, j))];
      if (q0 < 0) continue;  // unreached, or only through inward triangles
      const std::size_t b = walk[j % m];
      if (i < n) {  // rim edge i -> i+1 with curve vertex b
        const std::ptrdiff_t k = at(i + 1, j);
        if (k >= 0) {
          const std::size_t a0 = i, a1 = (i + 1) % n;
          const double q = std::min(
              q0, outward_quality(rim[a0], rim[a1], curve[b], rim_normals[a0], rim_normals[a1], curve_normals[b]));
          if (q > best[static_cast<std::size_t>(k)]) best[static_cast<std::size_t>(k)] = q, from_rim[k] = 1;
        }
      }
      if (j < m) {  // curve edge b' -> b (its own orientation) with rim vertex i
        const std::ptrdiff_t k = at(i, j + 1);
        if (k >= 0) {
          const std::size_t b1 = walk[(j + 1) % m], a = i % n;
          const double q = std::min(
              q0, outward_quality(curve[b1], curve[b], rim[a], curve_normals[b1], curve_normals[b], rim_normals[a]));
          if (q > best[static_cast<std::size_t>(k)]) best[static_cast<std::size_t>(k)] = q, from_rim[k] = 0;
        }
      }
    }
  const std::ptrdiff_t end = at(n, m);
  if (end < 0 || best[static_cast<std::size_t>(end)] < 0) return {};
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

}  // namespace

std::vector<StripTriangle> strip_triangulation(const std::vector<Vec3>& rim, const std::vector<Vec3>& rim_normals,
                                               const std::vector<Vec3>& curve, const std::vector<Vec3>& curve_normals,
                                               double corridor) {
  if (rim.size() < 3 || curve.size() < 3)
    throw std::invalid_argument("strip_triangulation: each polyline needs at least three vertices");
  if (rim_normals.size() != rim.size() || curve_normals.size() != curve.size())
    throw std::invalid_argument("strip_triangulation: one normal per vertex is needed");
  std::size_t start = 0;
  double d_start = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < curve.size(); ++j)
    if (const double d = (curve[j] - rim[0]).squaredNorm(); d < d_start) d_start = d, start = j;
  if (corridor < 1) {
    auto out = strip_in_corridor(rim, rim_normals, curve, curve_normals, start, corridor);
    if (!out.empty()) return out;
  }
  return strip_in_corridor(rim, rim_normals, curve, curve_normals, start, 1.0);
}

}  // namespace skinmesh::front
