// geometry/check/mesh_checks_geometry.cpp: the measured half of check_mesh() — signed
// volume and area of every component, and the angle statistics (minimum,
// maximum, worst triangle, histogram, small angles). Double-precision estimates,
// not exact decisions. Declared in mesh_checks_internal.h.
#include <Eigen/Geometry>  // cross()
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "geometry/check/mesh_checks_internal.h"
#include "geometry/kernel/tangent_angles.h"

namespace skinmesh::geometry::mesh_checks_detail {

namespace {

constexpr double kDegPerRad = 180.0 / kPi;

/// An estimate (degrees) of atan2(y, x) * kDegPerRad for y >= 0, within
/// kCoarseAtan2Error rad (geometry/kernel/tangent_angles.h); NaN when
/// x = y = 0 or an input is NaN. Used only to skip atan2 where the estimate
/// decides everything (measure_angles()).
double approx_angle_deg(double y, double x) {
  if (std::isnan(x) || std::isnan(y) || !(std::max(std::abs(x), std::abs(y)) > 0))
    return std::numeric_limits<double>::quiet_NaN();
  return coarse_atan2(y, x) * kDegPerRad;
}

}  // namespace

void measure_components(const IndexedMesh& mesh, const TriangleClasses& classes, const std::vector<Index>& component,
                        MeshCheckReport& r) {
  const auto& P = mesh.positions;
  const auto& T = mesh.triangles;
  const std::size_t nv = P.size(), nt = T.size();
  // Volumes relative to the centre of the bounding box, to limit cancellation.
  Vec3 centre = Vec3::Zero();
  {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (std::size_t v = 0; v < nv; ++v)
      if (classes.vertex_finite[v] && classes.referenced[v]) {
        lo = lo.cwiseMin(P[v]);
        hi = hi.cwiseMax(P[v]);
      }
    if (lo.x() <= hi.x()) centre = 0.5 * (lo + hi);
  }
  for (std::size_t t = 0; t < nt; ++t) {
    if (component[t] == kInvalidIndex) continue;
    if (classes.kind[t] == TriangleKind::kNonFinite) continue;
    MeshComponent& c = r.components[component[t]];
    const Vec3 a = P[T[t][0]] - centre, b = P[T[t][1]] - centre, d = P[T[t][2]] - centre;
    c.volume += a.dot(b.cross(d)) / 6.0;
    c.area += 0.5 * (b - a).cross(d - a).norm();
  }
}

void measure_angles(const IndexedMesh& mesh, const TriangleClasses& classes, double threshold_deg, MeshCheckReport& r) {
  const auto& P = mesh.positions;
  const auto& T = mesh.triangles;
  const std::size_t nt = T.size();
  double min_angle = std::numeric_limits<double>::infinity(), max_angle = -min_angle;
  // Fast path: estimates within kMargin degrees of the angles (approx_angle_deg()
  // errs by at most kCoarseAtan2Error rad, 1.15e-3 degrees) settle the
  // histogram bins, the maximum, the minimum and the small-angle count
  // whenever no decision lies within kMargin of a threshold; otherwise the
  // triangle takes the exact path (atan2), so every output is the one atan2 gives.
  constexpr double kMargin = 2e-3;  // [derived] above the estimate's error
  auto bin_of = [](double x) { return std::clamp(int(x / kHistogramBinDeg), 0, kHistogramBins - 1); };
  for (std::size_t t = 0; t < nt; ++t) {
    if (classes.kind[t] != TriangleKind::kGood && classes.kind[t] != TriangleKind::kZeroArea) continue;
    const Vec3& a = P[T[t][0]];
    const Vec3& b = P[T[t][1]];
    const Vec3& c = P[T[t][2]];
    {
      const Vec3 ab = b - a, ac = c - a, bc = c - b;
      // The (y, x) that corner_angle() hands to atan2 at a, b and c.
      const double est[3] = {approx_angle_deg(ab.cross(ac).norm(), ab.dot(ac)),
                             approx_angle_deg(bc.cross(-ab).norm(), bc.dot(-ab)),
                             approx_angle_deg((-ac).cross(-bc).norm(), (-ac).dot(-bc))};
      const double est_min = std::min({est[0], est[1], est[2]});
      bool settled = !std::isnan(est[0]) && !std::isnan(est[1]) && !std::isnan(est[2]) &&
                     est_min - kMargin > min_angle && !(std::abs(est_min - threshold_deg) <= kMargin);
      int bins[3] = {0, 0, 0};  // read only when settled, i.e. all three set
      for (int i = 0; i < 3 && settled; ++i) {
        bins[i] = bin_of(est[i] - kMargin);
        settled = bins[i] == bin_of(est[i] + kMargin) && est[i] + kMargin < max_angle;
      }
      if (settled) {  // the exact angles change neither the minimum nor the maximum
        for (int i = 0; i < 3; ++i) ++r.angle_histogram[std::size_t(bins[i])];
        if (est_min < threshold_deg) ++r.num_small_angle_triangles;
        continue;
      }
    }
    const double angles[3] = {corner_angle(a, b, c) * kDegPerRad, corner_angle(b, c, a) * kDegPerRad,
                              corner_angle(c, a, b) * kDegPerRad};
    double tri_min = angles[0];
    for (double x : angles) {
      tri_min = std::min(tri_min, x);
      max_angle = std::max(max_angle, x);
      ++r.angle_histogram[std::size_t(bin_of(x))];
    }
    if (tri_min < min_angle) {
      min_angle = tri_min;
      r.worst_triangle = Index(t);
    }
    if (tri_min < threshold_deg) ++r.num_small_angle_triangles;
  }
  if (r.worst_triangle != kInvalidIndex) {
    r.min_angle_deg = min_angle;
    r.max_angle_deg = max_angle;
  }
}

}  // namespace skinmesh::geometry::mesh_checks_detail
