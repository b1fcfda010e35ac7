// geometry/mesh_checks_geometry.cpp: the measured half of check_mesh() — signed
// volume and area of every component, and the angle statistics (minimum,
// maximum, worst triangle, histogram, small angles). Double-precision estimates,
// not exact decisions. Declared in mesh_checks_internal.h.
#include <Eigen/Geometry>  // cross()
#include <algorithm>
#include <limits>
#include <vector>

#include "geometry/mesh_checks_internal.h"

namespace skinmesh::geometry::mesh_checks_detail {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegPerRad = 180.0 / kPi;

}  // namespace

void measure_components(const IndexedMesh& mesh, const TriangleClasses& classes,
                        const std::vector<Index>& component, MeshCheckReport& r) {
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

void measure_angles(const IndexedMesh& mesh, const TriangleClasses& classes, double threshold_deg,
                    MeshCheckReport& r) {
  const auto& P = mesh.positions;
  const auto& T = mesh.triangles;
  const std::size_t nt = T.size();
  double min_angle = std::numeric_limits<double>::infinity(), max_angle = -min_angle;
  for (std::size_t t = 0; t < nt; ++t) {
    if (classes.kind[t] != TriangleKind::kGood && classes.kind[t] != TriangleKind::kZeroArea) continue;
    const Vec3& a = P[T[t][0]];
    const Vec3& b = P[T[t][1]];
    const Vec3& c = P[T[t][2]];
    const double angles[3] = {corner_angle(a, b, c) * kDegPerRad, corner_angle(b, c, a) * kDegPerRad,
                              corner_angle(c, a, b) * kDegPerRad};
    double tri_min = angles[0];
    for (double x : angles) {
      tri_min = std::min(tri_min, x);
      max_angle = std::max(max_angle, x);
      const int bin = std::clamp(int(x / kHistogramBinDeg), 0, kHistogramBins - 1);
      ++r.angle_histogram[std::size_t(bin)];
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
