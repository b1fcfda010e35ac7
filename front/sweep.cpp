// front/sweep.cpp: Algorithm 1 of Cheng & Shi 2004 §4.1 ("CreepTriangles"):
// the departure queue, the holds in protecting spheres, the release of saddles
// never bridged, and the order of the stages (initial front, creeping
// triangles, sealing holes). The operations live in their own files
// (front/operations.h declares them in the paper's order).
// Notes: papers/front/sweep.md
#include <algorithm>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "front/operations.h"
#include "core/errors.h"
#include "geometry/io/mesh_io.h"

namespace skinmesh::front {
namespace detail {

using morse::CriticalKind;

// Vertices and the Queue

Vertex new_vertex(FrontState& fs, const Vec3& p, Index cell) {
  if (fs.mesh.vertices_size() >= fs.vertex_budget) {
    // Near a thin neck or a narrow gap rho falls to the neck's scale and the
    // vertex density grows like 1/rho²; since rho is 1-Lipschitz, each halving
    // of the scale adds about as many vertices as the atom scale needs: allow
    // 2 log2(rho_max / rho_min) more times the base budget, rho_min the
    // smallest rho the front has met.
    const double octaves = std::log2(std::max(1.0, fs.rho_max / fs.rho_min_seen));
    fs.vertex_budget = static_cast<std::size_t>(fs.base_vertex_budget * (1 + 2 * octaves));
  }
  if (fs.mesh.vertices_size() >= fs.vertex_budget) {
    std::ostringstream os;
    os << "the front created more than " << fs.vertex_budget
       << " vertices without closing: it is running away (a bug; please report the input)";
    throw TopologyError(os.str());
  }
  const skin::SkinSample s = fs.skin.sample(p, cell);
  if (s.rho > 0) fs.rho_min_seen = std::min(fs.rho_min_seen, s.rho);
  const Vertex v = fs.mesh.add_vertex(p);
  fs.vertex_grid->insert(v.idx(), p);
  fs.normal[v] = s.gradient.normalized();
  fs.rho[v] = s.rho;
  fs.cell[v] = s.cell;
  fs.set_state(v, VState::Front);
  return v;
}

void push(FrontState& fs, Vertex v) {
  ++fs.stamp[v];
  fs.queue.push({fs.height(v), v.idx(), fs.stamp[v]});
}

void defer(FrontState& fs, Vertex v, double r) {
  ++fs.deferrals[v];
  ++fs.stamp[v];
  fs.queue.push({fs.height(v) + fs.opt.defer_step * r * fs.deferrals[v], v.idx(), fs.stamp[v]});
  ++fs.stats.deferred;
}

Vec3 project_tangent(FrontState& fs, Vertex v, const Vec3& dir, double r, Index* cell_out) {
  // Normal-line projection of q = v + r dir (papers/skin/skin_math.md §7.2):
  // the bracket [-delta, delta] comes from the sandwiching balls of radius rho(v).
  const double rho = fs.rho[v];
  const Vec3 n = fs.normal[v];
  const Vec3 q = fs.mesh.position(v) + r * dir;
  double delta = rho - std::sqrt(std::max(rho * rho - r * r, 0.0));
  Vec3 out;
  Index cell = fs.cell[v];
  for (int attempt = 0; attempt < 4; ++attempt, delta *= 2) {
    if (fs.skin.project_along_line(q, n, delta * (1 + 1e-9) + 1e-12 * fs.skin.length_scale(), out, cell)) {
      if (cell_out) *cell_out = cell;
      return out;
    }
  }
  // Fall back on the gradient pull-back (papers/skin/skin_math.md §7.3).
  cell = fs.cell[v];
  out = fs.skin.pull_back(q, cell);
  if (cell_out) *cell_out = cell;
  return out;
}

// Holds in Protecting Spheres (Algorithm 1, lines 3–10)

Index hold_region(const FrontState& fs, Vertex v) {
  // v is held if its tangent disc meets the protecting sphere of a live
  // saddle or maximum not yet resolved, so that no fan enters the sphere
  // (Cheng & Shi §4.2: "each step of the front advancing must not cross to the
  // other side of the spheres"); the nearest such critical point holds it.
  const Vec3& p = fs.mesh.position(v);
  const double r = fs.disc_radius(v);
  Index best = kInvalidIndex;
  double best_d = std::numeric_limits<double>::infinity();
  fs.hold_grid->for_each_near(p, fs.max_hold_radius + r, [&](Index c, const Vec3& q) {
    if (fs.resolved[c]) return;
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

bool release_saddles(FrontState& fs) {
  // Saddles never bridged (the front reached them from one side only, or the
  // two sides met elsewhere by a contact): release their holds and go on
  // (papers/front/open_questions.md Q6.4); the final topology check decides.
  bool any = false;
  for (std::size_t c = 0; c < fs.ms.critical.size(); ++c) {
    if (!fs.ms.live[c] || fs.ms.critical[c].kind != CriticalKind::Saddle || fs.resolved[c]) continue;
    fs.resolved[c] = 1;
    ++fs.stats.released;
    if (fs.tracing) fs.tracef("release saddle %zu unbridged\n", c);
    if (release_holds(fs, static_cast<Index>(c), /*requeue=*/true)) any = true;
  }
  return any;
}

// Algorithm 1

void create_initial_front(FrontState& fs) {
  // "Initial front": a bowl at every live minimum (Figure 5), lowest first.
  // Not in the paper: a minimum whose bowl would overlap a bowl already made
  // (two minima closer than the sum of their bowl radii, on a flat patch the
  // arc contraction left alone) gets none: the two bowls would overlap from
  // the start, and no front operation can undo that. The neighbouring bowl's
  // front sweeps its basin, and the saddles the missing bowl would have
  // touched are resolved with it (papers/front/creation.md, "Overlapping bowls").
  std::vector<Index> minima;
  for (std::size_t c = 0; c < fs.ms.critical.size(); ++c)
    if (fs.ms.live[c] && fs.ms.critical[c].kind == CriticalKind::Minimum) minima.push_back(static_cast<Index>(c));
  std::stable_sort(minima.begin(), minima.end(), [&](Index a, Index b) {
    return fs.ms.critical[a].position.dot(fs.e) < fs.ms.critical[b].position.dot(fs.e);
  });
  // rho never exceeds rho_max, the largest sphere radius sqrt(w/2) (as for vertex_grid).
  for (Index c : minima) {
    const morse::CriticalPoint& cp = fs.ms.critical[c];
    const double r = fs.opt.disc_factor * cp.rho;
    bool overlaps = false;
    fs.vertex_grid->for_each_near(cp.position, r + fs.opt.disc_factor * fs.rho_max, fs.mesh.positions().vector(),
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
    fs.hold_grid->for_each_near(cp.position, r + fs.max_hold_radius, [&](Index s, const Vec3& q) {
      if (fs.ms.critical[s].kind == CriticalKind::Saddle && (q - cp.position).norm() < r + fs.ms.protect_radius[s])
        fs.resolved[s] = 1;
    });
  }
}

void report_progress(FrontState& fs, double h) {
  if (!fs.opt.progress) return;
  const double span = fs.h_max - fs.h_min;
  const double f = span > 0 ? std::clamp((h - fs.h_min) / span, 0.0, 1.0) : 0.0;
  if (f < fs.next_progress) return;
  fs.next_progress = f + 0.01;
  fs.opt.progress("sweep", f);
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

SweepResult run_sweep(FrontState& fs) {
  create_initial_front(fs);
  // Creeping triangles: Algorithm 1 until the queue is empty, then release the
  // saddles never bridged and go on while that frees any vertex.
  do {
    while (departure_step(fs)) {
    }
  } while (release_saddles(fs));
  if (fs.opt.progress) fs.opt.progress("sweep", 1.0);
  // Sealing holes.
  if (!fs.opt.dump_path.empty()) geometry::write_mesh(fs.opt.dump_path, fs.mesh.to_indexed_mesh());
  seal_all(fs);
  // The result keeps the properties the refinement needs.
  fs.vertex_grid.reset();
  fs.front_grid.reset();
  fs.mesh.remove_vertex_property(fs.state);
  fs.mesh.remove_vertex_property(fs.held_by);
  fs.mesh.remove_vertex_property(fs.stamp);
  fs.mesh.remove_vertex_property(fs.deferrals);
  fs.mesh.remove_vertex_property(fs.reopenings);
  SweepResult res;
  res.mesh = std::move(fs.mesh);
  res.stats = fs.stats;
  return res;
}

}  // namespace detail

const char* operation_name(SweepOperation op) {
  switch (op) {
    case SweepOperation::Creation: return "creation";
    case SweepOperation::Creep: return "creep";
    case SweepOperation::Wings: return "wings";
    case SweepOperation::Hold: return "hold";
    case SweepOperation::Bridge: return "bridge";
    case SweepOperation::SmallHole: return "small hole";
    case SweepOperation::Seal: return "seal";
  }
  return "?";
}

SweepResult sweep_mesh(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const SweepOptions& opt) {
  detail::FrontState fs(skin, ms, opt);
  return detail::run_sweep(fs);
}

}  // namespace skinmesh::front
