// front/bridge.cpp: bridge() at a saddle (Cheng & Shi 2004 §4.1, "Bridging the
// front", Figure 8). When the front has reached a saddle's protecting sphere
// from two sides, a held front edge of each side is chosen and the gap between
// them is closed by a ladder of rows of two triangles, whose inner points are
// pulled back onto the skin. The same ladder (one row) joins two front parts
// in a contact (collision_net.cpp).
// Notes: papers/front/bridge.md
#include <algorithm>
#include <limits>

#include "front/operations.h"
#include "geometry/check/mesh_checks.h"

namespace skinmesh::front::detail {

using geometry::min_angle;

bool try_bridge(FrontState& fs, Index c) {
  const morse::CriticalPoint& cp = fs.ms.critical[c];
  // Held front edges a -> b with both ends held by c, classified by side of
  // the saddle along its descending direction (papers/front/open_questions.md Q6.1 (when a saddle is ready to be
  // bridged)).
  std::vector<Halfedge> side[2];
  for (Vertex v : fs.held[c]) {
    if (fs.state[v] != VState::Held || fs.held_by[v] != c || !fs.mesh.is_boundary(v)) continue;
    const Halfedge h = fs.mesh.halfedge(v);
    const Vertex w = fs.mesh.to_vertex(h);
    if (fs.state[w] != VState::Held || fs.held_by[w] != c) continue;
    const double sv = (fs.mesh.position(v) - cp.position).dot(cp.descent);
    const double sw = (fs.mesh.position(w) - cp.position).dot(cp.descent);
    if ((sv > 0) != (sw > 0)) continue;
    side[sv > 0 ? 0 : 1].push_back(h);
  }
  // "If the front reaches the protecting sphere of a saddle point on two
  // different sides" — otherwise the saddle is not ready yet.
  if (side[0].empty() || side[1].empty()) return false;
  // True if the front path from vertex x to vertex y (along next) leaves the
  // hold region of c; false if it stays inside it or does not reach y (y is
  // on another boundary loop).
  auto path_leaves = [&](Vertex x, Vertex y, bool& same_loop) {
    Halfedge h = fs.mesh.halfedge(x);
    bool left = false;
    for (std::size_t guard = 0; guard < fs.mesh.n_halfedges(); ++guard) {
      const Vertex z = fs.mesh.from_vertex(h);
      if (z == y) {
        same_loop = true;
        return left;
      }
      if (!(fs.state[z] == VState::Held && fs.held_by[z] == c)) left = true;
      h = fs.mesh.next(h);
      if (fs.mesh.from_vertex(h) == x) break;
    }
    same_loop = false;
    return left;
  };
  // The pair with the closest midpoints among the admissible ones: on two
  // different loops (merge), or on one loop with both connecting paths
  // leaving the hold region (split): a bowl or a front piece that straddles
  // the saddle's descending plane inside the region is one side, not two.
  struct Candidate {
    double dist;
    Halfedge h0, h1;
  };
  std::vector<Candidate> candidates;
  for (Halfedge h0 : side[0])
    for (Halfedge h1 : side[1]) {
      const Vertex a = fs.mesh.from_vertex(h0), b = fs.mesh.to_vertex(h0);
      const Vertex cc = fs.mesh.from_vertex(h1), d = fs.mesh.to_vertex(h1);
      if (a == cc || a == d || b == cc || b == d) continue;
      const double dist =
          (0.5 * (fs.mesh.position(a) + fs.mesh.position(b)) - 0.5 * (fs.mesh.position(cc) + fs.mesh.position(d)))
              .norm();
      // The quad a b c d must be convex in T_s, and the rails a-d, b-c must
      // enter the hole wedges at a, b, c, d (papers/front/open_questions.md Q6.2 (which pair of edges)).
      if (!quad_fits(fs, a, b, cc, d, cp.position, cp.sigma * fs.e)) continue;
      bool same = false;
      const bool leaves1 = path_leaves(b, cc, same);
      if (same) {
        bool same2 = false;
        if (!leaves1 || !path_leaves(d, a, same2)) continue;
      }
      candidates.push_back({dist, h0, h1});
    }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    return x.dist < y.dist ||
           (x.dist == y.dist && (x.h0.idx() < y.h0.idx() || (x.h0.idx() == y.h0.idx() && x.h1.idx() < y.h1.idx())));
  });
  // Rows about one tangent-disc radius of the saddle apart; the closest pair
  // whose ladder, pulled back onto the skin, still fits at its four corners.
  const double ell = fs.opt.disc_factor * cp.rho;
  for (const Candidate& cand : candidates) {
    const int rows = std::max(1, static_cast<int>(std::lround(cand.dist / ell)));
    const Rails rails = ladder_rails(fs, cand.h0, cand.h1, rows);
    if (!ladder_fits(fs, cand.h0, cand.h1, rails)) {
      if (fs.tracing) fs.tracef("bridge saddle %u: the ladder of %d rows would fold at a corner\n", c, rows);
      continue;
    }
    bridge(fs, cand.h0, cand.h1, c, rails);
    return true;
  }
  return false;
}

