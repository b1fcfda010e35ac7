// front/hole_filling.cpp: the project's hole filling — not in the paper.
//  - small holes: when the fronts around a departure vertex have met in a
//    loop of a few vertices, the hole is closed at once (as seal() would)
//    instead of creeping new vertices into it;
//  - the max-min-angle programme: a hole of at most dp_max_hole_vertices
//    vertices is triangulated by dynamic programming over all its
//    triangulations, keeping only triangles that face outwards and fit the
//    hole wedges at their corners;
//  - enlargement: a hole tangled in every projection plane is re-opened by
//    deleting the faces around it, and sealed again.
// Notes: papers/front/hole_filling.md
#include <algorithm>

#include "front/sweep_internal.h"
#include "geometry/check/mesh_checks.h"

namespace skinmesh::front::detail {

using geometry::min_angle;

bool Sweep::small_hole(Vertex v) const {
  const double reach = opt_.small_hole_reach * disc_radius(v);
  const Halfedge start = mesh_.halfedge(v);
  // First the cheap part: the loop closes within small_hole_vertices vertices,
  // all within reach of v (most departures stop here, before any angle).
  Halfedge h = start;
  int count = 1;
  for (;; ++count) {
    if (count > opt_.small_hole_vertices) return false;
    const Vertex x = mesh_.to_vertex(h);
    if (x == v) break;
    if ((mesh_.position(x) - mesh_.position(v)).norm() > reach) return false;
    h = mesh_.next(h);
  }
  // A loop of k vertices bounds a small hole iff its hole angles add up to
  // less than k 180°: (k - 2) 180° inside a polygon, (k + 2) 180° around the
  // outside of a small disc (like a fresh bowl).
  double angle_sum = 0;
  h = start;
  for (int i = 0; i < count; ++i, h = mesh_.next(h)) angle_sum += corner(mesh_.to_vertex(h)).angle;
  return angle_sum < count * kPi;
}

bool Sweep::fill_hole_dp(const std::vector<Vertex>& poly) {
  const std::size_t k = poly.size();
  const double kNone = -1;
  // q[i][j]: best minimum angle of a triangulation of the sub-polygon
  // poly[i..j] closed by the diagonal (i, j); arg[i][j]: its apex.
  std::vector<double> q(k * k, kNone);
  std::vector<std::size_t> arg(k * k, k);
  auto at = [k](std::size_t i, std::size_t j) { return i * k + j; };
  auto diagonal_ok = [&](std::size_t i, std::size_t j) {
    if (j == i + 1 || (i == 0 && j == k - 1)) return true;  // a hole edge
    return !mesh_.find_halfedge(poly[i], poly[j]).is_valid();
  };
  auto tri_quality = [&](std::size_t i, std::size_t m, std::size_t j) {
    const Vec3 &a = mesh_.position(poly[i]), &b = mesh_.position(poly[m]), &c = mesh_.position(poly[j]);
    const Vec3 nt = (b - a).cross(c - a);
    if (nt.dot(normal_[poly[i]]) <= 0 || nt.dot(normal_[poly[m]]) <= 0 || nt.dot(normal_[poly[j]]) <= 0) return kNone;
    // Each corner's span must lie in that vertex's hole wedge (no overlap
    // with the triangles already there).
    if (!fits_at(poly[i], poly[m], poly[j]) || !fits_at(poly[m], poly[j], poly[i]) ||
        !fits_at(poly[j], poly[i], poly[m]))
      return kNone;
    return min_angle(a, b, c);
  };
  for (std::size_t i = 0; i + 1 < k; ++i) q[at(i, i + 1)] = kPi;  // an edge: nothing to fill
  for (std::size_t len = 2; len < k; ++len)
    for (std::size_t i = 0; i + len < k; ++i) {
      const std::size_t j = i + len;
      if (!diagonal_ok(i, j)) continue;
      for (std::size_t m = i + 1; m < j; ++m) {
        const double sub = std::min(q[at(i, m)], q[at(m, j)]);
        if (sub <= q[at(i, j)]) continue;
        const double t = std::min(sub, tri_quality(i, m, j));
        if (t > q[at(i, j)]) q[at(i, j)] = t, arg[at(i, j)] = m;
      }
    }
  if (q[at(0, k - 1)] <= 0) return false;
  std::vector<std::array<std::size_t, 2>> stack{{0, k - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j == i + 1) continue;
    const std::size_t m = arg[at(i, j)];
    add_triangle(poly[i], poly[m], poly[j]);
    stack.push_back({i, m});
    stack.push_back({m, j});
  }
  for (Vertex v : poly) set_state(v, VState::Interior);
  ++stats_.seals;
  if (trace_) tracef("seal loop of %zu by the max-min-angle programme\n", k);
  return true;
}

Halfedge Sweep::enlarge_hole(const std::vector<Vertex>& poly) {
  std::vector<Vertex> rim;  // surviving corners of the deleted faces
  // Deletes every face around the vertices `around`; their corners that keep
  // a face join the rim.
  auto delete_faces_around = [&](const std::vector<Vertex>& around) {
    std::vector<Face> faces;
    for (Vertex v : around)
      for (Face f : mesh_.faces(v))
        if (std::find(faces.begin(), faces.end(), f) == faces.end()) faces.push_back(f);
    std::vector<Vertex> corners;
    for (Face f : faces)
      for (Vertex x : mesh_.vertices(f)) corners.push_back(x);
    for (Face f : faces) mesh_.delete_face(f);
    for (Vertex x : corners)
      if (!mesh_.is_deleted(x) && !mesh_.is_isolated(x)) rim.push_back(x);
  };
  auto gaps = [&](Vertex x) {
    int n = 0;
    for (Halfedge h : mesh_.halfedges(x)) n += mesh_.is_boundary(h);
    return n;
  };
  delete_faces_around(poly);
  // A pinched vertex (two boundary gaps) cannot be handled by the front:
  // delete its remaining faces too, a few times at most.
  for (int round = 0; round < opt_.max_pinch_rounds; ++round) {
    std::vector<Vertex> pinched;
    for (Vertex x : rim)
      if (!mesh_.is_deleted(x) && !mesh_.is_isolated(x) && gaps(x) > 1) pinched.push_back(x);
    if (pinched.empty()) break;
    delete_faces_around(pinched);
  }
  Halfedge start;
  for (Vertex x : rim) {
    if (mesh_.is_deleted(x) || mesh_.is_isolated(x)) continue;
    if (gaps(x) != 1) return Halfedge();
    set_state(x, VState::Front);
    start = mesh_.halfedge(x);
  }
  return start;
}

bool Sweep::reopen_hole(const std::vector<Vertex>& poly) {
  // Bound the re-meshing: a vertex on the rim of too many re-opened regions
  // means the sweep keeps tangling there.
  for (Vertex v : poly)
    if (reopenings_[v] >= opt_.max_reopenings) return false;
  // The region: the faces around the hole's vertices, grown at every corner
  // that would be pinched (two separate gaps in its fan) until none is, so
  // that the rim is a plain front (it may join the front around it: the sweep
  // goes on from there). Decided before anything is deleted.
  std::vector<Face> region;
  auto add_faces_around = [&](Vertex v) {
    for (Face f : mesh_.faces(v))
      if (std::find(region.begin(), region.end(), f) == region.end()) region.push_back(f);
  };
  for (Vertex v : poly) add_faces_around(v);
  std::sort(region.begin(), region.end());
  auto open = [&](Halfedge h) {  // the slot of h in its vertex's fan: a gap or a deleted face
    return mesh_.is_boundary(h) || std::binary_search(region.begin(), region.end(), mesh_.face(h));
  };
  const std::size_t max_faces = 64 * std::max<std::size_t>(region.size(), 1);
  std::vector<Vertex> rim;
  for (int round = 0;; ++round) {
    rim.clear();
    for (Face f : region)
      for (Vertex x : mesh_.vertices(f)) rim.push_back(x);
    std::sort(rim.begin(), rim.end());
    rim.erase(std::unique(rim.begin(), rim.end()), rim.end());
    std::vector<Vertex> pinched;
    for (Vertex x : rim) {
      int runs = 0, slots = 0, open_slots = 0;
      bool prev = false, first = false;
      for (Halfedge h : mesh_.halfedges(x)) {
        const bool o = open(h);
        if (slots == 0) first = o;
        else if (o && !prev) ++runs;
        prev = o, ++slots, open_slots += o;
      }
      if (first && !prev) ++runs;  // the circular wrap closes a run that starts the fan
      if (open_slots < slots && runs > 1) pinched.push_back(x);
    }
    if (pinched.empty()) break;
    if (round >= opt_.max_pinch_rounds || region.size() > max_faces) return false;
    for (Vertex x : pinched) add_faces_around(x);
    std::sort(region.begin(), region.end());
  }
  for (Face f : region) mesh_.delete_face(f);
  ++stats_.reopened_holes;
  for (Vertex x : rim) {
    if (mesh_.is_deleted(x) || mesh_.is_isolated(x)) continue;
    if (reopenings_[x] < 255) ++reopenings_[x];
    if (held_by_[x] != kInvalidIndex && !resolved_[held_by_[x]] && state_[x] == VState::Held) continue;
    set_state(x, VState::Front);
    push(x);
  }
  if (trace_) tracef("re-opened %zu faces around a tangled small hole of %zu vertices\n", region.size(), poly.size());
  return true;
}

}  // namespace skinmesh::front::detail
