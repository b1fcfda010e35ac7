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
#include <limits>

#include "front/operations.h"
#include "geometry/check/mesh_checks.h"

namespace skinmesh::front::detail {

using geometry::min_angle;

bool small_hole(const FrontState& fs, Vertex v) {
  const double reach = fs.opt.small_hole_reach * fs.disc_radius(v);
  const Halfedge start = fs.mesh.halfedge(v);
  // First the cheap part: the loop closes within small_hole_vertices vertices,
  // all within reach of v (most departures stop here, before any angle).
  Halfedge h = start;
  int count = 1;
  for (;; ++count) {
    if (count > fs.opt.small_hole_vertices) return false;
    const Vertex x = fs.mesh.to_vertex(h);
    if (x == v) break;
    if ((fs.mesh.position(x) - fs.mesh.position(v)).norm() > reach) return false;
    // A region's boundary (a ghost strip's top, a parked rim) is no hole.
    if (fs.region.role_of(x) != RegionRole::Inside) return false;
    h = fs.mesh.next(h);
  }
  // A loop of k vertices bounds a small hole iff its hole angles add up to
  // less than k 180°: (k - 2) 180° inside a polygon, (k + 2) 180° around the
  // outside of a small disc (like a fresh bowl).
  double angle_sum = 0;
  h = start;
  for (int i = 0; i < count; ++i, h = fs.mesh.next(h)) angle_sum += corner(fs, fs.mesh.to_vertex(h)).angle;
  return angle_sum < count * kPi;
}

bool fill_hole_dp(FrontState& fs, const std::vector<Vertex>& poly) {
  const std::size_t k = poly.size();
  const double kNone = -1;
  // q[i][j]: best minimum angle of a triangulation of the sub-polygon
  // poly[i..j] closed by the diagonal (i, j); arg[i][j]: its apex.
  std::vector<double> q(k * k, kNone);
  std::vector<std::size_t> arg(k * k, k);
  auto at = [k](std::size_t i, std::size_t j) { return i * k + j; };
  auto diagonal_ok = [&](std::size_t i, std::size_t j) {
    if (j == i + 1 || (i == 0 && j == k - 1)) return true;  // a hole edge
    return !fs.mesh.find_halfedge(poly[i], poly[j]).is_valid();
  };
  auto tri_quality = [&](std::size_t i, std::size_t m, std::size_t j) {
    const Vec3 &a = fs.mesh.position(poly[i]), &b = fs.mesh.position(poly[m]), &c = fs.mesh.position(poly[j]);
    const Vec3 nt = (b - a).cross(c - a);
    if (nt.dot(fs.normal[poly[i]]) <= 0 || nt.dot(fs.normal[poly[m]]) <= 0 || nt.dot(fs.normal[poly[j]]) <= 0)
      return kNone;
    // Each corner's span must lie in that vertex's hole wedge (no overlap
    // with the triangles already there).
    if (!fits_at(fs, poly[i], poly[m], poly[j]) || !fits_at(fs, poly[m], poly[j], poly[i]) ||
        !fits_at(fs, poly[j], poly[i], poly[m]))
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
    fs.add_triangle(poly[i], poly[m], poly[j]);
    stack.push_back({i, m});
    stack.push_back({m, j});
  }
  for (Vertex v : poly) fs.set_state(v, VState::Interior);
  ++fs.stats.seals;
  if (fs.tracing) fs.tracef("seal loop of %zu by the max-min-angle programme\n", k);
  return true;
}

Halfedge enlarge_hole(FrontState& fs, const std::vector<Vertex>& poly, std::vector<Vertex>* rim_out) {
  std::vector<Vertex> local_rim;
  std::vector<Vertex>& rim = rim_out ? *rim_out : local_rim;  // surviving corners of the deleted faces
  // Deletes every face around the vertices `around`; their corners that keep
  // a face join the rim.
  auto delete_faces_around = [&](const std::vector<Vertex>& around) {
    std::vector<Face> faces;
    for (Vertex v : around)
      for (Face f : fs.mesh.faces(v))
        if (std::find(faces.begin(), faces.end(), f) == faces.end()) faces.push_back(f);
    std::vector<Vertex> corners;
    for (Face f : faces)
      for (Vertex x : fs.mesh.vertices(f)) corners.push_back(x);
    for (Face f : faces) fs.mesh.delete_face(f);
    for (Vertex x : corners)
      if (!fs.mesh.is_deleted(x) && !fs.mesh.is_isolated(x)) rim.push_back(x);
  };
  auto gaps = [&](Vertex x) {
    int n = 0;
    for (Halfedge h : fs.mesh.halfedges(x)) n += fs.mesh.is_boundary(h);
    return n;
  };
  delete_faces_around(poly);
  // A pinched vertex (two boundary gaps) cannot be handled by the front:
  // delete its remaining faces too, a few times at most.
  for (int round = 0; round < fs.opt.max_pinch_rounds; ++round) {
    std::vector<Vertex> pinched;
    for (Vertex x : rim)
      if (!fs.mesh.is_deleted(x) && !fs.mesh.is_isolated(x) && gaps(x) > 1) pinched.push_back(x);
    if (pinched.empty()) break;
    delete_faces_around(pinched);
  }
  Halfedge start;
  for (Vertex x : rim) {
    if (fs.mesh.is_deleted(x) || fs.mesh.is_isolated(x)) continue;
    if (gaps(x) != 1) return Halfedge();
    fs.set_state(x, VState::Front);
    start = fs.mesh.halfedge(x);
  }
  return start;
}

bool reopen_hole(FrontState& fs, const std::vector<Vertex>& poly) {
  // Bound the re-meshing: a vertex on the rim of too many re-opened regions
  // means the sweep keeps tangling there.
  for (Vertex v : poly)
    if (fs.reopenings[v] >= fs.opt.max_reopenings) return false;
  // The region: the faces around the hole's vertices, grown at every corner
  // that would be pinched (two separate gaps in its fan) until none is, so
  // that the rim is a plain front (it may join the front around it: the sweep
  // goes on from there). Decided before anything is deleted.
  std::vector<Face> region;
  auto add_faces_around = [&](Vertex v) {
    for (Face f : fs.mesh.faces(v))
      if (std::find(region.begin(), region.end(), f) == region.end()) region.push_back(f);
  };
  for (Vertex v : poly) add_faces_around(v);
  std::sort(region.begin(), region.end());
  auto open = [&](Halfedge h) {  // the slot of h in its vertex's fan: a gap or a deleted face
    return fs.mesh.is_boundary(h) || std::binary_search(region.begin(), region.end(), fs.mesh.face(h));
  };
  constexpr std::size_t kMaxRegionGrowth = 64;  // [measured] a region that grows more is not a local tangle
  const std::size_t max_faces = kMaxRegionGrowth * std::max<std::size_t>(region.size(), 1);
  std::vector<Vertex> rim;
  for (int round = 0;; ++round) {
    rim.clear();
    for (Face f : region)
      for (Vertex x : fs.mesh.vertices(f)) rim.push_back(x);
    std::sort(rim.begin(), rim.end());
    rim.erase(std::unique(rim.begin(), rim.end()), rim.end());
    std::vector<Vertex> pinched;
    for (Vertex x : rim) {
      int runs = 0, slots = 0, open_slots = 0;
      bool prev = false, first = false;
      for (Halfedge h : fs.mesh.halfedges(x)) {
        const bool o = open(h);
        if (slots == 0)
          first = o;
        else if (o && !prev)
          ++runs;
        prev = o, ++slots, open_slots += o;
      }
      if (first && !prev) ++runs;  // the circular wrap closes a run that starts the fan
      if (open_slots < slots && runs > 1) pinched.push_back(x);
    }
    if (pinched.empty()) break;
    if (round >= fs.opt.max_pinch_rounds || region.size() > max_faces) return false;
    for (Vertex x : pinched) add_faces_around(x);
    std::sort(region.begin(), region.end());
  }
  // A region with a corner on the rim of earlier re-opened regions is where
  // the sweep tangles again: re-meshed from the same rim, it would tangle
  // the same way. And the faces ever deleted stay at most the faces standing,
  // so that the sweep makes at most twice the faces it keeps (the progress
  // guarantee, papers/front/sweep.md).
  for (Vertex x : rim)
    if (fs.reopenings[x] >= fs.opt.max_reopenings) return false;
  if (fs.stats.reopened_faces + 2 * region.size() > fs.mesh.n_faces()) return false;
  for (Face f : region) fs.mesh.delete_face(f);
  fs.stats.reopened_faces += region.size();
  ++fs.stats.reopened_holes;
  for (Vertex x : rim) {
    if (fs.mesh.is_deleted(x) || fs.mesh.is_isolated(x)) continue;
    if (fs.reopenings[x] < std::numeric_limits<std::uint8_t>::max()) ++fs.reopenings[x];
    if (fs.held_by[x] != kInvalidIndex && !fs.resolved[fs.held_by[x]] && fs.state[x] == VState::Held) continue;
    fs.set_state(x, VState::Front);
    push(fs, x);
  }
  if (fs.tracing)
    fs.tracef("re-opened %zu faces around a tangled small hole of %zu vertices\n", region.size(), poly.size());
  return true;
}

void leave_hole_for_seal(FrontState& fs, const std::vector<Vertex>& poly) {
  ++fs.stats.left_holes;
  for (Vertex x : poly) {
    fs.set_state(x, VState::Held);
    fs.held_by[x] = kInvalidIndex;
  }
  if (fs.tracing) fs.tracef("left an opening of %zu vertices for the seal\n", poly.size());
}

}  // namespace skinmesh::front::detail