Rails ladder_rails(const FrontState& fs, Halfedge ab, Halfedge cd, int rows) {
  const Vertex a = fs.mesh.from_vertex(ab), b = fs.mesh.to_vertex(ab);
  const Vertex cv = fs.mesh.from_vertex(cd), d = fs.mesh.to_vertex(cd);
  const Vec3 pa = fs.mesh.position(a), pb = fs.mesh.position(b), pc = fs.mesh.position(cv), pd = fs.mesh.position(d);
  Rails rails;
  for (int j = 1; j < rows; ++j) {
    const double t = double(j) / rows;
    Index cl = fs.cell[a], cr = fs.cell[b];
    rails.left.push_back(fs.skin.pull_back((1 - t) * pa + t * pd, cl));
    rails.right.push_back(fs.skin.pull_back((1 - t) * pb + t * pc, cr));
    rails.left_cell.push_back(cl);
    rails.right_cell.push_back(cr);
  }
  return rails;
}

namespace {

/// The diagonal of the ladder quad l0 r0 r1 l1 (counter-clockwise): true for
/// l0-r1 (triangles l0 r0 r1, r1 l1 l0), false for r0-l1 (triangles
/// l0 r0 l1, r0 r1 l1) — the split with the larger minimum angle.
bool split_l0_r1(const Vec3& l0, const Vec3& r0, const Vec3& r1, const Vec3& l1) {
  const double d1 = std::min(min_angle(l0, r0, r1), min_angle(r1, l1, l0));
  const double d2 = std::min(min_angle(l0, r0, l1), min_angle(r0, r1, l1));
  return d1 >= d2;
}

}  // namespace

bool ladder_fits(const FrontState& fs, Halfedge ab, Halfedge cd, const Rails& rails) {
  const Vertex a = fs.mesh.from_vertex(ab), b = fs.mesh.to_vertex(ab);
  const Vertex cv = fs.mesh.from_vertex(cd), d = fs.mesh.to_vertex(cd);
  // The rails with their existing end vertices; inner points have no vertex yet.
  std::vector<Vec3> L{fs.mesh.position(a)}, R{fs.mesh.position(b)};
  std::vector<Vertex> LV{a}, RV{b};
  for (std::size_t j = 0; j < rails.left.size(); ++j) {
    L.push_back(rails.left[j]), LV.push_back(Vertex());
    R.push_back(rails.right[j]), RV.push_back(Vertex());
  }
  L.push_back(fs.mesh.position(d)), LV.push_back(d);
  R.push_back(fs.mesh.position(cv)), RV.push_back(cv);
  // Every triangle of the ladder, with the diagonals bridge() will choose,
  // must fit in the hole wedge of each of its corners that is on the front
  // already (a, b, c, d), in that corner's own tangent plane: at corner x of
  // the counter-clockwise triangle (x, y, z) it spans from y to z.
  auto fits_corner = [&](Vertex x, const Vec3& py, Vertex y, const Vec3& pz, Vertex z) {
    return !x.is_valid() || fits_at(fs, x, py, pz, y, z);
  };
  auto tri_fits = [&](const Vec3& p0, Vertex v0, const Vec3& p1, Vertex v1, const Vec3& p2, Vertex v2) {
    return fits_corner(v0, p1, v1, p2, v2) && fits_corner(v1, p2, v2, p0, v0) && fits_corner(v2, p0, v0, p1, v1);
  };
  const std::size_t rows = L.size() - 1;
  for (std::size_t j = 1; j <= rows; ++j) {
    const Vec3 &l0 = L[j - 1], &r0 = R[j - 1], &r1 = R[j], &l1 = L[j];
    const Vertex vl0 = LV[j - 1], vr0 = RV[j - 1], vr1 = RV[j], vl1 = LV[j];
    if (split_l0_r1(l0, r0, r1, l1)) {
      if (!tri_fits(l0, vl0, r0, vr0, r1, vr1) || !tri_fits(r1, vr1, l1, vl1, l0, vl0)) return false;
    } else {
      if (!tri_fits(l0, vl0, r0, vr0, l1, vl1) || !tri_fits(r0, vr0, r1, vr1, l1, vl1)) return false;
    }
  }
  return true;
}

