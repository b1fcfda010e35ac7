// front/sweep.cpp: the driver of Algorithm 1 of Cheng & Shi 2004 §4.1
// ("CreepTriangles"): the initial front, the loop over departure vertices
// (lines 2–14: hold, small hole or creep, then the wings), the release of
// saddles never bridged, the seal. The operations live in their own files
// (front/operations.h declares them in the paper's order); the state's
// bookkeeping (vertices, queue) in front_state.cpp, the holds in holds.cpp.
// Notes: papers/front/sweep.md
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/errors.h"
#include "front/operations.h"
#include "geometry/io/mesh_io.h"

namespace skinmesh::front {
namespace detail {

using morse::CriticalKind;

void create_initial_front(FrontState& fs) {
  // "Initial front": a bowl at every live minimum (Figure 5), lowest first.
  // Not in the paper: a minimum whose bowl would overlap a bowl already made
  // (two minima closer than the sum of their bowl radii, on a flat patch the
  // arc contraction left alone) gets none: the two bowls would overlap from
  // the start, and no front operation can undo that. The neighbouring bowl's
  // front sweeps its basin, and the saddles the missing bowl would have
  // touched are resolved with it (papers/front/creation.md, "Overlapping bowls").
  std::vector<Index> minima;
  // In a region (front/region.h), only the minima it owns: the others are
  // in the regions below and above.
  for (std::size_t c = 0; c < fs.ms.critical.size(); ++c) {
    if (!fs.ms.live[c] || fs.ms.critical[c].kind != CriticalKind::Minimum) continue;
    if (fs.region.owns(static_cast<Index>(c), fs.ms.critical[c].height)) minima.push_back(static_cast<Index>(c));
  }
  std::stable_sort(minima.begin(), minima.end(), [&](Index a, Index b) {
    return fs.ms.critical[a].position.dot(fs.e) < fs.ms.critical[b].position.dot(fs.e);
  });
  for (Index c : minima) {
    const morse::CriticalPoint& cp = fs.ms.critical[c];
    const double r = fs.opt.disc_factor * cp.rho;
    bool overlaps = false;
    // A vertex x overlaps if |x - c| < r + c_r rho(x); rho being 1-Lipschitz,
    // rho(x) <= rho(c) + |x - c|, so such an x lies within
    // (r + c_r rho(c)) / (1 - c_r) = 2 r / (1 - c_r) of c.
    const double reach = 2 * r / (1 - fs.opt.disc_factor) * (1 + 1e-9);
    const auto [lo, hi] = FrontState::local_scales(cp.rho, reach);
    fs.vertex_grid->for_each_near(cp.position, reach, lo, hi, fs.mesh.positions().vector(),
                                  [&](Index xi, const Vec3& q) {
                                    if ((q - cp.position).norm() < r + fs.disc_radius(Vertex(xi))) overlaps = true;
                                  });
    if (!overlaps) {
      const std::size_t f0 = fs.mesh.faces_size();
      creation(fs, c);
      fs.notify(SweepOperation::Creation, Vertex(), c, f0);
      continue;
    }
    ++fs.stats.merged_minima;
    if (fs.tracing) fs.tracef("creation: no bowl at minimum %u, it would overlap a bowl already made\n", c);
    fs.for_each_hold_near(cp.position, cp.rho, r, [&](Index s, const Vec3& q) {
      if (fs.ms.critical[s].kind == CriticalKind::Saddle && (q - cp.position).norm() < r + fs.ms.protect_radius[s])
        fs.resolved[s] = 1;
    });
  }
}

bool departure_step(FrontState& fs) {
  // Line 1: while Q is not empty.
  while (!fs.queue.empty()) {
    // Line 2: t = ExtractMin(Q), the lowest front vertex (lazy deletion: an
    // entry whose stamp is old, or a vertex no longer free on the front, is
    // skipped).
    const QueueEntry top = fs.queue.top();
    fs.queue.pop();
    const Vertex v(top.v);
    if (top.stamp != fs.stamp[v] || fs.state[v] != VState::Front || fs.mesh.is_deleted(v) || fs.mesh.is_isolated(v) ||
        !fs.mesh.is_boundary(v))
      continue;
    if (fs.opt.max_steps >= 0 && fs.steps++ >= fs.opt.max_steps) {
      if (!fs.opt.dump_path.empty()) geometry::write_mesh(fs.opt.dump_path, fs.mesh.to_indexed_mesh());
      throw TopologyError("stopped after " + std::to_string(fs.opt.max_steps) + " departures (max_steps)");
    }
    report_progress(fs, top.h);
    // Not in the paper: the progress guarantee (papers/front/sweep.md,
    // "Progress"), and the upper boundary of the region being swept.
    if (departure_spent(fs, v) || parks(fs, v)) return true;
    // Lines 3–10: in the protecting sphere of a saddle (bridged when ready)
    // or of a maximum: the vertex is held.
    if (const Index c = hold_region(fs, v); c != kInvalidIndex) {
      hold(fs, v, c);
      return true;
    }
    const std::size_t f0 = fs.mesh.faces_size();
    if (small_hole(fs, v)) {
      // Not in the paper: the fronts around v have met in a small hole; close
      // it now, as seal() would, instead of creeping new vertices into it
      // (papers/front/hole_filling.md).
      close_small_hole(fs, v);
      paranoid_check(fs, f0, "closing a small hole");
      fs.notify(SweepOperation::SmallHole, v, kInvalidIndex, f0);
      return true;
    }
    // Lines 11–12: creep().
    creep(fs, v);
    paranoid_check(fs, f0, "creep");
    fs.notify(SweepOperation::Creep, v, kInvalidIndex, f0);
    // Line 14, "refine the newly added triangles": here the wings of the
    // front angles below 90° (Figure 7); the local refinement of §4.3 runs
    // after the seal (papers/front/sweep.md, "Deviations").
    const std::size_t f1 = fs.mesh.faces_size();
    drain_wings(fs);
    paranoid_check(fs, f1, "wings after a creep");
    if (fs.mesh.faces_size() > f1) fs.notify(SweepOperation::Wings, v, kInvalidIndex, f1);
    return true;
  }
  return false;
}

bool parks(FrontState& fs, Vertex v) {
  // A vertex within about park_factor · r of the upper cut, measured along
  // the skin, stops there: the band above it is the strip's (decompose/band.h).
  // The skin rises by sin(theta) per unit length along its slope (theta the
  // angle between n and e), so the height gap is scaled by it: on a gentle
  // slope a height bound alone would leave a band many edges wide, which one
  // strip of triangles cannot fill. Near a ball the upper cut passes around,
  // the cut is no level curve: the vertex parks within park_factor · r of
  // the cut's polyline. For the whole skin the cut is at +infinity.
  const Region& region = fs.region.spec;
  // Where the region must first resolve a critical point it owns under the
  // cut, the hold comes first (Region::holds_before_parking).
  if (region.holds_before_parking && hold_region(fs, v) != kInvalidIndex) return false;
  bool stop = false;
  if (const int near = near_upper_detour(fs, v); near != 0) {
    stop = near > 0;
  } else if (const double gap = region.upper - fs.height(v); gap < region.park_factor * fs.disc_radius(v)) {
    const double cos_theta = fs.e.dot(fs.normal[v]);
    const double sin_theta = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
    stop = gap < region.park_factor * fs.disc_radius(v) * sin_theta;
  }
  if (stop) park(fs, v);
  return stop;
}

int near_upper_detour(const FrontState& fs, Vertex v) {
  if (fs.region.upper_balls.empty()) return 0;
  const Vec3& p = fs.mesh.position(v);
  const double park_factor = fs.region.spec.park_factor;
  const double r = fs.disc_radius(v), reach = 2 * park_factor * r;
  bool near = false;
  fs.region.ball_grid.for_each_near(p, reach, [&](Index i) {
    const morse::DetourBall& b = fs.region.upper_balls[i];
    if ((p - b.center).norm() < b.radius + reach) near = true;
  });
  if (!near) return 0;
  // The distance to the cut's polyline, over the edges near v: an edge
  // within park_factor · r of v has its midpoint within park_factor · r plus
  // its half length (the grid's reach), so the test is the one over every
  // edge.
  double best = std::numeric_limits<double>::infinity();
  fs.region.edge_grid.for_each_near(p, park_factor * r, [&](Index i) {
    const auto [k, j] = fs.region.upper_edges[i];
    const std::vector<Vec3>& points = fs.region.spec.upper_curves[k].points;
    const Vec3& a = points[j];
    const Vec3& b = points[(j + 1) % points.size()];
    const Vec3 ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
    best = std::min(best, (p - (a + t * ab)).norm());
  });
  return best < park_factor * r ? 1 : -1;
}

void park(FrontState& fs, Vertex v) {
  fs.set_state(v, VState::Held);
  fs.held_by[v] = kInvalidIndex;
  fs.region.mark(v, RegionRole::Parked, fs.mesh.vertices_size());
  ++fs.stats.parked;
  if (fs.tracing) fs.tracef("park v%u at height %.4f\n", v.idx(), fs.height(v));
}

bool departure_spent(FrontState& fs, Vertex v) {
  ++fs.stats.departures;
  if (fs.departures[v] < fs.opt.max_departures) {
    fs.stats.most_departures = std::max<std::size_t>(fs.stats.most_departures, ++fs.departures[v]);
    return false;
  }
  ++fs.stats.spent_vertices;
  if (fs.tracing) fs.tracef("v%u has departed %d times: left for the seal\n", v.idx(), fs.opt.max_departures);
  leave_hole_for_seal(fs, {v});
  return true;
}

void sweep_and_seal(FrontState& fs) {
  // Creeping triangles: Algorithm 1 until the queue is empty, then release the
  // saddles never bridged and go on while that frees any vertex.
  do {
    while (departure_step(fs)) {
    }
  } while (release_saddles(fs));
  fs.stats.swept_faces = fs.mesh.n_faces();
  if (fs.run.progress) fs.run.progress("sweep", 1.0);
  // Sealing holes.
  if (!fs.opt.dump_path.empty()) geometry::write_mesh(fs.opt.dump_path, fs.mesh.to_indexed_mesh());
  seal_all(fs);
}

void drop_sweep_properties(FrontState& fs) {
  // The result keeps the properties the refinement needs.
  fs.vertex_grid.reset();
  fs.front_grid.reset();
  fs.mesh.remove_vertex_property(fs.state);
  fs.mesh.remove_vertex_property(fs.held_by);
  fs.mesh.remove_vertex_property(fs.stamp);
  fs.mesh.remove_vertex_property(fs.deferrals);
  fs.mesh.remove_vertex_property(fs.reopenings);
  fs.mesh.remove_vertex_property(fs.departures);
  fs.mesh.remove_vertex_property(fs.normal);
  fs.mesh.remove_vertex_property(fs.rho);
}

SweepResult run_sweep(FrontState& fs) {
  create_initial_front(fs);
  sweep_and_seal(fs);
  drop_sweep_properties(fs);
  SweepResult res;
  res.mesh = std::move(fs.mesh);
  res.stats = fs.stats;
  return res;
}

}  // namespace detail

const char* operation_name(SweepOperation op) {
  switch (op) {
    case SweepOperation::Creation:
      return "creation";
    case SweepOperation::Creep:
      return "creep";
    case SweepOperation::Wings:
      return "wings";
    case SweepOperation::Hold:
      return "hold";
    case SweepOperation::Bridge:
      return "bridge";
    case SweepOperation::SmallHole:
      return "small hole";
    case SweepOperation::Seal:
      return "seal";
    case SweepOperation::Patch:
      return "patch";
  }
  return "?";
}

std::size_t departure_bound(const SweepStats& s, int max_departures) {
  // Every vertex departs at most B + 1 times until it is spent; a spent
  // vertex departs once more each time it is put back on the front: by a
  // re-opening (at most 3 rim vertices per deleted face, D <= F of them) or
  // as a rail vertex of a ladder (2 (k + 1) <= 2 · 2k per ladder of k rows
  // and 2k faces, at most 2 per face ever made). A bowl brings 7 vertices,
  // every other vertex comes with a face, and the faces ever made are the F
  // standing plus the D <= F that re-openings deleted.
  const std::size_t b = static_cast<std::size_t>(std::max(max_departures, 0)) + 1;
  return b * (7 * s.creations + 2 * s.swept_faces) + 7 * s.swept_faces;
}

SweepResult sweep_mesh(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const SweepOptions& opt,
                       const skin::RunContext& run) {
  detail::FrontState fs(skin, ms, opt, run);
  return detail::run_sweep(fs);
}

}  // namespace skinmesh::front
