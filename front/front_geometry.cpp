// front/front_geometry.cpp: the geometry of the front in tangent planes — the
// corner (hole angle) at a front vertex, the hole-wedge test that keeps a new
// triangle from folding over the triangles already at a vertex, the convex
// quad test of bridges and contacts, and the fold test of the paranoid mode.
// These are the tests the paper leaves implicit in Figure 7 ("the newly added
// triangles may overlap existing ones").
// Notes: papers/front/creep.md (hole wedges), papers/front/open_questions.md Q4.1 (the fan and its orientation), Q6.2
// (which pair of edges)
#include <sstream>

#include "core/assert.h"
#include "core/errors.h"
#include "front/operations.h"
#include "geometry/io/mesh_io.h"
#include "geometry/kernel/predicates.h"

namespace skinmesh::front::detail {

Corner corner(const FrontState& fs, Vertex v) {
  Corner k;
  k.out = fs.mesh.halfedge(v);
  SKINMESH_ASSERT(fs.mesh.is_boundary(k.out));
  k.in = fs.mesh.prev(k.out);
  k.w = fs.mesh.to_vertex(k.out);
  k.u = fs.mesh.from_vertex(k.in);
  const Vec3& p = fs.mesh.position(v);
  const Vec3& n = fs.normal[v];
  k.dw = tangent_dir(p, n, fs.mesh.position(k.w));
  const Vec3 du = tangent_dir(p, n, fs.mesh.position(k.u));
  k.angle = ccw_angle(k.dw, du, n);
  return k;
}

bool clearly_not_below(const FrontState& fs, Vertex v, double bound) {
  // Without atan2: for the unit tangents dw, du the hole angle t satisfies
  // cos t = dw . du and sin t = (dw x du) . n. A cosine below -1e-9 puts t in
  // (90° + 1e-9, 270°), a sine below -1e-9 in (180° + 1e-9, 360°), both clear
  // of the rounding of atan2 and of a bound at 90° or 180° (a few ulps off).
  // Most wing candidates after a creep have an obtuse hole angle and stop here.
  constexpr double kUlps = 1e-12;            // [derived] a few ulps of an angle in [0, 2 pi]
  constexpr double kClearOfRounding = 1e-9;  // [derived] far above atan2's rounding, far below any decision
  if (bound > kPi + kUlps) return false;
  const Halfedge out = fs.mesh.halfedge(v);
  const Vec3& p = fs.mesh.position(v);
  const Vec3& n = fs.normal[v];
  const Vec3 dw = tangent_dir(p, n, fs.mesh.position(fs.mesh.to_vertex(out)));
  const Vec3 du = tangent_dir(p, n, fs.mesh.position(fs.mesh.from_vertex(fs.mesh.prev(out))));
  if (dw.cross(du).dot(n) < -kClearOfRounding) return true;
  return bound <= kPi / 2 + kUlps && dw.dot(du) < -kClearOfRounding;
}

bool fits_at(const FrontState& fs, Vertex x, Vertex y_from, Vertex y_to) {
  return fits_at(fs, x, fs.mesh.position(y_from), fs.mesh.position(y_to), y_from, y_to);
}

bool fits_at(const FrontState& fs, Vertex x, const Vec3& from, const Vec3& to, Vertex y_from, Vertex y_to) {
  if (!fs.mesh.is_boundary(x) || fs.mesh.is_isolated(x)) return fs.mesh.is_isolated(x);
  // The span [a, b] of the new triangle at x, measured counter-clockwise from
  // the front edge x -> w, must lie within the hole angle [0, K]:
  //   a < b - tol,  b <= K + tol,  K > tol.
  // Decided from pseudo-angles of the same tangents when they are clear of
  // the tolerance by a factor of two (almost always), else from the angles
  // (atan2) as before: the same verdicts (pseudo_angle's slope bounds).
  const Halfedge out = fs.mesh.halfedge(x);
  const Vertex w = fs.mesh.to_vertex(out), u = fs.mesh.from_vertex(fs.mesh.prev(out));
  const Vec3 px = fs.mesh.position(x), n = fs.normal[x];
  const Vec3 dw = tangent_dir(px, n, fs.mesh.position(w));
  const Vec3 du = tangent_dir(px, n, fs.mesh.position(u));
  const Vec3 df = y_from == w ? dw : tangent_dir(px, n, from);
  const Vec3 dt = y_to == u ? du : tangent_dir(px, n, to);
  const double tol = kWedgeTolerance;
  if (!fs.tracing) {
    auto pseudo = [&](const Vec3& d) { return pseudo_angle(dw.cross(d).dot(n), dw.dot(d)); };
    const double pk = pseudo(du);
    const double pa = y_from == w ? 0.0 : pseudo(df);
    const double pb = y_to == u ? pk : pseudo(dt);
    using geometry::PseudoVerdict;
    const PseudoVerdict span = pseudo_exceeds(pb, pa, tol), over = pseudo_exceeds(pb, pk, tol),
                        open = pseudo_exceeds(pk, 0.0, tol);
    if (span == PseudoVerdict::Fails || over == PseudoVerdict::Holds || open == PseudoVerdict::Fails) return false;
    if (span == PseudoVerdict::Holds && over == PseudoVerdict::Fails && open == PseudoVerdict::Holds) return true;
  }
  const double angle = ccw_angle(dw, du, n);
  const double a = y_from == w ? 0.0 : ccw_angle(dw, df, n);
  const double b = y_to == u ? angle : ccw_angle(dw, dt, n);
  if (fs.tracing)
    fs.tracef("fits_at v%u: a %.1f b %.1f hole %.1f (from v%u to v%u; w v%u u v%u)\n", x.idx(), a / kDegree,
              b / kDegree, angle / kDegree, y_from.idx(), y_to.idx(), w.idx(), u.idx());
  return a < b - tol && b <= angle + tol && angle > tol;
}

bool quad_fits(const FrontState& fs, Vertex a, Vertex b, Vertex c, Vertex d, const Vec3& origin, const Vec3& normal) {
  const Vec3 t1 = normal.unitOrthogonal(), t2 = normal.cross(t1);
  std::array<std::array<double, 2>, 4> P;
  const Vertex q[4] = {a, b, c, d};
  for (int i = 0; i < 4; ++i) {
    const Vec3 dd = fs.mesh.position(q[i]) - origin;
    P[i] = {dd.dot(t1), dd.dot(t2)};
  }
  for (int i = 0; i < 4; ++i)
    if (geometry::orient2d(P[i][0], P[i][1], P[(i + 1) % 4][0], P[(i + 1) % 4][1], P[(i + 2) % 4][0],
                           P[(i + 2) % 4][1]) != Sign::Positive)
      return false;
  // Counter-clockwise quad a b c d: at a the new triangles span from b to d,
  // at b from c to a, at c from d to b, at d from a to c.
  return fits_at(fs, a, b, d) && fits_at(fs, b, c, a) && fits_at(fs, c, d, b) && fits_at(fs, d, a, c);
}

double fold_excess(const FrontState& fs, Vertex v) {
  // A test with a tolerance of degrees (opt.fold_tolerance_deg): the angles of
  // coarse_ccw_angle (within 2e-5 rad) are plenty and cost a fraction of
  // atan2's. The tangent vectors need no normalisation.
  const Vec3 pv = fs.mesh.position(v);
  const Vec3 n = fs.normal[v];
  auto tangent = [&](Vertex x) {
    const Vec3 d = fs.mesh.position(x) - pv;
    return Vec3(d - d.dot(n) * n);
  };
  double covered = 0;
  for (Halfedge h : fs.mesh.halfedges(v)) {
    if (!fs.mesh.face(h).is_valid()) continue;  // the face of h has corners v, to(h), to(next(h))
    covered += coarse_ccw_angle(tangent(fs.mesh.to_vertex(h)), tangent(fs.mesh.to_vertex(fs.mesh.next(h))), n);
  }
  if (fs.mesh.is_boundary(v)) {  // the hole angle, as corner(v) measures it
    const Halfedge out = fs.mesh.halfedge(v);
    covered += coarse_ccw_angle(tangent(fs.mesh.to_vertex(out)), tangent(fs.mesh.from_vertex(fs.mesh.prev(out))), n);
  }
  return covered - 2 * kPi;
}

void paranoid_check(FrontState& fs, std::size_t first_face, const char* op) {
  if (!fs.opt.paranoid) return;
  for (std::size_t fi = first_face; fi < fs.mesh.faces_size(); ++fi) {
    const Face f(static_cast<Index>(fi));
    if (fs.mesh.is_deleted(f)) continue;
    for (Vertex v : fs.mesh.vertices(f)) {
      const double ex = fold_excess(fs, v);
      if (std::abs(ex) > fs.opt.fold_tolerance_deg * kDegree) {
        std::ostringstream os;
        os << "paranoid: after " << op << " (faces " << first_face << ".." << fs.mesh.faces_size()
           << ") the mesh folds at vertex " << v.idx() << " (" << fs.mesh.position(v).transpose() << "): excess "
           << ex / kDegree << "°";
        if (!fs.opt.dump_path.empty()) geometry::write_mesh(fs.opt.dump_path, fs.mesh.to_indexed_mesh());
        throw TopologyError(os.str());
      }
    }
  }
}

}  // namespace skinmesh::front::detail