void bridge(FrontState& fs, Halfedge ab, Halfedge cd, Index c, const Rails& rails) {
  const int rows = static_cast<int>(rails.left.size()) + 1;
  const Vertex a = fs.mesh.from_vertex(ab), b = fs.mesh.to_vertex(ab);
  const Vertex cv = fs.mesh.from_vertex(cd), d = fs.mesh.to_vertex(cd);
  // Ladder of `rows` rows across the gap (papers/front/open_questions.md Q6.2 (which pair of edges; filling the gap)):
  // left rail a -> d, right rail b -> c, intermediate points pulled back onto
  // the skin.
  if (fs.tracing)
    fs.tracef("bridge saddle %d: a v%u b v%u c v%u d v%u rows %d\n", int(c), a.idx(), b.idx(), cv.idx(), d.idx(), rows);
  std::vector<Vertex> L{a}, R{b};
  for (int j = 0; j + 1 < rows; ++j) {
    L.push_back(new_vertex(fs, rails.left[j], rails.left_cell[j]));
    R.push_back(new_vertex(fs, rails.right[j], rails.right_cell[j]));
  }
  L.push_back(d);
  R.push_back(cv);
  for (int j = 1; j <= rows; ++j) {
    const Vertex l0 = L[j - 1], r0 = R[j - 1], r1 = R[j], l1 = L[j];
    // Quad l0 r0 r1 l1 (counter-clockwise): split by the diagonal with the
    // better minimum angle.
    if (split_l0_r1(fs.mesh.position(l0), fs.mesh.position(r0), fs.mesh.position(r1), fs.mesh.position(l1))) {
      fs.add_triangle(l0, r0, r1);
      fs.add_triangle(r1, l1, l0);
    } else {
      fs.add_triangle(l0, r0, l1);
      fs.add_triangle(r0, r1, l1);
    }
  }
  if (c != kInvalidIndex) {
    fs.stats.bridge_rows += rows;
    ++fs.stats.bridges;
    fs.resolved[c] = 1;
    release_holds(fs, c, /*requeue=*/false);
  }
  for (std::size_t j = 0; j < L.size(); ++j)
    for (Vertex v : {L[j], R[j]})
      if (fs.mesh.is_boundary(v) && fs.state[v] != VState::Interior) fs.set_state(v, VState::Front);
  // "We update the priority queue Q after a bridge() operation": re-push the
  // free front near the saddle (cheap: lazy deletion), or the quad's corners
  // after a contact.
  if (c != kInvalidIndex) {
    const double reach = fs.opt.bridge_requeue_factor * fs.ms.protect_radius[c];
    const Vec3 centre = fs.ms.critical[c].position;
    // Every vertex not Interior is in front_grid (set_state), so every free
    // front vertex; the grid makes this local (a scan of all vertices made the
    // sweep quadratic in the bridge count).
    std::vector<Index> near;
    const auto [lo, hi] = FrontState::local_scales(fs.ms.critical[c].rho, reach);
    fs.front_grid->for_each_near(centre, reach, lo, hi, fs.mesh.positions().vector(), [&](Index xi, const Vec3& q) {
      if ((q - centre).norm() < reach) near.push_back(xi);
    });
    std::sort(near.begin(), near.end());  // the order of the scan it replaces
    for (Index xi : near) {
      const Vertex v(xi);
      if (!fs.mesh.is_deleted(v) && fs.state[v] == VState::Front && fs.mesh.is_boundary(v) && !fs.mesh.is_isolated(v))
        push(fs, v);
    }
  } else {
    for (Vertex v : {a, b, cv, d})
      if (fs.state[v] == VState::Front && fs.mesh.is_boundary(v)) push(fs, v);
  }
  for (Vertex v : {a, b, cv, d}) {
    if (fs.mesh.is_boundary(v) && fs.state[v] == VState::Front) fs.wing_worklist.push_back(v);
    if (!fs.mesh.is_boundary(v)) fs.set_state(v, VState::Interior);
  }
  for (std::size_t j = 1; j + 1 < L.size(); ++j)
    for (Vertex v : {L[j], R[j]})
      if (!fs.mesh.is_boundary(v)) fs.set_state(v, VState::Interior);
}

}  // namespace skinmesh::front::detail
