// front/creation.cpp: creation() at a minimum (Cheng & Shi 2004 §4.1, "Initial
// front", Figure 5): six points at 60° on the tangent circle of radius
// r = disc_factor · rho, projected onto the skin, make a bowl of six triangles
// whose rim is the first front polygon.
// Notes: papers/front/creation.md
#include <array>

#include "front/sweep_internal.h"

namespace skinmesh::front::detail {

void Sweep::creation(Index c) {
  const morse::CriticalPoint& cp = ms_.critical[c];
  const Vertex p0 = new_vertex(cp.position, cp.cell);
  const Vec3 n = normal_[p0];
  const Vec3 t1 = n.unitOrthogonal();
  const double r = disc_radius(p0);
  // The paper's bowl has six triangles: 360° / fan_angle_deg of them.
  const int k = static_cast<int>(std::lround(360.0 / opt_.fan_angle_deg));
  std::vector<Vertex> ring(static_cast<std::size_t>(k));
  for (int i = 0; i < k; ++i) {
    // q_i on the tangent circle, projected along the normal line to p_i.
    const Vec3 dir = rotate(t1, n, i * opt_.fan_angle_deg * kDeg);
    Index cell = kInvalidIndex;
    const Vec3 p = project_tangent(p0, dir, r, &cell);
    ring[static_cast<std::size_t>(i)] = new_vertex(p, cell);
  }
  for (int i = 0; i < k; ++i)
    add_triangle(p0, ring[static_cast<std::size_t>(i)], ring[static_cast<std::size_t>((i + 1) % k)]);
  set_state(p0, VState::Interior);
  // "We push all the edges in the front polygons to a priority queue."
  for (Vertex v : ring) push(v);
  ++stats_.creations;
}

}  // namespace skinmesh::front::detail
