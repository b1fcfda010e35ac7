// front/wing.cpp: wing() (Cheng & Shi 2004 §4.1, Figure 7): a front angle
// below 90° at v is closed by the triangle (v, w, u), so that the next fan
// cannot overlap the triangles already there. Wings run after every creep
// (a worklist of the vertices it touched) and, forced up to 180°, inside the
// Figure 7 test of creep().
// Notes: papers/front/wing.md
#include "front/sweep_internal.h"

namespace skinmesh::front::detail {

bool Sweep::wing(Vertex v, bool force) {
  const char* why = wing_refusal(v, force);
  if (force && why && trace_) tracef("wing v%u refused: %s\n", v.idx(), why);
  if (why) return false;
  // The front neighbours (the hole angle is not needed here).
  const Halfedge out = mesh_.halfedge(v);
  const Vertex w = mesh_.to_vertex(out), u = mesh_.from_vertex(mesh_.prev(out));
  add_triangle(v, w, u);
  set_state(v, VState::Interior);
  wing_worklist_.push_back(u);
  wing_worklist_.push_back(w);
  ++stats_.wings;
  return true;
}

const char* Sweep::wing_refusal(Vertex v, bool force) const {
  if (state_[v] != VState::Front || !mesh_.is_boundary(v)) return "not a free front vertex";
  const double max_angle = (force ? opt_.forced_wing_angle_deg : opt_.wing_angle_deg) * kDeg;
  if (clearly_not_below(v, max_angle)) return "front angle too large";
  const Corner k = corner(v);
  if (k.angle >= max_angle) return "front angle too large";
  // A 3-gon is closed only by seal; the new edge u-w must not exist yet.
  if (mesh_.next(k.out) == k.in) return "the front loop is a triangle";
  if (mesh_.find_halfedge(k.w, k.u).is_valid()) return "the edge u-w exists";
  // An unforced wing leaves held neighbours alone (their front edges are what
  // the bridge joins); a forced one (Figure 7) may touch them.
  if (!force && (state_[k.u] == VState::Held || state_[k.w] == VState::Held)) return "a neighbour is held";
  if ((mesh_.position(k.w) - mesh_.position(k.u)).norm() >
      opt_.wing_max_edge_factor * std::max(disc_radius(k.w), disc_radius(k.u)))
    return "the new edge u-w would be too long";
  const Vec3 nt = (mesh_.position(k.w) - mesh_.position(v)).cross(mesh_.position(k.u) - mesh_.position(v));
  if (nt.dot(normal_[v]) <= 0) return "the triangle would face inwards";
  // Triangle (v, w, u): at w it spans from u to v, at u from v to w.
  if (!fits_at(k.w, k.u, v)) return "it does not fit at w";
  if (!fits_at(k.u, v, k.w)) return "it does not fit at u";
  return nullptr;
}

void Sweep::drain_wings() {
  while (!wing_worklist_.empty()) {
    const Vertex v = wing_worklist_.back();
    wing_worklist_.pop_back();
    wing(v, false);
  }
}

}  // namespace skinmesh::front::detail
