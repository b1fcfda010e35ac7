// front/wing.cpp: wing() (Cheng & Shi 2004 §4.1, Figure 7): a front angle
// below 90° at v is closed by the triangle (v, w, u), so that the next fan
// cannot overlap the triangles already there. Wings run after every creep
// (a worklist of the vertices it touched) and, forced up to 180°, inside the
// Figure 7 test of creep().
// Notes: papers/front/wing.md
#include "front/operations.h"

namespace skinmesh::front::detail {

namespace {
/// wing_refusal's reason when the triangle would cover a front vertex (compared by address in wing()).
constexpr const char* kCoversFrontVertex = "it would cover a front vertex";
}  // namespace

bool wing(FrontState& fs, Vertex v, bool force) {
  const char* why = wing_refusal(fs, v, force);
  if (force && why && fs.tracing) fs.tracef("wing v%u refused: %s\n", v.idx(), why);
  if (why == kCoversFrontVertex) ++fs.stats.covered_triangles;
  if (why) return false;
  // The front neighbours (the hole angle is not needed here).
  const Halfedge out = fs.mesh.halfedge(v);
  const Vertex w = fs.mesh.to_vertex(out), u = fs.mesh.from_vertex(fs.mesh.prev(out));
  fs.add_triangle(v, w, u);
  fs.set_state(v, VState::Interior);
  fs.wing_worklist.push_back(u);
  fs.wing_worklist.push_back(w);
  ++fs.stats.wings;
  return true;
}

const char* wing_refusal(const FrontState& fs, Vertex v, bool force) {
  // A vertex on the worklist may have lost its faces since (a re-opened region).
  if (fs.mesh.is_deleted(v) || fs.mesh.is_isolated(v) || fs.state[v] != VState::Front || !fs.mesh.is_boundary(v))
    return "not a free front vertex";
  const double max_angle = (force ? fs.opt.forced_wing_angle_deg : fs.opt.wing_angle_deg) * kDegree;
  if (clearly_not_below(fs, v, max_angle)) return "front angle too large";
  const Corner k = corner(fs, v);
  if (k.angle >= max_angle) return "front angle too large";
  // A 3-gon is closed only by seal; the new edge u-w must not exist yet.
  if (fs.mesh.next(k.out) == k.in) return "the front loop is a triangle";
  if (fs.mesh.find_halfedge(k.w, k.u).is_valid()) return "the edge u-w exists";
  // An unforced wing leaves held neighbours alone (their front edges are what
  // the bridge joins); a forced one (Figure 7) may touch them.
  if (!force && (fs.state[k.u] == VState::Held || fs.state[k.w] == VState::Held)) return "a neighbour is held";
  if ((fs.mesh.position(k.w) - fs.mesh.position(k.u)).norm() >
      fs.opt.wing_max_edge_factor * std::max(fs.disc_radius(k.w), fs.disc_radius(k.u)))
    return "the new edge u-w would be too long";
  const Vec3 nt = (fs.mesh.position(k.w) - fs.mesh.position(v)).cross(fs.mesh.position(k.u) - fs.mesh.position(v));
  if (nt.dot(fs.normal[v]) <= 0) return "the triangle would face inwards";
  // Triangle (v, w, u): at w it spans from u to v, at u from v to w.
  if (!fits_at(fs, k.w, k.u, v)) return "it does not fit at w";
  if (!fits_at(fs, k.u, v, k.w)) return "it does not fit at u";
  // Where fronts meet outside a protecting sphere, a front vertex of another
  // part can lie inside the triangle: it would cover it.
  if (covered_front_vertex(fs, v, k.w, k.u).is_valid()) return kCoversFrontVertex;
  return nullptr;
}

void drain_wings(FrontState& fs) {
  while (!fs.wing_worklist.empty()) {
    const Vertex v = fs.wing_worklist.back();
    fs.wing_worklist.pop_back();
    wing(fs, v, false);
  }
}

}  // namespace skinmesh::front::detail
