// front/seal.cpp: seal() (Cheng & Shi 2004 §4.1, "Sealing holes"): when the
// queue is empty, the surface is covered but for holes around the maxima;
// each is closed "by repeatedly adding triangles whose two edges are
// neighbors in the circle" — ear clipping, in a plane where the hole is a
// simple polygon. Small holes go first to the max-min-angle programme, and
// a hole tangled in every plane is enlarged first (hole_filling.cpp).
// Notes: papers/front/seal.md
#include <sstream>

#include <Eigen/Eigenvalues>

#include "core/errors.h"
#include "front/operations.h"
#include "geometry/check/mesh_checks.h"
#include "geometry/kernel/predicates.h"

namespace skinmesh::front::detail {

using geometry::min_angle;

namespace {

/// Orthogonal projection onto the plane through `centre` with unit normal n.
struct HolePlane {
  Vec3 centre, n, t1, t2;
  std::array<double, 2> operator()(const Vec3& p) const {
    const Vec3 d = p - centre;
    return {d.dot(t1), d.dot(t2)};
  }
};

/// True if the projection of the closed polygon P (counter-clockwise wanted)
/// has positive area and no two non-adjacent edges touch or cross (exact
/// orient2d).
bool simple_ccw(const std::vector<std::array<double, 2>>& P) {
  const std::size_t k = P.size();
  double area2 = 0;
  for (std::size_t i = 0; i < k; ++i) area2 += P[i][0] * P[(i + 1) % k][1] - P[(i + 1) % k][0] * P[i][1];
  if (!(area2 > 0)) return false;
  auto o = [&](std::size_t a, std::size_t b, std::size_t c) {
    return geometry::orient2d(P[a][0], P[a][1], P[b][0], P[b][1], P[c][0], P[c][1]);
  };
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = i + 1; j < k; ++j) {
      const std::size_t i1 = (i + 1) % k, j1 = (j + 1) % k;
      if (j == i1 || i == j1) continue;  // adjacent edges
      const Sign s1 = o(i, i1, j), s2 = o(i, i1, j1), s3 = o(j, j1, i), s4 = o(j, j1, i1);
      if (s1 != s2 && s3 != s4) return false;  // the edges touch or cross
    }
  return true;
}

/// The fallback at the seal (patch_hole), told to the observer.
bool patch(FrontState& fs, const std::vector<Vertex>& around, const Vec3& near) {
  const std::size_t f0 = fs.mesh.faces_size();
  if (!patch_hole(fs, around, near)) return false;
  fs.notify(SweepOperation::Patch, Vertex(), kInvalidIndex, f0);
  return true;
}

}  // namespace

void seal_all(FrontState& fs) {
  const std::size_t max_loops = fs.mesh.n_halfedges() + 1;
  // The vertices are scanned once, from a cursor (a scan from the first vertex
  // per hole was quadratic: 16 % of the time on 30,000 atoms); an enlargement
  // can re-open a hole behind the cursor, so the end of the scan is confirmed
  // by one more pass from the start.
  std::size_t cursor = 0;
  bool rescanned = false;
  // In a region (front/region.h), the loops of the ghost strips and the
  // parked rims are the region's boundary: they stay open. Their vertices are marked
  // once, so that the scan skips them without walking the loop again.
  std::vector<char> kept_open;
  for (std::size_t iter = 0;; ++iter) {
    if (iter > max_loops) throw TopologyError("seal: the holes do not close");
    Halfedge start;
    const std::size_t n = fs.mesh.vertices_size();
    for (; cursor < n; ++cursor) {
      const Vertex v(static_cast<Index>(cursor));
      if (fs.mesh.is_deleted(v) || fs.mesh.is_isolated(v) || !fs.mesh.is_boundary(v)) continue;
      if (cursor < kept_open.size() && kept_open[cursor]) continue;
      if (fs.region.on_boundary(fs.mesh, fs.mesh.halfedge(v))) {
        kept_open.resize(n, 0);
        for (Halfedge g : fs.mesh.boundary_loop(fs.mesh.halfedge(v))) kept_open[fs.mesh.to_vertex(g).idx()] = 1;
        continue;
      }
      start = fs.mesh.halfedge(v);
      break;
    }
    if (!start.is_valid()) {
      if (rescanned) return;
      rescanned = true;
      cursor = 0;
      continue;
    }
    rescanned = false;
    const std::size_t f0 = fs.mesh.faces_size(), seals = fs.stats.seals;
    seal_loop(fs, start, fs.opt.max_hole_enlargements);
    // A hole the fallback re-meshed was told to the observer as a patch.
    if (fs.stats.seals > seals) fs.notify(SweepOperation::Seal, Vertex(), kInvalidIndex, f0);
  }
}

