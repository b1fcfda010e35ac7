// front/creep.cpp: creep() at the departure vertex (Cheng & Shi 2004 §4.1,
// "Creeping triangles"), in two parts. plan_creep(): the Figure 7 test — a
// fan triangle that would not fit in a neighbour's hole wedge makes that
// neighbour a forced wing (or holds, defers or finally leaves v for the
// seal) — then the fold check and the collision net decide whether the fan
// is built. build_fan(), Figure 6: a fan of m = ceil(theta / 60°) triangles
// over the hole angle theta at v, its m - 1 new points on the tangent circle
// projected onto the skin.
// Notes: papers/front/creep.md
#include <algorithm>
#include <sstream>

#include "core/errors.h"
#include "front/operations.h"

namespace skinmesh::front::detail {

CreepVerdict leave_fold(FrontState& fs, Vertex v) {
  // The fold is already in the mesh around v: building on it would carry it
  // into the rest of the sweep. Its faces go, the rim back to the front (as a
  // tangled small hole's do); where that is no longer allowed, v is left for
  // the seal, whose fallback re-meshes the region (papers/front/patch.md).
  ++fs.stats.folds;
  if (fs.tracing) fs.tracef("creep: the mesh folds at v%u: the fallback takes it\n", v.idx());
  const std::vector<Vertex> around{v};
  if (reopen_hole(fs, around)) return CreepVerdict::Reopened;
  leave_hole_for_seal(fs, around);
  return CreepVerdict::Stuck;
}

CreepPlan plan_creep(FrontState& fs, Vertex v) {
  const double r = fs.disc_radius(v);
  // Copies: new vertices grow the property arrays and would invalidate references.
  const Vec3 n = fs.normal[v];
  const Vec3 pv = fs.mesh.position(v);
  const double fan_angle = fs.opt.fan_angle_deg * kDegree;
  CreepPlan plan;
  Corner& k = plan.corner;
  int& m = plan.triangles;
  m = 1;
  // Figure 7: if the first (last) fan triangle would not fit in the hole
  // wedge of w (u), measured in T_w (T_u), or its new point would come close
  // to w's (u's) other neighbour, wing w (u) first and look again.
  // The end points p_1 and p_{m-1} of the last Figure 7 test, projected
  // there once and reused by the fan (valid while test_m == m and k is the
  // corner they were computed for).
  int& test_m = plan.tested_triangles;
  Vec3& test_p1 = plan.p1;
  Vec3& test_pm = plan.pm;
  Index& test_cell1 = plan.cell1;
  Index& test_cellm = plan.cellm;
  auto decided = [&plan](CreepVerdict verdict) {
    plan.verdict = verdict;
    return plan;
  };
  for (int attempt = 0;; ++attempt) {
    k = corner(fs, v);
    test_m = 0;
    if (!std::isfinite(k.angle)) {
      if (fs.opt.patch_fallback) return decided(leave_fold(fs, v));
      std::ostringstream os;
      os << "creep: undefined front angle at vertex " << v.idx() << " (" << pv.transpose()
         << "): a front neighbour coincides with it in the tangent plane";
      throw TopologyError(os.str());
    }
    if (k.angle < fs.opt.wing_angle_deg * kDegree && wing(fs, v, false)) return decided(CreepVerdict::Wing);
    if (attempt == 0 && try_contact(fs, v, k)) return decided(CreepVerdict::Contact);
    m = std::max(1, static_cast<int>(std::ceil(k.angle / fan_angle - kFanCountSlack)));
    if (attempt >= fs.opt.max_wing_rounds) break;
    const Vertex w2 = fs.mesh.to_vertex(fs.mesh.next(k.out));
    const Vertex u2 = fs.mesh.from_vertex(fs.mesh.prev(k.in));
    const Vec3 pw2 = fs.mesh.position(w2), pu2 = fs.mesh.position(u2);
    // Figure 7 test of a fan of mm triangles at both ends. For mm = 1 the
    // "fan" is the single triangle (v, w, u). Triangle (v, w, p1) spans from
    // p1 to v at w; (v, p_{m-1}, u) from v to p_{m-1} at u.
    auto test_fan = [&](int mm, bool& bw, bool& bu) {
      // The new points where they will be: projected onto the skin along
      // v's normal. That keeps their direction in T_v but not in T_w or T_u,
      // where a point just inside the wedge on the tangent circle can fall
      // just outside it on the skin (src kinase at probe 0: 0.3° inside, then
      // a fold at w).
      // For mm = 2 both ends are the same point (the angles k.angle / 2 and
      // k.angle * 1 / 2 are the same double), projected once.
      test_m = mm;
      if (mm == 1) {
        test_p1 = fs.mesh.position(k.u), test_pm = fs.mesh.position(k.w);
      } else {
        test_p1 = project_tangent(fs, v, rotate(k.dw, n, k.angle / mm), r, &test_cell1);
        if (mm == 2)
          test_pm = test_p1, test_cellm = test_cell1;
        else
          test_pm = project_tangent(fs, v, rotate(k.dw, n, k.angle * (mm - 1) / mm), r, &test_cellm);
      }
      const Vec3& p1 = test_p1;
      const Vec3& pm = test_pm;
      const Vertex p1v = mm == 1 ? k.u : Vertex(), pmv = mm == 1 ? k.w : Vertex();
      const double clearance = fs.opt.fan_clearance * r;
      bw = w2 != k.u && ((mm > 1 && (p1 - pw2).norm() < clearance) || !fits_at(fs, k.w, p1, pv, p1v, v));
      bu = u2 != k.w && ((mm > 1 && (pm - pu2).norm() < clearance) || !fits_at(fs, k.u, pv, pm, v, pmv));
    };
    bool bad_w = false, bad_u = false;
    test_fan(m, bad_w, bad_u);
    if (fs.tracing)
      fs.tracef("creep v%u theta %.1f m %d w v%u u v%u w2 v%u u2 v%u bad_w %d bad_u %d state_u %d\n", v.idx(),
                k.angle / kDegree, m, k.w.idx(), k.u.idx(), w2.idx(), u2.idx(), bad_w, bad_u, int(fs.state[k.u]));
    if (bad_w && wing(fs, k.w, true)) continue;
    if (bad_u && wing(fs, k.u, true)) continue;
    // The neighbour's own neighbour may close a narrow spike first.
    if (bad_w && w2 != k.u && wing(fs, w2, true)) continue;
    if (bad_u && u2 != k.w && wing(fs, u2, true)) continue;
    // A fan that would fold over a held neighbour: v joins the hold (it is at
    // the rim of the hold region; the bridge or seal will take care of it).
    const Index holder = bad_w && fs.holder_of(k.w) != kInvalidIndex ? fs.holder_of(k.w)
                         : bad_u                                     ? fs.holder_of(k.u)
                                                                     : kInvalidIndex;
    if (holder != kInvalidIndex) {
      hold(fs, v, holder);
      return decided(CreepVerdict::Hold);
    }
    if ((bad_w || bad_u) && fs.deferrals[v] >= fs.opt.max_deferrals) {
      // Last resort before giving up: a fan with more or fewer triangles
      // whose end triangles fit.
      for (int mm : {m + 1, m + 2, m - 1}) {
        if (mm < 1 || (mm == 1 && k.angle >= kPi)) continue;
        bool bw = false, bu = false;
        test_fan(mm, bw, bu);
        if (!bw && !bu) {
          m = mm, bad_w = bad_u = false;
          break;
        }
      }
      if (!bad_w && !bad_u) break;
    }
    if ((bad_w || bad_u) && fs.deferrals[v] < fs.opt.max_deferrals) {
      // The fan would fold over a neighbour that cannot be winged now: let
      // the front move on around v and try again a little later.
      defer(fs, v, r);
      return decided(CreepVerdict::Defer);
    }
    if (bad_w || bad_u) {
      // Stuck: no fan fits here even after the front moved on. v stays on the
      // front without departing again; the hole around it is filled when the
      // fronts meet (small hole) or at the seal, and the final checks decide.
      if (fs.tracing)
        fs.tracef("creep: v%u is stuck: its fan would fold over v%u (Figure 7)\n", v.idx(), (bad_w ? k.w : k.u).idx());
      fs.set_state(v, VState::Held);
      fs.held_by[v] = kInvalidIndex;
      ++fs.stats.stuck;
      return decided(CreepVerdict::Stuck);
    }
    break;
  }
  // Fold check (papers/front/open_questions.md Q4.1 (the fan and its orientation)): the tangent angles of
  // the triangles at v plus the hole angle make a full turn.
  const std::size_t fold_check = fs.fold_checks++;
  if (const double excess = fold_excess(fs, v); std::abs(excess) > fs.opt.fold_tolerance_deg * kDegree ||
                                                std::find(fs.opt.injected_folds.begin(), fs.opt.injected_folds.end(),
                                                          fold_check) != fs.opt.injected_folds.end()) {
    if (fs.opt.patch_fallback) return decided(leave_fold(fs, v));
    std::ostringstream os;
    os << "creep: the mesh folds at vertex " << v.idx() << " (" << pv.transpose() << "): triangles and hole cover "
       << (2 * kPi + excess) / kDegree << "°";
    throw TopologyError(os.str());
  }
  // The safety net for the fan (collision_net.cpp).
  if (fan_collision(fs, v, k, m)) return decided(CreepVerdict::Collision);
  return decided(CreepVerdict::Build);
}

void build_fan(FrontState& fs, Vertex v, const CreepPlan& plan) {
  const double r = fs.disc_radius(v);
  const Vec3 n = fs.normal[v];  // a copy: new vertices grow the property arrays
  const Corner& k = plan.corner;
  const int m = plan.triangles;
  const int test_m = plan.tested_triangles;
  // The fan: p_0 = w, p_1 .. p_{m-1} new, p_m = u (Figure 6).
  std::vector<Vertex>& fan = fs.scratch_fan;  // a member: no allocation per creep
  fan.clear();
  fan.push_back(k.w);
  for (int i = 1; i < m; ++i) {
    // The same rotation angle as test_fan's for i = 1 (1 * a / m == a / m) and
    // i = m - 1 ((m - 1) * a == a * (m - 1)): its projections are reused.
    if (test_m == m && i == 1) {
      fan.push_back(new_vertex(fs, plan.p1, plan.cell1));
    } else if (test_m == m && i == m - 1) {
      fan.push_back(new_vertex(fs, plan.pm, plan.cellm));
    } else {
      Index cell = kInvalidIndex;
      const Vec3 p = project_tangent(fs, v, rotate(k.dw, n, i * k.angle / m), r, &cell);
      fan.push_back(new_vertex(fs, p, cell));
    }
  }
  fan.push_back(k.u);
  for (int i = 1; i <= m; ++i) fs.add_triangle(v, fan[i - 1], fan[i]);
  fs.set_state(v, VState::Interior);
  // "After each creep() operation, we push the new front edges to the
  // priority queue"; the fan's ends and points are wing candidates.
  for (int i = 1; i < m; ++i) push(fs, fan[i]);
  fs.wing_worklist.push_back(k.u);
  fs.wing_worklist.push_back(k.w);
  for (int i = 1; i < m; ++i) fs.wing_worklist.push_back(fan[i]);
  ++fs.stats.creeps;
}

void creep(FrontState& fs, Vertex v) {
  const CreepPlan plan = plan_creep(fs, v);
  if (plan.verdict == CreepVerdict::Build) build_fan(fs, v, plan);
}

}  // namespace skinmesh::front::detail
