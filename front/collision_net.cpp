// front/collision_net.cpp: the project's collision safety net — not in the
// paper. Cheng & Shi argue that fronts meet only inside protecting spheres; on
// real molecules noisy critical points and flat saddles break that (fronts
// meet outside any sphere), so:
//  - a contact joins the departure vertex's front to a nearby free front
//    vertex of another front part by one ladder row (bridge.cpp), when each
//    lies inside the other's hole wedge;
//  - a fan whose new point would come within collision_radius · r of another
//    vertex is not built: the departure vertex joins that vertex's hold, makes
//    a contact, or is deferred.
// Notes: papers/front/collision_net.md, papers/front/open_questions.md Q2.3 (a cheap safety net), Q4.3 (overlap and
// snapping)
#include <algorithm>
#include <limits>

#include "front/operations.h"
#include "geometry/check/mesh_checks.h"

namespace skinmesh::front::detail {

using geometry::min_angle;

bool try_contact(FrontState& fs, Vertex v, const Corner& k) {
  const double r = fs.disc_radius(v);
  const Vec3 pv = fs.mesh.position(v), n = fs.normal[v];
  // Vertices fewer than contact_min_hops hops along the front are the wing's business.
  std::vector<Vertex>& near_hops = fs.scratch_near_hops;  // a member: no allocation per call
  near_hops.clear();
  {
    Halfedge f = k.out, b = k.in;
    for (int i = 0; i + 1 < fs.opt.contact_min_hops; ++i) {
      near_hops.push_back(fs.mesh.to_vertex(f));
      near_hops.push_back(fs.mesh.from_vertex(b));
      f = fs.mesh.next(f), b = fs.mesh.prev(b);
    }
  }
  const double margin = fs.opt.contact_margin_deg * kDegree;
  Vertex best;
  double best_d = std::numeric_limits<double>::infinity();
  // Every vertex whose state is not Interior is in front_grid (set_state).
  const auto& positions = fs.mesh.positions().vector();
  const double reach = fs.opt.contact_radius * r;
  const auto [lo, hi] = FrontState::local_scales(fs.rho[v], reach);
  fs.front_grid->for_each_near(pv, reach, lo, hi, positions, [&](Index xi, const Vec3& px) {
    const Vertex x(xi);
    if (x == v || fs.state[x] == VState::Interior || fs.mesh.is_deleted(x) || fs.mesh.is_isolated(x) ||
        !fs.mesh.is_boundary(x))
      return;
    if (std::find(near_hops.begin(), near_hops.end(), x) != near_hops.end()) return;
    if (fs.normal[x].dot(n) <= fs.opt.min_normal_cosine) return;
    const double a = ccw_angle(k.dw, tangent_dir(pv, n, px), n);
    if (!(a > margin && a < k.angle - margin)) return;
    const Corner kx = corner(fs, x);
    const double ax = ccw_angle(kx.dw, tangent_dir(px, fs.normal[x], pv), fs.normal[x]);
    if (fs.tracing)
      fs.tracef("contact candidate v%u for v%u: a %.1f of %.1f, ax %.1f of %.1f\n", x.idx(), v.idx(), a / kDegree,
                k.angle / kDegree, ax / kDegree, kx.angle / kDegree);
    if (!(ax > margin && ax < kx.angle - margin)) return;
    // The nearest candidate, ties to the lower index: the verdict does not
    // depend on the order in which the grid visits its points.
    const double d = (px - pv).squaredNorm();
    if (d < best_d || (d == best_d && x.idx() < best.idx())) best_d = d, best = x;
  });
  if (!best.is_valid()) return false;
  if (fs.holder_of(best) != kInvalidIndex) {
    hold(fs, v, fs.holder_of(best));
    return true;
  }
  return contact_with(fs, v, k, best);
}

bool contact_with(FrontState& fs, Vertex v, const Corner& k, Vertex best) {
  const Vec3 pv = fs.mesh.position(v), n = fs.normal[v];
  // Two ways to join: v->w with x_u->x (quad v w x_u x), or u->v with x->x_w
  // (quad u v x x_w). Take the convex one that fits at its four corners, with
  // the better minimum angle.
  const Halfedge xo = fs.mesh.halfedge(best);
  const Halfedge cand[2][2] = {{k.out, fs.mesh.prev(xo)}, {k.in, xo}};
  double best_q = -1;
  int pick = -1;
  for (int o = 0; o < 2; ++o) {
    const Vertex a = fs.mesh.from_vertex(cand[o][0]), b = fs.mesh.to_vertex(cand[o][0]);
    const Vertex c = fs.mesh.from_vertex(cand[o][1]), d = fs.mesh.to_vertex(cand[o][1]);
    if (a == c || a == d || b == c || b == d) continue;
    if (fs.mesh.find_halfedge(b, c).is_valid() || fs.mesh.find_halfedge(d, a).is_valid() ||
        fs.mesh.find_halfedge(a, c).is_valid() || fs.mesh.find_halfedge(b, d).is_valid())
      continue;
    if (!quad_fits(fs, a, b, c, d, pv, n) || !ladder_fits(fs, cand[o][0], cand[o][1], Rails{})) continue;
    const Vec3 pa = fs.mesh.position(a), pb = fs.mesh.position(b), pc = fs.mesh.position(c), pd = fs.mesh.position(d);
    const double qual = std::max(std::min(min_angle(pa, pb, pc), min_angle(pc, pd, pa)),
                                 std::min(min_angle(pa, pb, pd), min_angle(pb, pc, pd)));
    if (qual > best_q) best_q = qual, pick = o;
  }
  if (pick < 0) return false;
  if (fs.tracing)
    fs.tracef("contact v%u with v%u (dist %.3f)\n", v.idx(), best.idx(), (fs.mesh.position(best) - pv).norm());
  bridge(fs, cand[pick][0], cand[pick][1], kInvalidIndex, Rails{});
  ++fs.stats.contacts;
  return true;
}

Vertex covered_front_vertex(const FrontState& fs, Vertex v, Vertex w, Vertex u) {
  const Vec3 &pv = fs.mesh.position(v), &pw = fs.mesh.position(w), &pu = fs.mesh.position(u);
  const Vec3 n = fs.normal[v];
  // The triangle lies within max(|w - v|, |u - v|) of v; so does every point
  // that projects into it along n and lies within that distance of v.
  const double reach = std::max((pw - pv).norm(), (pu - pv).norm());
  const auto [lo, hi] = FrontState::local_scales(fs.rho[v], reach);
  // Orientation of x against the directed edge a -> b, seen along n.
  auto left_of = [&n](const Vec3& a, const Vec3& b, const Vec3& x) { return (b - a).cross(x - a).dot(n) > 0; };
  Vertex best;
  double best_d = std::numeric_limits<double>::infinity();
  fs.front_grid->for_each_near(pv, reach, lo, hi, fs.mesh.positions().vector(), [&](Index xi, const Vec3& px) {
    const Vertex x(xi);
    if (x == v || x == w || x == u || fs.mesh.is_deleted(x) || fs.mesh.is_isolated(x)) return;
    if (fs.normal[x].dot(n) <= fs.opt.min_normal_cosine) return;
    if (!left_of(pv, pw, px) || !left_of(pw, pu, px) || !left_of(pu, pv, px)) return;
    const double d = (px - pv).squaredNorm();
    if (d < best_d || (d == best_d && x.idx() < best.idx())) best_d = d, best = x;
  });
  return best;
}

bool fan_collision(FrontState& fs, Vertex v, const Corner& k, int m) {
  // A new point within collision_radius · r of a vertex x other than u, v, w
  // would come too close to another part of the front
  // (papers/front/open_questions.md Q4.3 (overlap and snapping), case b). Join v to x instead, hold v if x
  // is held, or let the front move on and come back.
  const double r = fs.disc_radius(v);
  const Vec3 pv = fs.mesh.position(v), n = fs.normal[v];
  // The first fan point (in fan order) with such a vertex; of its vertices,
  // the nearest, ties to the lower index (independent of the grid's order).
  Vertex hit;
  // The points within collision_radius · r of a fan point are within
  // (1 + collision_radius) r of v: the vertex grid has them in v's level.
  for (int i = 1; i < m && !hit.is_valid(); ++i) {
    const Vec3 q = pv + r * rotate(k.dw, n, i * k.angle / m);
    double hit_d = std::numeric_limits<double>::infinity();
    fs.vertex_grid->for_each_near_at(q, fs.opt.collision_radius * r, fs.rho[v], fs.mesh.positions().vector(),
                                     [&](Index xi, const Vec3& px) {
                                       const Vertex x(xi);
                                       if (x == v || x == k.u || x == k.w || fs.mesh.is_deleted(x)) return;
                                       if (fs.mesh.is_isolated(x) || fs.normal[x].dot(n) <= fs.opt.min_normal_cosine)
                                         return;
                                       // a front vertex, or an interior one: the fan would cover meshed surface
                                       const double d = (px - q).squaredNorm();
                                       if (d < hit_d || (d == hit_d && xi < hit.idx())) hit_d = d, hit = x;
                                     });
  }
  // A fan of one triangle has no new point; the triangle (v, w, u) itself
  // must not cover a front vertex.
  const bool covers = m == 1 && (hit = covered_front_vertex(fs, v, k.w, k.u)).is_valid();
  if (!hit.is_valid()) return false;
  ++fs.stats.collisions;
  if (covers) ++fs.stats.covered_triangles;
  if (fs.tracing) fs.tracef("collision: fan of v%u reaches v%u\n", v.idx(), hit.idx());
  if (fs.holder_of(hit) != kInvalidIndex) {
    hold(fs, v, fs.holder_of(hit));
    return true;
  }
  // A ghost below a region's lower cut (front/region.h) is no front to join.
  if (fs.mesh.is_boundary(hit) && !fs.region.is_ghost(hit) && contact_with(fs, v, k, hit)) return true;
  if (fs.deferrals[v] < fs.opt.max_deferrals) {
    defer(fs, v, r);
    return true;
  }
  // Deferred too often. A fan reaching a front vertex is built: the fronts
  // meet there and the small holes close what is left between them. A fan
  // reaching an interior vertex would lay triangles over meshed surface, and
  // every later fan of that front would do the same: one front passing
  // through another is how a component comes out swept twice. A triangle
  // covering a front vertex would fold the mesh there. With the fallback, v
  // is left for the seal instead (papers/front/collision_net.md).
  if (fs.opt.patch_fallback && (covers || fs.state[hit] == VState::Interior)) {
    if (fs.tracing)
      fs.tracef("collision: v%u would cover meshed surface at v%u: left for the seal\n", v.idx(), hit.idx());
    leave_hole_for_seal(fs, {v});
    return true;
  }
  return false;
}

}  // namespace skinmesh::front::detail