void close_small_hole(FrontState& fs, Vertex v) { seal_loop(fs, fs.mesh.halfedge(v), 0, /*in_sweep=*/true); }

void seal_loop(FrontState& fs, Halfedge start, int enlargements_left, bool in_sweep) {
  std::vector<Halfedge> loop = fs.mesh.boundary_loop(start);
  std::vector<Vertex> poly;
  for (Halfedge h : loop) poly.push_back(fs.mesh.to_vertex(h));
  if (!in_sweep && enlargements_left == fs.opt.max_hole_enlargements) {
    const std::size_t hole = fs.seal_holes++;
    if (fs.opt.force_patch_every > 0 && hole % fs.opt.force_patch_every == 0) {
      Vec3 centre = Vec3::Zero();
      for (Vertex v : poly) centre += fs.mesh.position(v);
      if (patch(fs, poly, centre / double(poly.size()))) return;
      if (fs.tracing) fs.tracef("patch: forced patch failed at hole %zu of %zu vertices\n", hole, poly.size());
    }
  }
  if (poly.size() <= static_cast<std::size_t>(fs.opt.dp_max_hole_vertices) && fill_hole_dp(fs, poly)) return;
  // Plane of projection: the first of (the average vertex normal, the normal
  // of the best-fit plane, each vertex normal) in which the hole is a simple,
  // counter-clockwise polygon. A hole with a narrow waist can cross itself in
  // the average plane.
  HolePlane plane;
  plane.centre = Vec3::Zero();
  Vec3 nbar = Vec3::Zero();
  for (Vertex v : poly) plane.centre += fs.mesh.position(v), nbar += fs.normal[v];
  plane.centre /= double(poly.size());
  if (nbar.norm() == 0) {
    if (!in_sweep && patch(fs, poly, fs.mesh.position(poly.front()))) return;
    throw TopologyError("seal: hole with a degenerate average normal");
  }
  nbar.normalize();
  std::vector<Vec3> planes{nbar};
  {
    Mat3 cov = Mat3::Zero();
    for (Vertex v : poly) {
      const Vec3 d = fs.mesh.position(v) - plane.centre;
      cov += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Mat3> es(cov);
    Vec3 pn = es.eigenvectors().col(0);
    planes.push_back(pn.dot(nbar) < 0 ? Vec3(-pn) : pn);
    for (Vertex v : poly) planes.push_back(fs.normal[v]);
  }
  auto proj = [&](Vertex v) { return plane(fs.mesh.position(v)); };
  bool found = false;
  std::vector<std::array<double, 2>> P(poly.size());
  for (const Vec3& cand : planes) {
    if (cand.dot(nbar) <= fs.opt.seal_plane_min_cosine) continue;
    plane.n = cand;
    plane.t1 = cand.unitOrthogonal(), plane.t2 = cand.cross(plane.t1);
    for (std::size_t i = 0; i < poly.size(); ++i) P[i] = proj(poly[i]);
    if ((found = simple_ccw(P))) break;
  }
  if (!found) {
    std::ostringstream os;
    os << "seal: the hole of " << poly.size() << " vertices near (" << plane.centre.transpose()
       << ") is not a simple polygon in any plane tried";
    if (in_sweep) {
      if (fs.tracing) fs.tracef("%s: re-opening it\n", os.str().c_str());
      if (reopen_hole(fs, poly)) return;
      if (fs.opt.patch_fallback) {
        leave_hole_for_seal(fs, poly);
        return;
      }
      os << "; re-opening it pinched the front";
    } else if (enlargements_left > 0) {
      if (fs.tracing) fs.tracef("%s: enlarging it\n", os.str().c_str());
      std::vector<Vertex> rim;
      const Halfedge h = enlarge_hole(fs, poly, &rim);
      ++fs.stats.enlarged_holes;
      if (h.is_valid()) {
        seal_loop(fs, h, enlargements_left - 1);
        return;
      }
      if (patch(fs, rim, plane.centre)) return;
      os << "; enlarging it pinched the front";
    } else if (patch(fs, poly, plane.centre)) {
      return;
    }
    throw TopologyError(os.str());
  }
  if (fs.tracing) {
    std::ostringstream os;
    os << "seal loop of " << poly.size() << ":";
    for (Vertex x : poly) {
      const auto px = proj(x);
      os << " v" << x.idx() << "[" << px[0] << "," << px[1] << "|hole " << corner(fs, x).angle / kDegree << "]";
    }
    fs.opt.trace(os.str());
  }
  // Ear clipping: the hole is on the left of u -> v -> w; an ear at v is a
  // left turn with no other polygon vertex inside; take the best 3D angle.
  bool strict = true;  // ears must fit the hole wedges; relaxed when no ear does
  while (poly.size() > 3) {
    const std::size_t k = poly.size();
    double best = -1;
    std::size_t bi = k;
    for (std::size_t i = 0; i < k; ++i) {
      const Vertex u = poly[(i + k - 1) % k], v = poly[i], w = poly[(i + 1) % k];
      const auto pu = proj(u), pv = proj(v), pw = proj(w);
      if (geometry::orient2d(pu[0], pu[1], pv[0], pv[1], pw[0], pw[1]) != Sign::Positive) continue;
      if (fs.mesh.find_halfedge(w, u).is_valid()) continue;
      bool empty = true;
      for (std::size_t j = 0; j < k && empty; ++j) {
        const Vertex x = poly[j];
        if (x == u || x == v || x == w) continue;
        const auto px = proj(x);
        if (geometry::orient2d(pu[0], pu[1], pv[0], pv[1], px[0], px[1]) != Sign::Negative &&
            geometry::orient2d(pv[0], pv[1], pw[0], pw[1], px[0], px[1]) != Sign::Negative &&
            geometry::orient2d(pw[0], pw[1], pu[0], pu[1], px[0], px[1]) != Sign::Negative)
          empty = false;
      }
      if (!empty) continue;
      // The ear must also face outwards at its three corners (a sliver across
      // a narrow waist can turn over between the projection plane and T_x).
      const Vec3 nt = (fs.mesh.position(w) - fs.mesh.position(v)).cross(fs.mesh.position(u) - fs.mesh.position(v));
      if (nt.dot(fs.normal[u]) <= 0 || nt.dot(fs.normal[v]) <= 0 || nt.dot(fs.normal[w]) <= 0) continue;
      if (strict && (!fits_at(fs, u, v, w) || !fits_at(fs, v, w, u) || !fits_at(fs, w, u, v))) continue;
      const double q = min_angle(fs.mesh.position(u), fs.mesh.position(v), fs.mesh.position(w));
      if (q > best) best = q, bi = i;
    }
    if (bi == k && strict) {
      strict = false;
      continue;
    }
    if (bi == k) {
      if (fs.tracing) {
        std::ostringstream os;
        os << "seal: no ear; the hole's vertices in its projection plane:";
        for (Vertex x : poly) {
          const auto px = proj(x);
          os << " [" << px[0] << "," << px[1] << "]";
        }
        fs.opt.trace(os.str());
      }
      if (in_sweep && fs.opt.patch_fallback) {
        leave_hole_for_seal(fs, poly);
        return;
      }
      if (!in_sweep && patch(fs, poly, plane.centre)) return;
      std::ostringstream os;
      os << "seal: no ear in a hole of " << k << " vertices near (" << plane.centre.transpose() << ")";
      throw TopologyError(os.str());
    }
    const Vertex u = poly[(bi + k - 1) % k], v = poly[bi], w = poly[(bi + 1) % k];
    if (fs.tracing) fs.tracef("  ear v%u v%u v%u\n", u.idx(), v.idx(), w.idx());
    fs.add_triangle(v, w, u);
    fs.set_state(v, VState::Interior);
    poly.erase(poly.begin() + static_cast<std::ptrdiff_t>(bi));
  }
  fs.add_triangle(poly[0], poly[1], poly[2]);
  for (Vertex v : poly) fs.set_state(v, VState::Interior);
  ++fs.stats.seals;
}

}  // namespace skinmesh::front::detail
