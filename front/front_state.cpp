// front/front_state.cpp: FrontState's constructor — the empty partial mesh
// with its per-vertex data, and the grids of the protecting spheres, of the
// vertices and of the front — and what every operation does to the state:
// new vertices on the skin, the departure queue, the projection onto the
// skin, the progress reports.
// Notes: papers/front/sweep.md
#include "front/front_state.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "core/errors.h"
#include "front/operations.h"
#include "skin/vertex_data.h"

namespace skinmesh::front::detail {

using morse::CriticalKind;

SweptRegion::SweptRegion(Region r) : spec(std::move(r)) {
  for (const morse::CutDetour& d : spec.upper_detours)
    upper_balls.insert(upper_balls.end(), d.balls.begin(), d.balls.end());
  if (upper_balls.empty()) return;
  std::vector<Vec3> at;
  std::vector<double> size;
  for (const morse::DetourBall& b : upper_balls) at.push_back(b.center), size.push_back(b.radius);
  ball_grid.build(at, size);
  at.clear(), size.clear();
  for (std::size_t k = 0; k < spec.upper_curves.size(); ++k) {
    const std::vector<Vec3>& p = spec.upper_curves[k].points;
    for (std::size_t j = 0; j < p.size(); ++j) {
      const Vec3& a = p[j];
      const Vec3& b = p[(j + 1) % p.size()];
      at.push_back(0.5 * (a + b)), size.push_back(0.5 * (b - a).norm());
      upper_edges.emplace_back(static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(j));
    }
  }
  edge_grid.build(at, size);
}

FrontState::FrontState(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const SweepOptions& opt,
                       skin::RunContext run, Region region)
    : skin(skin), ms(ms), opt(opt), run(std::move(run)), e(ms.height_direction), region(std::move(region)) {
  const skin::SizeConstants& size = this->run.size;
  if (!(opt.disc_factor > size.disc_factor_lower() && opt.disc_factor <= size.disc_factor_upper())) {
    std::ostringstream os;
    os << "sweep: disc_factor " << opt.disc_factor << " is outside the tangent-disc window ("
       << size.disc_factor_lower() << ", " << size.disc_factor_upper() << "] of C = " << size.C << ", Q = " << size.Q
       << " (Cheng & Shi §4.2)";
    throw std::invalid_argument(os.str());
  }
  // The per-vertex counters are 8 bits wide.
  if (!(opt.max_deferrals >= 0 && opt.max_deferrals <= 255) ||
      !(opt.max_reopenings >= 0 && opt.max_reopenings <= 255) ||
      !(opt.max_departures >= 0 && opt.max_departures <= 255))
    throw std::invalid_argument("sweep: max_deferrals, max_reopenings and max_departures must lie in [0, 255]");
  normal = mesh.add_vertex_property(kVertexFrontNormal, Vec3::Zero());
  rho = mesh.add_vertex_property(kVertexFrontRho, 0.0);
  cell = mesh.add_vertex_property(skin::kVertexCell, kInvalidIndex);
  state = mesh.add_vertex_property(kVertexState, VState::Interior);
  held_by = mesh.add_vertex_property(kVertexHeldBy, kInvalidIndex);
  stamp = mesh.add_vertex_property(kVertexStamp, 0);
  deferrals = mesh.add_vertex_property(kVertexDeferrals, 0);
  reopenings = mesh.add_vertex_property(kVertexReopenings, 0);
  departures = mesh.add_vertex_property(kVertexDepartures, 0);
  const std::size_t nc = ms.critical.size();
  resolved.assign(nc, 0);
  held.resize(nc);
  // Only the critical points that can hold this region's front go into the
  // hold grid and its bounds (every one for the whole skin and for level
  // cuts; a group of components or a detoured region holds its own): a
  // region's grid follows its own size, not the skin's.
  const auto holds_here = [this](std::size_t i) { return this->region.holds(static_cast<Index>(i)); };
  double rmax = 0;
  for (std::size_t i = 0; i < nc; ++i) {
    if (!holds_here(i)) continue;
    rmax = std::max(rmax, ms.protect_radius[i]);
    if (ms.critical[i].rho > 0) protect_factor = std::max(protect_factor, ms.protect_radius[i] / ms.critical[i].rho);
  }
  // A hold query at a vertex of scale rho reaches hold_reach · rho
  // (for_each_hold_near): each critical point goes into the levels of the
  // queries that can reach it, so that a query reads its own level alone, in
  // cells of twice its reach at the level's largest rho (1-2 cells per axis;
  // the critical points are sparse, so a probe of an empty cell costs more
  // than reading a few more points: [measured] papers/bench/profile.md,
  // "After": the grids' cell sizes).
  hold_reach = protect_factor < 1 ? (protect_factor + opt.disc_factor) / (1 - protect_factor) * (1 + 1e-9) : 0;
  hold_grid = std::make_unique<geometry::LeveledPointGrid>(std::max(2 * hold_reach, kMinGridCell), kGridOctaves,
                                                           /*erasable=*/false);
  critical_positions.resize(nc);
  for (std::size_t i = 0; i < nc; ++i) {
    critical_positions[i] = ms.critical[i].position;
    if (!ms.live[i] || ms.critical[i].kind == CriticalKind::Minimum || !holds_here(i)) continue;
    const double rho_c = ms.critical[i].rho;
    if (hold_reach > 0 && hold_reach < 1)  // queries from rho_p with |rho_c - rho_p| <= hold_reach rho_p
      hold_grid->insert_for_queries(static_cast<Index>(i), ms.critical[i].position, rho_c / (1 + hold_reach),
                                    rho_c / (1 - hold_reach));
    else
      hold_grid->insert_for_queries(static_cast<Index>(i), ms.critical[i].position, 0,
                                    std::numeric_limits<double>::infinity());
  }
  max_hold_radius = rmax;
  for (const auto& wp : skin.points()) rho_max = std::max(rho_max, std::sqrt(std::max(wp.w, 0.0) / 2));
  // Per level of rho, the front grid's cells are four disc radii at the
  // level's largest rho: the contact query (1.5 r) then probes 1-2 cells per
  // axis, and the front is a curve, so most probed cells would be empty at a
  // finer size. The vertex grid's are two disc radii: the fan-collision query
  // (0.5 r) then probes one or two cells per axis, and the grid, which holds
  // every vertex to the end of the sweep, has an eighth of the cells of a grid
  // of one radius: 4.1 MB less at maltoporin's peak, the sweep's instruction
  // count 1 % higher ([measured] papers/bench/profile.md, "The vertex grid's
  // cells").
  // The fan-collision query at v reads the vertices within collision_reach ·
  // rho(v) of v (FrontState::collision_reach): each vertex goes into the
  // levels of the queries that can reach it (new_vertex).
  collision_reach = (1 + opt.collision_radius) * opt.disc_factor * (1 + 1e-9);
  vertex_grid = std::make_unique<geometry::LeveledIndexGrid>(2 * opt.disc_factor, kGridOctaves, /*erasable=*/false);
  front_grid = std::make_unique<geometry::LeveledPointGrid>(4 * opt.disc_factor, kGridOctaves);
  // A generous bound on the vertex count: 8 times what a separate sphere per
  // atom would need (4 pi / (c_r² sqrt(3)/2) vertices per sphere), times a
  // factor for the scales below the atoms' that the front has met (new_vertex).
  const double per_atom = 4 * kPi / (opt.disc_factor * opt.disc_factor * kFanAreaPerVertex);
  base_vertex_budget = kVertexBudgetFloor + kVertexBudgetFactor * per_atom * static_cast<double>(skin.points().size());
  vertex_budget = static_cast<std::size_t>(base_vertex_budget);
  // Height range for progress reports.
  h_min = std::numeric_limits<double>::infinity();
  h_max = -h_min;
  for (const auto& cp : ms.critical) {
    h_min = std::min(h_min, e.dot(cp.position));
    h_max = std::max(h_max, e.dot(cp.position));
  }
}

// Vertices and the queue

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
  if (fs.collision_reach < 1)
    fs.vertex_grid->insert_for_queries(v.idx(), p, s.rho / (1 + fs.collision_reach), s.rho / (1 - fs.collision_reach));
  else
    fs.vertex_grid->insert_for_queries(v.idx(), p, 0, std::numeric_limits<double>::infinity());
  fs.normal[v] = s.gradient.normalized();  // what skin::VertexNormals gives from the cell below
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
  for (int attempt = 0; attempt < kProjectionAttempts; ++attempt, delta *= 2) {
    if (fs.skin.project_along_line(
            q, n, delta * (1 + kBracketRelativeSlack) + kBracketAbsoluteSlack * fs.skin.length_scale(), out, cell)) {
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

void report_progress(FrontState& fs, double h) {
  if (fs.run.cancel && fs.run.cancel->load(std::memory_order_relaxed)) throw Cancelled();
  if (!fs.run.progress) return;
  const double span = fs.h_max - fs.h_min;
  const double f = span > 0 ? std::clamp((h - fs.h_min) / span, 0.0, 1.0) : 0.0;
  if (f < fs.next_progress) return;
  fs.next_progress = f + kProgressStep;
  fs.run.progress("sweep", f);
}

}  // namespace skinmesh::front::detail
