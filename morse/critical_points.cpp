// morse/critical_points.cpp: analytic critical points per patch.
// papers/skin/skin_math.md §5.
#include "morse/critical_points.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/parallel.h"
#include "geometry/kernel/predicates.h"
#include "skin/mixed_cell_distance.h"

namespace skinmesh::morse {

Vec3 default_height_direction() {
  // y axis tilted by ~2.4° towards a generic x/z direction (constants are
  // arbitrary irrational-looking numbers; fixed so runs are reproducible).
  return Vec3(0.031415926535, 1.0, 0.027182818284).normalized();
}

namespace {

/// Appends to `out` the critical points of h(x) = e·x in cell c (the
/// candidates of critical_points() that lie in the cell within `tol`);
/// `planes` is scratch for the cell's planes.
void scan_cell(const skin::SkinSurface& skin, const Vec3& e, double tol, Index c, std::vector<skin::CellPlane>& planes,
               std::vector<CriticalPoint>& out) {
  const skin::MixedComplex& mc = skin.mixed_complex();
  if (mc.simplex(c).bounding) return;
  const skin::MixedCell X = mc.cell_value(c);            // made for the test, not kept
  const Mat3 A = skin::MixedComplex::quadric_matrix(X);  // A^{-1} = A for s = 1/2
  const Vec3 Ae = A * e;
  const double eAe = e.dot(Ae);
  if (eAe == 0.0) return;  // e asymptotic: no finite candidate
  const double mu2 = -X.focus_weight / (2.0 * eAe);
  if (!(mu2 > 0.0)) return;
  const double mu = std::sqrt(mu2);
  // A vertex's or an edge's planes, made for its two candidates and not kept
  // (a triangle's and a tetrahedron's test reads none).
  planes.clear();
  if (X.dim <= 1) mc.planes_into(c, planes);
  for (int sgn = -1; sgn <= 1; sgn += 2) {
    const Vec3 p = X.focus + (sgn * mu) * Ae;
    if (skin::cell_distance(mc, c, X, p, planes) > tol) continue;
    CriticalPoint cp;
    cp.position = p;
    cp.cell = c;
    cp.height = e.dot(p);
    cp.rho = (p - X.focus).norm();
    // grad f = 2 A y = 2 (sgn mu) A A e = 2 sgn mu e, so n = sgn e.
    cp.sigma = sgn;
    const skin::PrincipalCurvatures k = skin.curvatures(c, p);
    cp.k1 = k.k1;
    cp.k2 = k.k2;
    const double K = k.k1 * k.k2;
    if (K < 0) {
      cp.kind = CriticalKind::Saddle;
      // Circle direction e_c = u x y / |u x y|; meridian e_m = n x e_c.
      const Vec3 y = p - X.focus;
      const Vec3 ec = X.axis.cross(y).normalized();
      const Vec3 em = (sgn * e).cross(ec).normalized();
      // Hessian of h in (e_c, e_m) is -sigma diag(k_circ, k_mer): k1 is the
      // circle curvature for edges and triangles (SkinSurface::curvatures).
      const bool circle_ascends = -sgn * k.k1 > 0;
      cp.ascent = circle_ascends ? ec : em;
      cp.descent = circle_ascends ? em : ec;
    } else {
      cp.kind = (sgn * k.k1 > 0) ? CriticalKind::Maximum : CriticalKind::Minimum;
    }
    out.push_back(cp);
  }
}

}  // namespace

std::vector<CriticalPoint> critical_points(const skin::SkinSurface& skin, const Vec3& e_in, int threads) {
  const Vec3 e = e_in.normalized();
  const skin::MixedComplex& mc = skin.mixed_complex();
  // A candidate counts as inside its cell within this distance (times the
  // length scale): [derived] above the rounding of the quadric's solution.
  constexpr double kCellTolerance = 1e-9;
  const double tol = kCellTolerance * mc.length_scale();
  // Blocks of cells on the threads, joined in block order: the list one loop
  // over the cells makes.
  constexpr std::size_t kBlock = 4096;  // [chosen] cells per block: a few milliseconds
  const std::size_t num_blocks = (std::size_t(mc.num_cells()) + kBlock - 1) / kBlock;
  std::vector<std::vector<CriticalPoint>> found(num_blocks);
  parallel_for(num_blocks, thread_count(threads), 1, [&](std::size_t b) {
    std::vector<CriticalPoint>& out = found[b];
    std::vector<skin::CellPlane> planes;
    const Index end = static_cast<Index>(std::min<std::size_t>(mc.num_cells(), (b + 1) * kBlock));
    for (Index c = static_cast<Index>(b * kBlock); c < end; ++c) scan_cell(skin, e, tol, c, planes, out);
  });
  std::vector<CriticalPoint> out;
  for (const std::vector<CriticalPoint>& f : found) out.insert(out.end(), f.begin(), f.end());
  // Merge duplicates found in two cells sharing a face.
  std::sort(out.begin(), out.end(), [](const CriticalPoint& a, const CriticalPoint& b) { return a.height < b.height; });
  std::vector<CriticalPoint> merged;
  for (const CriticalPoint& cp : out) {
    bool dup = false;
    for (std::size_t j = merged.size(); j-- > 0;) {
      if (cp.height - merged[j].height > tol) break;
      if ((merged[j].position - cp.position).norm() <= tol && merged[j].kind == cp.kind) dup = true;
    }
    if (!dup) merged.push_back(cp);
  }
  return merged;
}

MorseCount count_critical_points(const std::vector<CriticalPoint>& cps) {
  MorseCount m;
  for (const CriticalPoint& cp : cps) {
    if (cp.kind == CriticalKind::Minimum) ++m.minima;
    if (cp.kind == CriticalKind::Saddle) ++m.saddles;
    if (cp.kind == CriticalKind::Maximum) ++m.maxima;
  }
  return m;
}

}  // namespace skinmesh::morse
