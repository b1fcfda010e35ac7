// front/sweep.cpp: Algorithm 1 of Cheng & Shi 2004 §4.1 ("CreepTriangles"):
// the departure queue, the holds in protecting spheres, the release of saddles
// never bridged, and the order of the stages (initial front, creeping
// triangles, sealing holes). The operations live in their own files
// (front/sweep_internal.h lists them).
// Notes: papers/front/sweep.md
#include <algorithm>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "front/sweep_internal.h"
#include "core/errors.h"
#include "geometry/io/mesh_io.h"

namespace skinmesh::front {
namespace detail {

using morse::CriticalKind;

Sweep::Sweep(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const SweepOptions& opt)
    : skin_(skin), ms_(ms), opt_(opt), e_(ms.height_direction) {
  if (!(opt.disc_factor > opt.size.disc_factor_lower() && opt.disc_factor <= opt.size.disc_factor_upper())) {
    std::ostringstream os;
    os << "sweep: disc_factor " << opt.disc_factor << " is outside the tangent-disc window ("
       << opt.size.disc_factor_lower() << ", " << opt.size.disc_factor_upper() << "] of C = " << opt.size.C
       << ", Q = " << opt.size.Q << " (Cheng & Shi §4.2)";
    throw std::invalid_argument(os.str());
  }
  normal_ = mesh_.add_vertex_property<Vec3>("v:normal", Vec3::Zero());
  rho_ = mesh_.add_vertex_property<double>("v:rho", 0.0);
  cell_ = mesh_.add_vertex_property<Index>("v:cell", kInvalidIndex);
  state_ = mesh_.add_vertex_property<VState>("v:state", VState::Interior);
  held_by_ = mesh_.add_vertex_property<Index>("v:held_by", kInvalidIndex);
  stamp_ = mesh_.add_vertex_property<std::uint32_t>("v:stamp", 0);
  deferrals_ = mesh_.add_vertex_property<std::uint8_t>("v:deferrals", 0);
  reopenings_ = mesh_.add_vertex_property<std::uint8_t>("v:reopenings", 0);
  const std::size_t nc = ms.critical.size();
  resolved_.assign(nc, 0);
  held_.resize(nc);
  double rmax = 0;
  for (std::size_t i = 0; i < nc; ++i) rmax = std::max(rmax, ms.protect_radius[i]);
  // Cells of four protecting radii: the hold query (rmax + r) then probes 1-2
  // cells per axis; the critical points are sparse, so a probe of an empty
  // cell costs more than reading a few more points (crambin probe 0:
  // hold_region 70 -> 37 million instructions, against cells of 2 rmax).
  hold_grid_ = std::make_unique<geometry::PointGrid>(std::max(4 * rmax, 1e-6));
  for (std::size_t i = 0; i < nc; ++i)
    if (ms.live[i] && ms.critical[i].kind != CriticalKind::Minimum)
      hold_grid_->insert(static_cast<Index>(i), ms.critical[i].position);
  max_hold_radius_ = rmax;
  double rho_max = 0;
  for (const auto& wp : skin.points()) rho_max = std::max(rho_max, std::sqrt(std::max(wp.w, 0.0) / 2));
  // The front grid's cells are four disc radii at the largest scale: the
  // contact query (1.5 r) then probes 1-2 cells per axis, and the front is a
  // curve, so most probed cells would be empty at a finer size (maltoporin:
  // sweep 3,000 -> 2,940 million instructions against two disc radii). The
  // vertex grid's are one disc radius: the fan-collision query
  // (0.5 r) reads a quarter of the points per cell (crambin probe 0: sweep
  // 1,650 -> 1,578 million instructions; maltoporin, whose vertices are mostly
  // at the largest scale: 3,294 -> 3,310 million).
  vertex_grid_ = std::make_unique<geometry::ErasablePointGrid>(std::max(opt.disc_factor * rho_max, 1e-6),
                                                               /*erasable=*/false);
  front_grid_ = std::make_unique<geometry::ErasablePointGrid>(std::max(4 * opt.disc_factor * rho_max, 1e-6));
  // A generous bound on the vertex count: 8 times what a separate sphere per
  // atom would need (4 pi / (c_r² sqrt(3)/2) vertices per sphere), times a
  // factor for the scales below the atoms' that the front has met (new_vertex).
  const double per_atom = 4 * kPi / (opt.disc_factor * opt.disc_factor * 0.866);
  base_vertex_budget_ = 1e5 + 8 * per_atom * static_cast<double>(skin.points().size());
  rho_max_ = rho_max;
  vertex_budget_ = static_cast<std::size_t>(base_vertex_budget_);
  // Height range for progress reports.
  h_min_ = std::numeric_limits<double>::infinity();
  h_max_ = -h_min_;
  for (const auto& cp : ms.critical) {
    h_min_ = std::min(h_min_, e_.dot(cp.position));
    h_max_ = std::max(h_max_, e_.dot(cp.position));
  }
}

// Vertices and the Queue

Vertex Sweep::new_vertex(const Vec3& p, Index cell) {
  if (mesh_.vertices_size() >= vertex_budget_) {
    // Near a thin neck or a narrow gap rho falls to the neck's scale and the
    // vertex density grows like 1/rho²; since rho is 1-Lipschitz, each halving
    // of the scale adds about as many vertices as the atom scale needs: allow
    // 2 log2(rho_max / rho_min) more times the base budget, rho_min the
    // smallest rho the front has met.
    const double octaves = std::log2(std::max(1.0, rho_max_ / rho_min_seen_));
    vertex_budget_ = static_cast<std::size_t>(base_vertex_budget_ * (1 + 2 * octaves));
  }
  if (mesh_.vertices_size() >= vertex_budget_) {
    std::ostringstream os;
    os << "the front created more than " << vertex_budget_
       << " vertices without closing: it is running away (a bug; please report the input)";
    throw TopologyError(os.str());
  }
  const skin::SkinSample s = skin_.sample(p, cell);
  if (s.rho > 0) rho_min_seen_ = std::min(rho_min_seen_, s.rho);
  const Vertex v = mesh_.add_vertex(p);
  vertex_grid_->insert(v.idx(), p);
  normal_[v] = s.gradient.normalized();
  rho_[v] = s.rho;
  cell_[v] = s.cell;
  set_state(v, VState::Front);
  return v;
}

void Sweep::push(Vertex v) {
  ++stamp_[v];
  queue_.push({height(v), v.idx(), stamp_[v]});
}

void Sweep::defer(Vertex v, double r) {
  ++deferrals_[v];
  ++stamp_[v];
  queue_.push({height(v) + opt_.defer_step * r * deferrals_[v], v.idx(), stamp_[v]});
  ++stats_.deferred;
}

Vec3 Sweep::project_tangent(Vertex v, const Vec3& dir, double r, Index* cell_out) {
  // Normal-line projection of q = v + r dir (papers/skin/skin_math.md §7.2):
  // the bracket [-delta, delta] comes from the sandwiching balls of radius rho(v).
  const double rho = rho_[v];
  const Vec3 n = normal_[v];
  const Vec3 q = mesh_.position(v) + r * dir;
  double delta = rho - std::sqrt(std::max(rho * rho - r * r, 0.0));
  Vec3 out;
  Index cell = cell_[v];
  for (int attempt = 0; attempt < 4; ++attempt, delta *= 2) {
    if (skin_.project_along_line(q, n, delta * (1 + 1e-9) + 1e-12 * skin_.length_scale(), out, cell)) {
      if (cell_out) *cell_out = cell;
      return out;
    }
  }
  // Fall back on the gradient pull-back (papers/skin/skin_math.md §7.3).
  cell = cell_[v];
  out = skin_.pull_back(q, cell);
  if (cell_out) *cell_out = cell;
  return out;
}

// Holds in Protecting Spheres (Algorithm 1, lines 3–10)

Index Sweep::hold_region(Vertex v) const {
  // v is held if its tangent disc meets the protecting sphere of a live
  // saddle or maximum not yet resolved, so that no fan enters the sphere
  // (Cheng & Shi §4.2: "each step of the front advancing must not cross to the
  // other side of the spheres"); the nearest such critical point holds it.
  const Vec3& p = mesh_.position(v);
  const double r = disc_radius(v);
  Index best = kInvalidIndex;
  double best_d = std::numeric_limits<double>::infinity();
  hold_grid_->for_each_near(p, max_hold_radius_ + r, [&](Index c, const Vec3& q) {
    if (resolved_[c]) return;
    const double d = (p - q).norm();
    // The nearest, ties to the lower index (independent of the grid's order).
    if (d < ms_.protect_radius[c] + r && (d < best_d || (d == best_d && c < best))) best = c, best_d = d;
  });
  return best;
}

void Sweep::hold(Vertex v, Index c) {
  // Lines 7 and 10: "mark the triangle red / green"; line 4–5: a saddle that
  // is ready is bridged at once.
  set_state(v, VState::Held);
  held_by_[v] = c;
  held_[c].push_back(v);
  ++stats_.held;
  if (trace_) tracef("hold v%u by critical point %u\n", v.idx(), c);
  const std::size_t f0 = mesh_.faces_size();
  notify(SweepOperation::Hold, v, c, f0);
  if (ms_.critical[c].kind == CriticalKind::Saddle && try_bridge(c)) {
    paranoid_check(f0, "bridge");
    notify(SweepOperation::Bridge, Vertex(), c, f0);
  }
  const std::size_t f1 = mesh_.faces_size();
  drain_wings();
  paranoid_check(f1, "wings after a hold");
  if (mesh_.faces_size() > f1) notify(SweepOperation::Wings, v, kInvalidIndex, f1);
}

bool Sweep::release_holds(Index c, bool requeue) {
  bool any = false;
  for (Vertex v : held_[c])
    if (state_[v] == VState::Held && held_by_[v] == c) {
      set_state(v, VState::Front);
      held_by_[v] = kInvalidIndex;
      if (requeue && mesh_.is_boundary(v)) push(v), any = true;
    }
  held_[c].clear();
  return any;
}

bool Sweep::release_saddles() {
  // Saddles never bridged (the front reached them from one side only, or the
  // two sides met elsewhere by a contact): release their holds and go on
  // (papers/front/open_questions.md Q6.4); the final topology check decides.
  bool any = false;
  for (std::size_t c = 0; c < ms_.critical.size(); ++c) {
    if (!ms_.live[c] || ms_.critical[c].kind != CriticalKind::Saddle || resolved_[c]) continue;
    resolved_[c] = 1;
    ++stats_.released;
    if (trace_) tracef("release saddle %zu unbridged\n", c);
    if (release_holds(static_cast<Index>(c), /*requeue=*/true)) any = true;
  }
  return any;
}

// Algorithm 1

void Sweep::create_initial_front() {
  // "Initial front": a bowl at every live minimum (Figure 5), lowest first.
  // Not in the paper: a minimum whose bowl would overlap a bowl already made
  // (two minima closer than the sum of their bowl radii, on a flat patch the
  // arc contraction left alone) gets none: the two bowls would overlap from
  // the start, and no front operation can undo that. The neighbouring bowl's
  // front sweeps its basin, and the saddles the missing bowl would have
  // touched are resolved with it (papers/front/creation.md, "Overlapping bowls").
  std::vector<Index> minima;
  for (std::size_t c = 0; c < ms_.critical.size(); ++c)
    if (ms_.live[c] && ms_.critical[c].kind == CriticalKind::Minimum) minima.push_back(static_cast<Index>(c));
  std::stable_sort(minima.begin(), minima.end(), [&](Index a, Index b) {
    return ms_.critical[a].position.dot(e_) < ms_.critical[b].position.dot(e_);
  });
  // rho never exceeds rho_max_, the largest sphere radius sqrt(w/2) (as for vertex_grid_).
  for (Index c : minima) {
    const morse::CriticalPoint& cp = ms_.critical[c];
    const double r = opt_.disc_factor * cp.rho;
    bool overlaps = false;
    vertex_grid_->for_each_near(cp.position, r + opt_.disc_factor * rho_max_, mesh_.positions().vector(),
                                [&](Index xi, const Vec3& q) {
      if ((q - cp.position).norm() < r + disc_radius(Vertex(xi))) overlaps = true;
    });
    if (!overlaps) {
      const std::size_t f0 = mesh_.faces_size();
      creation(c);
      notify(SweepOperation::Creation, Vertex(), c, f0);
      continue;
    }
    ++stats_.merged_minima;
    if (trace_) tracef("creation: no bowl at minimum %u, it would overlap a bowl already made\n", c);
    hold_grid_->for_each_near(cp.position, r + max_hold_radius_, [&](Index s, const Vec3& q) {
      if (ms_.critical[s].kind == CriticalKind::Saddle && (q - cp.position).norm() < r + ms_.protect_radius[s])
        resolved_[s] = 1;
    });
  }
}

void Sweep::report_progress(double h) {
  if (!opt_.progress) return;
  const double span = h_max_ - h_min_;
  const double f = span > 0 ? std::clamp((h - h_min_) / span, 0.0, 1.0) : 0.0;
  if (f < next_progress_) return;
  next_progress_ = f + 0.01;
  opt_.progress("sweep", f);
}

bool Sweep::departure_step() {
  // Line 1: while Q is not empty.
  while (!queue_.empty()) {
    // Line 2: t = ExtractMin(Q), the lowest front vertex (lazy deletion: an
    // entry whose stamp is old, or a vertex no longer free on the front, is
    // skipped).
    const QueueEntry top = queue_.top();
    queue_.pop();
    const Vertex v(top.v);
    if (top.stamp != stamp_[v] || state_[v] != VState::Front || mesh_.is_deleted(v) || mesh_.is_isolated(v) ||
        !mesh_.is_boundary(v))
      continue;
    if (opt_.max_steps >= 0 && steps_++ >= opt_.max_steps) {
      if (!opt_.dump_path.empty()) geometry::write_mesh(opt_.dump_path, mesh_.to_indexed_mesh());
      throw TopologyError("stopped after " + std::to_string(opt_.max_steps) + " departures (max_steps)");
    }
    report_progress(top.h);
    // Lines 3–10: in the protecting sphere of a saddle (bridged when ready)
    // or of a maximum: the vertex is held.
    if (const Index c = hold_region(v); c != kInvalidIndex) {
      hold(v, c);
      return true;
    }
    const std::size_t f0 = mesh_.faces_size();
    if (small_hole(v)) {
      // Not in the paper: the fronts around v have met in a small hole; close
      // it now, as seal() would, instead of creeping new vertices into it
      // (papers/front/hole_filling.md).
      close_small_hole(v);
      paranoid_check(f0, "closing a small hole");
      notify(SweepOperation::SmallHole, v, kInvalidIndex, f0);
      return true;
    }
    // Lines 11–12: creep().
    creep(v);
    paranoid_check(f0, "creep");
    notify(SweepOperation::Creep, v, kInvalidIndex, f0);
    // Line 14, "refine the newly added triangles": here the wings of the
    // front angles below 90° (Figure 7); the local refinement of §4.3 runs
    // after the seal (papers/front/sweep.md, "Deviations").
    const std::size_t f1 = mesh_.faces_size();
    drain_wings();
    paranoid_check(f1, "wings after a creep");
    if (mesh_.faces_size() > f1) notify(SweepOperation::Wings, v, kInvalidIndex, f1);
    return true;
  }
  return false;
}

SweepResult Sweep::run() {
  create_initial_front();
  // Creeping triangles: Algorithm 1 until the queue is empty, then release the
  // saddles never bridged and go on while that frees any vertex.
  do {
    while (departure_step()) {
    }
  } while (release_saddles());
  if (opt_.progress) opt_.progress("sweep", 1.0);
  // Sealing holes.
  if (!opt_.dump_path.empty()) geometry::write_mesh(opt_.dump_path, mesh_.to_indexed_mesh());
  seal_all();
  // The result keeps the properties the refinement needs.
  vertex_grid_.reset();
  front_grid_.reset();
  mesh_.remove_vertex_property(state_);
  mesh_.remove_vertex_property(held_by_);
  mesh_.remove_vertex_property(stamp_);
  mesh_.remove_vertex_property(deferrals_);
  mesh_.remove_vertex_property(reopenings_);
  SweepResult res;
  res.mesh = std::move(mesh_);
  res.stats = stats_;
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
  detail::Sweep sweep(skin, ms, opt);
  return sweep.run();
}

}  // namespace skinmesh::front
