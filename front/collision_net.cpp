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
// Notes: papers/front/collision_net.md, papers/front/open_questions.md Q2.3, Q4.3
#include <algorithm>
#include <limits>

#include "front/sweep_internal.h"
#include "geometry/check/mesh_checks.h"

namespace skinmesh::front::detail {

using geometry::min_angle;

bool Sweep::try_contact(Vertex v, const Corner& k) {
  const double r = disc_radius(v);
  const Vec3 pv = mesh_.position(v), n = normal_[v];
  // Vertices fewer than contact_min_hops hops along the front are the wing's business.
  std::vector<Vertex>& near_hops = scratch_near_hops_;  // a member: no allocation per call
  near_hops.clear();
  {
    Halfedge f = k.out, b = k.in;
    for (int i = 0; i + 1 < opt_.contact_min_hops; ++i) {
      near_hops.push_back(mesh_.to_vertex(f));
      near_hops.push_back(mesh_.from_vertex(b));
      f = mesh_.next(f), b = mesh_.prev(b);
    }
  }
  const double margin = opt_.contact_margin_deg * kDeg;
  Vertex best;
  double best_d = std::numeric_limits<double>::infinity();
  // Every vertex whose state is not Interior is in front_grid_ (set_state).
  const auto& positions = mesh_.positions().vector();
  front_grid_->for_each_near(pv, opt_.contact_radius * r, positions, [&](Index xi, const Vec3& px) {
    const Vertex x(xi);
    if (x == v || state_[x] == VState::Interior || mesh_.is_deleted(x) || mesh_.is_isolated(x) ||
        !mesh_.is_boundary(x))
      return;
    if (std::find(near_hops.begin(), near_hops.end(), x) != near_hops.end()) return;
    if (normal_[x].dot(n) <= opt_.min_normal_cosine) return;
    const double a = ccw_angle(k.dw, tangent_dir(pv, n, px), n);
    if (!(a > margin && a < k.angle - margin)) return;
    const Corner kx = corner(x);
    const double ax = ccw_angle(kx.dw, tangent_dir(px, normal_[x], pv), normal_[x]);
    if (trace_)
      tracef("contact candidate v%u for v%u: a %.1f of %.1f, ax %.1f of %.1f\n", x.idx(), v.idx(), a / kDeg,
             k.angle / kDeg, ax / kDeg, kx.angle / kDeg);
    if (!(ax > margin && ax < kx.angle - margin)) return;
    // The nearest candidate, ties to the lower index: the verdict does not
    // depend on the order in which the grid visits its points.
    const double d = (px - pv).squaredNorm();
    if (d < best_d || (d == best_d && x.idx() < best.idx())) best_d = d, best = x;
  });
  if (!best.is_valid()) return false;
  if (holder_of(best) != kInvalidIndex) {
    hold(v, holder_of(best));
    return true;
  }
  return contact_with(v, k, best);
}

bool Sweep::contact_with(Vertex v, const Corner& k, Vertex best) {
  const Vec3 pv = mesh_.position(v), n = normal_[v];
  // Two ways to join: v->w with x_u->x (quad v w x_u x), or u->v with x->x_w
  // (quad u v x x_w). Take the convex one that fits at its four corners, with
  // the better minimum angle.
  const Halfedge xo = mesh_.halfedge(best);
  const Halfedge cand[2][2] = {{k.out, mesh_.prev(xo)}, {k.in, xo}};
  double best_q = -1;
  int pick = -1;
  for (int o = 0; o < 2; ++o) {
    const Vertex a = mesh_.from_vertex(cand[o][0]), b = mesh_.to_vertex(cand[o][0]);
    const Vertex c = mesh_.from_vertex(cand[o][1]), d = mesh_.to_vertex(cand[o][1]);
    if (a == c || a == d || b == c || b == d) continue;
    if (mesh_.find_halfedge(b, c).is_valid() || mesh_.find_halfedge(d, a).is_valid() ||
        mesh_.find_halfedge(a, c).is_valid() || mesh_.find_halfedge(b, d).is_valid())
      continue;
    if (!quad_fits(a, b, c, d, pv, n) || !ladder_fits(cand[o][0], cand[o][1], Rails{})) continue;
    const Vec3 pa = mesh_.position(a), pb = mesh_.position(b), pc = mesh_.position(c), pd = mesh_.position(d);
    const double qual = std::max(std::min(min_angle(pa, pb, pc), min_angle(pc, pd, pa)),
                                 std::min(min_angle(pa, pb, pd), min_angle(pb, pc, pd)));
    if (qual > best_q) best_q = qual, pick = o;
  }
  if (pick < 0) return false;
  if (trace_) tracef("contact v%u with v%u (dist %.3f)\n", v.idx(), best.idx(), (mesh_.position(best) - pv).norm());
  bridge(cand[pick][0], cand[pick][1], kInvalidIndex, Rails{});
  ++stats_.contacts;
  return true;
}

bool Sweep::fan_collision(Vertex v, const Corner& k, int m) {
  // A new point within collision_radius · r of a vertex x other than u, v, w
  // would come too close to another part of the front
  // (papers/front/open_questions.md Q4.3 b). Join v to x instead, hold v if x
  // is held, or let the front move on and come back.
  const double r = disc_radius(v);
  const Vec3 pv = mesh_.position(v), n = normal_[v];
  // The first fan point (in fan order) with such a vertex; of its vertices,
  // the nearest, ties to the lower index (independent of the grid's order).
  Vertex hit;
  for (int i = 1; i < m && !hit.is_valid(); ++i) {
    const Vec3 q = pv + r * rotate(k.dw, n, i * k.angle / m);
    double hit_d = std::numeric_limits<double>::infinity();
    vertex_grid_->for_each_near(q, opt_.collision_radius * r, mesh_.positions().vector(),
                                [&](Index xi, const Vec3& px) {
      const Vertex x(xi);
      if (x == v || x == k.u || x == k.w || mesh_.is_deleted(x)) return;
      if (mesh_.is_isolated(x) || normal_[x].dot(n) <= opt_.min_normal_cosine) return;
      // a front vertex, or an interior one: the fan would cover meshed surface
      const double d = (px - q).squaredNorm();
      if (d < hit_d || (d == hit_d && xi < hit.idx())) hit_d = d, hit = x;
    });
  }
  if (!hit.is_valid()) return false;
  ++stats_.collisions;
  if (trace_) tracef("collision: fan of v%u reaches v%u\n", v.idx(), hit.idx());
  if (holder_of(hit) != kInvalidIndex) {
    hold(v, holder_of(hit));
    return true;
  }
  if (mesh_.is_boundary(hit) && contact_with(v, k, hit)) return true;
  if (deferrals_[v] < opt_.max_deferrals) {
    defer(v, r);
    return true;
  }
  return false;
}

}  // namespace skinmesh::front::detail
