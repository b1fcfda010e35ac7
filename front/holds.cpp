// front/holds.cpp: the holds of Algorithm 1 (Cheng & Shi 2004 §4.1, §4.2):
// a front vertex whose tangent disc meets the protecting sphere of an
// unresolved saddle or maximum stops there; a saddle is bridged when the
// front has reached it from two sides; the holds of saddles never bridged
// are released when the queue runs dry.
// Notes: papers/front/sweep.md
#include <algorithm>
#include <limits>

#include "front/operations.h"

namespace skinmesh::front::detail {

using morse::CriticalKind;

Index hold_region(const FrontState& fs, Vertex v) {
  // v is held if its tangent disc meets the protecting sphere of a live
  // saddle or maximum not yet resolved, so that no fan enters the sphere
  // (Cheng & Shi §4.2: "each step of the front advancing must not cross to the
  // other side of the spheres"); the nearest such critical point holds it.
  const Vec3& p = fs.mesh.position(v);
  const double r = fs.disc_radius(v);
  Index best = kInvalidIndex;
  double best_d = std::numeric_limits<double>::infinity();
  fs.for_each_hold_near(p, fs.rho[v], r, [&](Index c, const Vec3& q) {
    if (fs.resolved[c] || !fs.region.holds(c)) return;
    const double d = (p - q).norm();
    // The nearest, ties to the lower index (independent of the grid's order).
    if (d < fs.ms.protect_radius[c] + r && (d < best_d || (d == best_d && c < best))) best = c, best_d = d;
  });
  return best;
}

void hold(FrontState& fs, Vertex v, Index c) {
  // Lines 7 and 10: "mark the triangle red / green"; line 4–5: a saddle that
  // is ready is bridged at once.
  fs.set_state(v, VState::Held);
  fs.held_by[v] = c;
  fs.held[c].push_back(v);
  ++fs.stats.held;
  if (fs.tracing) fs.tracef("hold v%u by critical point %u\n", v.idx(), c);
  const std::size_t f0 = fs.mesh.faces_size();
  fs.notify(SweepOperation::Hold, v, c, f0);
  if (fs.ms.critical[c].kind == CriticalKind::Saddle && try_bridge(fs, c)) {
    paranoid_check(fs, f0, "bridge");
    fs.notify(SweepOperation::Bridge, Vertex(), c, f0);
  }
  const std::size_t f1 = fs.mesh.faces_size();
  drain_wings(fs);
  paranoid_check(fs, f1, "wings after a hold");
  if (fs.mesh.faces_size() > f1) fs.notify(SweepOperation::Wings, v, kInvalidIndex, f1);
}

bool release_holds(FrontState& fs, Index c, bool requeue) {
  bool any = false;
  for (Vertex v : fs.held[c])
    if (fs.state[v] == VState::Held && fs.held_by[v] == c) {
      fs.set_state(v, VState::Front);
      fs.held_by[v] = kInvalidIndex;
      if (requeue && fs.mesh.is_boundary(v)) push(fs, v), any = true;
    }
  fs.held[c].clear();
  return any;
}

namespace {

/// A saddle of a region's slab that the front reached from one side only,
/// its other side parked below the upper cut before the hold region was
/// reached (the saddle a few hundredths of an ångström under a detoured cut:
/// its sphere's hold region and the parking zone overlap): the parked
/// boundary vertices within its protecting radius plus two disc radii are
/// lent to its hold as the missing side, and the saddle bridged as if they
/// had been held. Without the bridge the two cut curves above the saddle
/// share one parked rim and the slab fails ("0 parked rims"). Where every
/// held vertex lies on one side of the saddle's descending plane, the other
/// side's parked vertices are lent from twice that reach: that side parked
/// before its discs met the sphere (src kinase at probe 0 in 16 detoured
/// slabs: a saddle 0.04 Å under a cut, its other side parked 0.41 Å away,
/// reach 0.375 Å; released unbridged, it left a hole the seal could not
/// close, and the cut was dropped).
/// The lent vertices go back to the queue (to park again where they stand)
/// whether or not the bridge is built. True if it was.
bool bridge_to_parked(FrontState& fs, Index c) {
  const morse::CriticalPoint& cp = fs.ms.critical[c];
  const double reach = fs.ms.protect_radius[c] + 2 * fs.opt.disc_factor * cp.rho;
  // [measured] 2: on 18 detoured runs (crambin, HIV protease, src kinase,
  // gramicidin A at probes 0 and 1.4, maltoporin at 1.4; 16 and 32 slabs)
  // 1x reach drops 26 cuts, 2x 16, 3x and 4x 19 (the longer ladders fold).
  constexpr double kMissingSideReach = 2;
  auto side_of = [&](const Vec3& q) { return (q - cp.position).dot(cp.descent) > 0 ? 0 : 1; };
  bool held_on[2] = {false, false};
  for (Vertex v : fs.held[c])
    if (fs.state[v] == VState::Held && fs.held_by[v] == c) held_on[side_of(fs.mesh.position(v))] = true;
  const int missing = held_on[0] == held_on[1] ? -1 : held_on[0] ? 1 : 0;
  const double far = missing < 0 ? reach : kMissingSideReach * reach;
  const auto [lo, hi] = FrontState::local_scales(cp.rho, far);
  std::vector<Index> near;
  fs.front_grid->for_each_near(cp.position, far, lo, hi, fs.mesh.positions().vector(), [&](Index xi, const Vec3& q) {
    const double d = (q - cp.position).norm();
    if (d < reach || (d < far && side_of(q) == missing)) near.push_back(xi);
  });
  std::sort(near.begin(), near.end());
  std::vector<Vertex> lent;
  for (Index xi : near) {
    const Vertex v(xi);
    if (fs.mesh.is_deleted(v) || !fs.region.is_parked(v) || fs.state[v] != VState::Held ||
        fs.held_by[v] != kInvalidIndex || !fs.mesh.is_boundary(v))
      continue;
    fs.held_by[v] = c;
    fs.held[c].push_back(v);
    lent.push_back(v);
  }
  if (lent.empty()) return false;
  const bool bridged = try_bridge(fs, c);
  for (Vertex v : lent) {
    if (fs.mesh.is_deleted(v) || fs.mesh.is_isolated(v) || !fs.mesh.is_boundary(v)) continue;
    if (fs.state[v] == VState::Held && fs.held_by[v] == c) fs.held_by[v] = kInvalidIndex;
    if (bridged) {
      fs.set_state(v, VState::Front);
      push(fs, v);
    }
  }
  if (!bridged) {
    auto& held = fs.held[c];
    held.erase(std::remove_if(held.begin(), held.end(),
                              [&](Vertex v) { return std::find(lent.begin(), lent.end(), v) != lent.end(); }),
               held.end());
  }
  if (bridged && fs.tracing) fs.tracef("bridge saddle %u to %zu parked vertices\n", c, lent.size());
  return bridged;
}

}  // namespace

bool release_saddles(FrontState& fs) {
  // Saddles never bridged (the front reached them from one side only, or the
  // two sides met elsewhere by a contact; in a region that holds before
  // parking, first bridged to a parked other side if one is near): release
  // their holds and go on
  // (papers/front/open_questions.md Q6.4 (one side arrived when the queue runs empty)); the final topology check
  // decides.
  // In a region (front/region.h), another region's saddle that holds
  // nothing here is resolved without a count: the count is of this region's
  // releases (a group of components would otherwise count every saddle of
  // the skin).
  bool any = false;
  for (std::size_t c = 0; c < fs.ms.critical.size(); ++c) {
    if (!fs.ms.live[c] || fs.ms.critical[c].kind != CriticalKind::Saddle || fs.resolved[c]) continue;
    if (fs.region.spec.holds_before_parking && !fs.held[c].empty() && bridge_to_parked(fs, static_cast<Index>(c))) {
      any = true;
      continue;
    }
    fs.resolved[c] = 1;
    if (fs.held[c].empty() && !fs.region.owns(static_cast<Index>(c), fs.ms.critical[c].height)) continue;
    ++fs.stats.released;
    if (fs.tracing) fs.tracef("release saddle %zu unbridged\n", c);
    if (release_holds(fs, static_cast<Index>(c), /*requeue=*/true)) any = true;
  }
  return any;
}

// Algorithm 1

}  // namespace skinmesh::front::detail
