// front/creation.cpp: creation() at a minimum (Cheng & Shi 2004 §4.1, "Initial
// front", Figure 5): six points at 60° on the tangent circle of radius
// r = disc_factor · rho, projected onto the skin, make a bowl of six triangles
// whose rim is the first front polygon.
// Notes: papers/front/creation.md
#include <array>

#include "front/operations.h"

namespace skinmesh::front::detail {

void creation(FrontState& fs, Index c) {
  const morse::CriticalPoint& cp = fs.ms.critical[c];
  const Vertex p0 = new_vertex(fs, cp.position, cp.cell);
  const Vec3 n = fs.normal[p0];
  const Vec3 t1 = n.unitOrthogonal();
  const double r = fs.disc_radius(p0);
  // The paper's bowl has six triangles: 360° / fan_angle_deg of them.
  const int k = static_cast<int>(std::lround(360.0 / fs.opt.fan_angle_deg));
  std::vector<Vertex> ring(static_cast<std::size_t>(k));
  for (int i = 0; i < k; ++i) {
    // q_i on the tangent circle, projected along the normal line to p_i.
    const Vec3 dir = rotate(t1, n, i * fs.opt.fan_angle_deg * kDegree);
    Index cell = kInvalidIndex;
    const Vec3 p = project_tangent(fs, p0, dir, r, &cell);
    ring[static_cast<std::size_t>(i)] = new_vertex(fs, p, cell);
  }
  for (int i = 0; i < k; ++i)
    fs.add_triangle(p0, ring[static_cast<std::size_t>(i)], ring[static_cast<std::size_t>((i + 1) % k)]);
  fs.set_state(p0, VState::Interior);
  // "We push all the edges in the front polygons to a priority queue."
  for (Vertex v : ring) push(fs, v);
  ++fs.stats.creations;
}

}  // namespace skinmesh::front::detail
