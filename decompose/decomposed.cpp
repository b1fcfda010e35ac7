// decompose/decomposed.cpp: the cut choice and the glue of the decomposed sweep
// (decompose/decomposed.h). Every slab's mesh keeps its own vertices; the cut
// samples are vertices of the slab above (its first ones, in curve order),
// which the band below reuses, so the glued mesh shares them exactly.
// Notes: papers/decompose/README.md ("The cuts", "The glue")
#include "decompose/decomposed.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <mutex>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/errors.h"
#include "core/parallel.h"
#include "decompose/band.h"
#include "decompose/slab_pool.h"
#include "decompose/work.h"
#include "skin/vertex_data.h"

namespace skinmesh::decompose {

using front::LowerCutError;
using front::Region;
using front::RegionResult;
using front::SweepOptions;
using front::SweepResult;
using front::SweepStats;

namespace {

/// The critical points sorted by height, with the bounds that let a cut's
/// tests read only the points near its plane: the largest disc radius (for
/// the height window) and the largest protecting radius of a live point (for
/// the sphere margin). Built once per choose_cuts(); each test then costs the
/// points within its reach of the plane, not all of them.
struct CriticalByHeight {
  std::vector<std::size_t> order;  ///< indices into ms.critical, by increasing height
  std::vector<double> height;      ///< their heights, in that order
  double r_max = 0, s_max = 0;

  CriticalByHeight(const morse::MorseSmaleComplex& ms, double disc_factor) {
    order.resize(ms.critical.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return ms.critical[a].height < ms.critical[b].height || (ms.critical[a].height == ms.critical[b].height && a < b);
    });
    for (std::size_t i : order) {
      height.push_back(ms.critical[i].height);
      r_max = std::max(r_max, disc_factor * ms.critical[i].rho);
      if (i < ms.live.size() && ms.live[i] && i < ms.protect_radius.size())
        s_max = std::max(s_max, ms.protect_radius[i]);
    }
  }
  /// The positions in `order` of the points with lo <= height <= hi.
  std::pair<std::size_t, std::size_t> range(double lo, double hi) const {
    return {static_cast<std::size_t>(std::lower_bound(height.begin(), height.end(), lo) - height.begin()),
            static_cast<std::size_t>(std::upper_bound(height.begin(), height.end(), hi) - height.begin())};
  }
};

/// True if no critical point lies in the height window that the cut at c
/// forbids it (DecompositionOptions::window_below, window_above).
bool window_clear(const morse::MorseSmaleComplex& ms, const CriticalByHeight& by_height, double c,
                  const DecompositionOptions& opt, double disc_factor) {
  const auto [first, last] =
      by_height.range(c - opt.window_below * by_height.r_max, c + opt.window_above * by_height.r_max);
  for (std::size_t k = first; k < last; ++k) {
    const morse::CriticalPoint& p = ms.critical[by_height.order[k]];
    const double r = disc_factor * p.rho;
    if (p.height >= c - opt.window_below * r && p.height <= c + opt.window_above * r) return false;
  }
  return true;
}

/// True if every sample of `curves` lies sphere_margin disc radii outside
/// every live protecting sphere.
bool clear_of_spheres(const morse::MorseSmaleComplex& ms, const CriticalByHeight& by_height, double c,
                      const std::vector<morse::LevelCurve>& curves, const DecompositionOptions& opt,
                      double disc_factor) {
  double rho_max = 0;
  for (const morse::LevelCurve& curve : curves)
    for (double rho : curve.rho) rho_max = std::max(rho_max, rho);
  const double reach = opt.sphere_margin * disc_factor * rho_max;
  // A sample is at least |h(p) - c| from p: only the spheres near the
  // plane can come within the margin.
  const auto [first, last] = by_height.range(c - by_height.s_max - reach, c + by_height.s_max + reach);
  for (std::size_t k = first; k < last; ++k) {
    const std::size_t i = by_height.order[k];
    if (i >= ms.live.size() || !ms.live[i] || i >= ms.protect_radius.size()) continue;
    const double s = ms.protect_radius[i];
    const morse::CriticalPoint& p = ms.critical[i];
    if (std::abs(p.height - c) >= s + reach) continue;
    for (const morse::LevelCurve& curve : curves)
      for (std::size_t j = 0; j < curve.points.size(); ++j)
        if ((curve.points[j] - p.position).norm() - s < opt.sphere_margin * disc_factor * curve.rho[j]) return false;
  }
  return true;
}

/// True if the cuts at `a` (below) and `b` are at least min_thickness disc
/// radii apart at every sample of either.
bool thick_enough(const Cut& a, const Cut& b, const DecompositionOptions& opt, double disc_factor) {
  const double gap = b.height - a.height;
  for (const Cut* cut : {&a, &b})
    for (const morse::LevelCurve& curve : cut->curves)
      for (double rho : curve.rho)
        if (gap < opt.min_thickness * disc_factor * rho) return false;
  return true;
}

/// True if every sample of the cut `b` lies min_thickness disc radii (r at
/// the sample) above every sample of the cut `a` below it: cuts that detour
/// rise and dip around their balls, so their heights alone do not tell.
bool apart(const Cut& a, const Cut& b, const Vec3& e, const DecompositionOptions& opt, double disc_factor) {
  double top = -std::numeric_limits<double>::infinity();
  for (const morse::LevelCurve& curve : a.curves)
    for (const Vec3& p : curve.points) top = std::max(top, p.dot(e));
  for (const morse::LevelCurve& curve : b.curves)
    for (std::size_t j = 0; j < curve.points.size(); ++j)
      if (curve.points[j].dot(e) - top < opt.min_thickness * disc_factor * curve.rho[j]) return false;
  return true;
}

/// Per critical point, whether it lies below the cut (in the part the slab
/// below it meshes): by its cluster's side if a ball of the cut holds it,
/// else by its height.
std::vector<char> below_cut(const Cut& cut, const morse::MorseSmaleComplex& ms) {
  std::vector<char> below(ms.critical.size());
  for (std::size_t p = 0; p < below.size(); ++p) below[p] = ms.critical[p].height <= cut.height;
  for (const morse::CutDetour& d : cut.detours)
    for (const morse::DetourBall& b : d.balls) below[b.critical] = !d.upper;
  return below;
}

void add_stats(SweepStats& a, const SweepStats& b) {
  a.creations += b.creations, a.creeps += b.creeps, a.wings += b.wings, a.bridges += b.bridges;
  a.seals += b.seals, a.held += b.held, a.deferred += b.deferred, a.bridge_rows += b.bridge_rows;
  a.contacts += b.contacts, a.stuck += b.stuck, a.enlarged_holes += b.enlarged_holes;
  a.reopened_holes += b.reopened_holes, a.collisions += b.collisions, a.released += b.released;
  a.merged_minima += b.merged_minima, a.left_holes += b.left_holes, a.folds += b.folds;
  a.patched_holes += b.patched_holes, a.patch_faces += b.patch_faces, a.parked += b.parked;
  a.departures += b.departures, a.spent_vertices += b.spent_vertices, a.reopened_faces += b.reopened_faces;
  a.covered_triangles += b.covered_triangles, a.swept_faces += b.swept_faces,
      a.most_departures = std::max(a.most_departures, b.most_departures);
}

/// Wall-clock seconds since `start`.
double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Refines the slab's mesh in place, its boundary kept
/// (DecompositionOptions::refine_regions), on one thread, and compacts it;
/// the indices of its lower loops and rims follow. Returns the old -> new
/// vertex map (empty: nothing deleted). The lower curves' samples, its
/// first vertices and all on the boundary, keep theirs.
std::vector<Index> refine_region(const skin::SkinSurface& skin, SlabOutcome& o, const DecompositionOptions& opt,
                                 const skin::RunContext& run) {
  RegionResult& r = *o.result;
  const auto start = std::chrono::steady_clock::now();
  o.refinement = refine::refine_mesh(skin, r.mesh, opt.refinement, run.with_threads(1));
  o.refined = true;
  std::vector<Index> to;
  if (r.mesh.has_garbage()) {
    to.assign(r.mesh.vertices_size(), kInvalidIndex);
    Index next = 0;
    for (std::size_t i = 0; i < to.size(); ++i)
      if (!r.mesh.is_deleted(geometry::Vertex(static_cast<Index>(i)))) to[i] = next++;
    for (std::vector<std::vector<Index>>* loops : {&r.lower_loops, &r.upper_rims})
      for (std::vector<Index>& loop : *loops)
        for (Index& v : loop) v = to[v];
    r.mesh.garbage_collection();
  }
  o.seconds += seconds_since(start);
  return to;
}

/// sweep_region(), with the failures the decomposition answers by merging
/// the slab with a neighbour (a front the slab's bounds disturb, a
/// construction near them that fails, a slab too thin) caught.
SlabOutcome sweep_one(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const Region& slab,
                      const SweepOptions& sweep, const skin::RunContext& run) {
  SlabOutcome o;
  const auto start = std::chrono::steady_clock::now();
  try {
    o.result = sweep_region(skin, ms, slab, sweep, run);
  } catch (const LowerCutError& e) {
    o.error = e.what();
    o.at_lower_cut = true;
  } catch (const TopologyError& e) {
    o.error = e.what();
  } catch (const GeometryError& e) {
    o.error = e.what();
  } catch (const std::invalid_argument& e) {
    o.error = e.what();
  }
  o.seconds = seconds_since(start);
  return o;
}

/// Appends `part` (garbage-collected) to `mesh` with its vertex data
/// (normal, rho, cell: the properties both carry), emptying `part` as it is
/// read so that the glue never holds two copies of it
/// (SurfaceMesh::append_consuming); returns the index its vertex 0 gets.
Index append_with_vertex_data(geometry::SurfaceMesh& mesh, geometry::SurfaceMesh& part) {
  const Index base = static_cast<Index>(mesh.vertices_size());
  mesh.append_consuming(part);
  return base;
}

/// The ladder's rung of groups: one sweep per group of whole components
/// (morse::component_groups()), on up to run.threads threads, their meshes
/// appended in group order. Nothing when the skin is one group, or when a
/// group's sweep fails (its error in `why`): the next rung sweeps everything
/// at once. A group's fronts never meet another group's surface, so nothing else is
/// shared (papers/decompose/README.md, "Groups of whole components"). With `unglued`,
/// two or more groups' meshes are moved there in group order instead of
/// appended, and the result holds their summed stats only. With
/// run.release_made_cells the groups go in windows of run.threads, and the
/// complex's made cells and planes go back after each window.
std::optional<SweepResult> sweep_components(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms,
                                            const SweepOptions& sweep, const skin::RunContext& run,
                                            DecompositionCosts& costs, std::string& why,
                                            std::vector<SweepResult>* unglued) {
  const morse::ComponentGroups groups = morse::component_groups(ms);
  if (groups.count < 2) return std::nullopt;
  const int threads = run.threads;
  const bool release_made = run.release_made_cells;
  // Each group reports nothing: the progress is the groups done.
  const skin::RunContext part_run = run.quiet();
  std::vector<std::optional<SweepResult>> parts(groups.count);
  std::vector<std::string> errors(groups.count);
  std::vector<double> seconds(groups.count, 0.0);
  std::mutex progress_mutex;
  std::size_t finished = 0;
  // Largest groups first (by their critical points, ties in group order):
  // the threads' loads even out at the end, and a window of `threads`
  // groups holds groups of about one size. The order of the work changes no
  // group's mesh: each reads only the skin and its own front.
  std::vector<std::size_t> points(groups.count, 0), order(groups.count);
  for (const Index g : groups.group) ++points[g];
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return points[a] > points[b]; });
  auto sweep_group = [&](std::size_t g) {
    const auto start = std::chrono::steady_clock::now();
    try {
      Region group;
      group.owns.assign(ms.critical.size(), 0);
      for (std::size_t p = 0; p < ms.critical.size(); ++p) group.owns[p] = groups.group[p] == g;
      parts[g] = sweep_mesh(skin, ms, group, sweep, part_run);
      parts[g]->mesh.garbage_collection();
    } catch (const TopologyError& e) {
      errors[g] = e.what();
    } catch (const GeometryError& e) {
      errors[g] = e.what();
    }
    seconds[g] = seconds_since(start);
    if (run.progress) {
      const std::lock_guard<std::mutex> lock(progress_mutex);
      run.progress("sweep", static_cast<double>(++finished) / static_cast<double>(groups.count));
    }
  };
  const std::size_t window = release_made ? static_cast<std::size_t>(std::max(threads, 1)) : order.size();
  for (std::size_t w = 0; w < order.size(); w += window) {
    const std::size_t end = std::min(order.size(), w + window);
    parallel_for(end - w, threads, 1, [&](std::size_t i) { sweep_group(order[w + i]); });
    if (release_made) skin.mixed_complex().release_made();
  }
  for (Index g = 0; g < groups.count; ++g)
    if (!errors[g].empty()) {
      why = "component group " + std::to_string(g) + " of " + std::to_string(groups.count) + ": " + errors[g];
      return std::nullopt;
    }
  if (unglued) {
    SweepResult out;
    unglued->reserve(groups.count);
    for (Index g = 0; g < groups.count; ++g) {
      costs.components.push_back({seconds[g], parts[g]->mesh.n_faces()});
      if (g == 0)
        out.stats = parts[g]->stats;
      else
        add_stats(out.stats, parts[g]->stats);
      unglued->push_back(std::move(*parts[g]));
    }
    return out;
  }
  // The glue: the first group's mesh taken as it is (no copy of it at the
  // peak), every other group's appended, its vertex data with it.
  const auto glue_start = std::chrono::steady_clock::now();
  SweepResult out;
  out.mesh = std::move(parts[0]->mesh);
  out.stats = parts[0]->stats;
  costs.components.push_back({seconds[0], out.mesh.n_faces()});
  parts[0].reset();
  geometry::SurfaceMesh& mesh = out.mesh;
  {
    std::size_t nv = mesh.vertices_size(), nf = mesh.faces_size();
    for (Index g = 1; g < groups.count; ++g) nv += parts[g]->mesh.vertices_size(), nf += parts[g]->mesh.faces_size();
    mesh.reserve(nv, nf);
  }
  for (Index g = 1; g < groups.count; ++g) {
    SweepResult& r = *parts[g];
    costs.components.push_back({seconds[g], r.mesh.n_faces()});
    add_stats(out.stats, r.stats);
    append_with_vertex_data(mesh, r.mesh);
    parts[g].reset();  // its copy is in the glued mesh
  }
  costs.glue = seconds_since(glue_start);
  return out;
}

/// A vertex of a band: of the slab below the cut (a rim vertex) or of the
/// slab above (a sample of the cut's curve), by its index in that slab's mesh.
struct BandVertex {
  bool above = false;
  Index index = 0;
};

/// The strip closing one parked rim's band.
struct Band {
  std::vector<std::array<BandVertex, 3>> triangles;
};

/// The bands under the cut at `height` between the slab `below` and the
/// slab `above`: each parked rim of `below` with the samples of its curve,
/// which are the vertices of `above`'s lower loop of that curve (both
/// meshes of the skin whose mixed complex is `mc`). Throws TopologyError if a
/// band has no outward strip.
std::vector<Band> close_bands(const skin::MixedComplex& mc, const RegionResult& below, const RegionResult& above,
                              double height) {
  const skin::VertexNormals normal_below(mc, below.mesh), normal_above(mc, above.mesh);
  std::vector<Band> bands;
  for (std::size_t i = 0; i < below.upper_rims.size(); ++i) {
    const std::vector<Index>& whole = below.upper_rims[i];
    const std::vector<Index>& curve = above.lower_loops[below.rim_curve[i]];
    // The strip starts at rim vertex 0 and the curve samples nearest to it;
    // where those lie across a narrow gap (another stretch of the same
    // curve), no outward strip starts there: the rim is tried from other
    // starts, a quarter of it apart, before the band is given up.
    std::vector<Vec3> b, bn;
    for (Index v : curve) {
      b.push_back(above.mesh.position(geometry::Vertex(v)));
      bn.push_back(normal_above[geometry::Vertex(v)]);
    }
    std::vector<Index> rim;
    std::vector<StripTriangle> strip;
    for (int attempt = 0; attempt < 4 && strip.empty(); ++attempt) {
      const std::size_t shift = static_cast<std::size_t>(attempt) * whole.size() / 4;
      rim.assign(whole.begin() + static_cast<std::ptrdiff_t>(shift), whole.end());
      rim.insert(rim.end(), whole.begin(), whole.begin() + static_cast<std::ptrdiff_t>(shift));
      std::vector<Vec3> a, an;
      for (Index v : rim) {
        a.push_back(below.mesh.position(geometry::Vertex(v)));
        an.push_back(normal_below[geometry::Vertex(v)]);
      }
      // The corridor: a few dozen edges of slack in arc-length fraction.
      const double corridor = std::min(1.0, 24.0 / static_cast<double>(std::min(a.size(), b.size())));
      strip = strip_triangulation(a, an, b, bn, corridor);
    }
    if (strip.empty()) {
      std::ostringstream os;
      os << "decomposed sweep: the band between a parked rim and the cut curve at height " << height << " through ("
         << b.front().transpose() << ") has no outward strip";
      throw TopologyError(os.str());
    }
    Band& band = bands.emplace_back();
    const Index n_rim = static_cast<Index>(rim.size());
    for (const StripTriangle& t : strip) {
      std::array<BandVertex, 3>& g = band.triangles.emplace_back();
      for (int k = 0; k < 3; ++k)
        g[k] = t[k] < n_rim ? BandVertex{false, rim[t[k]]} : BandVertex{true, curve[t[k] - n_rim]};
    }
  }
  return bands;
}

}  // namespace

int automatic_slabs(std::size_t atoms, const DecompositionOptions& opt) {
  double n = static_cast<double>(atoms) / opt.atoms_per_slab;
  if (opt.atoms_per_root_slab > 0) n = std::min(n, std::sqrt(static_cast<double>(atoms) / opt.atoms_per_root_slab));
  n = std::round(n);
  return static_cast<int>(std::clamp(n, 1.0, static_cast<double>(opt.max_slabs)));
}

int automatic_slabs(std::size_t atoms, const morse::MorseSmaleComplex& ms, const DecompositionOptions& opt,
                    const SweepOptions& sweep) {
  if (!opt.components || sweep.observer || sweep.trace || ms.critical.empty()) return 1;
  // A group's share only lowers the count: one slab for every atom means one
  // for any group, without the groups' cost (small inputs).
  if (automatic_slabs(atoms, opt) == 1) return 1;
  const morse::ComponentGroups groups = morse::component_groups(ms);
  if (groups.count < 2) return automatic_slabs(atoms, opt);
  std::vector<std::size_t> points(static_cast<std::size_t>(groups.count), 0);
  for (const Index g : groups.group) ++points[g];
  const std::size_t largest = *std::max_element(points.begin(), points.end());
  if (2 * largest <= ms.critical.size()) return 1;
  const double share = static_cast<double>(largest) / static_cast<double>(ms.critical.size());
  return automatic_slabs(static_cast<std::size_t>(std::llround(share * static_cast<double>(atoms))), opt);
}

namespace {

/// The detoured cut at height c (morse::cut_detours(), morse::cut_curves()),
/// or nothing where the height admits none: a near-tangency or an unjoined
/// corner (GeometryError), or no curve. A cluster that goes down but whose
/// union the level set enters (the cut runs along its arcs above c) goes up
/// instead: below such arcs the slab below would have to bridge or seal the
/// cluster's critical points within a disc radius or two of its parked rim,
/// and its front parks before it reaches their protecting spheres (HIV
/// protease at probe 0: a saddle 0.011 Å under the cut, the curves on its
/// ball's boundary, the two curves' rims one loop). Above, the slab starts on
/// the arcs below the cluster, inside its spheres' hold regions, as the sweep
/// reaches any protecting sphere. A cluster the level set does not enter lies
/// wholly on its side and keeps it, and so does one that holds a live
/// minimum under c: sent up, the part of the minimum's dent below c outside
/// its balls would stay with the slab below, cut off from that slab's fronts
/// and with no minimum of its own to start one (HIV protease at probe 0: a
/// curve of 22 samples with no rim; papers/decompose/history.md, seventh
/// session). Depends on c and the input only.
std::optional<Cut> detoured_cut(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, double c,
                                const DecompositionOptions& opt) {
  Cut cut{c, {}, morse::cut_detours(ms, c), true};
  try {
    cut.curves = morse::cut_curves(skin, ms, c, cut.detours, opt.curves);
    std::vector<char> entered(cut.detours.size(), 0);
    for (const morse::LevelCurve& curve : cut.curves)
      for (Index d : curve.detour)
        if (d != kInvalidIndex && !cut.detours[d].upper) entered[d] = 1;
    // A cluster with a live minimum under the cut keeps its side.
    for (std::size_t d = 0; d < entered.size(); ++d)
      for (const morse::DetourBall& b : cut.detours[d].balls)
        if (ms.live[b.critical] && ms.critical[b.critical].kind == morse::CriticalKind::Minimum &&
            ms.critical[b.critical].height < c)
          entered[d] = 0;
    if (std::find(entered.begin(), entered.end(), 1) != entered.end()) {
      for (std::size_t d = 0; d < entered.size(); ++d)
        if (entered[d]) cut.detours[d].upper = true;
      cut.curves = morse::cut_curves(skin, ms, c, cut.detours, opt.curves);
    }
  } catch (const GeometryError&) {
    return std::nullopt;
  }
  if (cut.curves.empty()) return std::nullopt;
  return cut;
}

}  // namespace

std::vector<Cut> choose_cuts(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms,
                             const DecompositionOptions& opt, const SweepOptions& sweep, const skin::RunContext& run) {
  if (opt.slabs < 0) throw std::invalid_argument("choose_cuts: the slab count must be positive, or 0 (automatic)");
  const int slabs = opt.slabs == 0 ? automatic_slabs(skin.points().size(), ms, opt, sweep) : opt.slabs;
  std::vector<Cut> cuts;
  if (slabs == 1 || ms.critical.empty()) return cuts;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const morse::CriticalPoint& p : ms.critical) lo = std::min(lo, p.height), hi = std::max(hi, p.height);
  const double slab_height = (hi - lo) / slabs;
  // The targets: equal shares of the predicted work (work_profile()), and
  // equal parts of the critical heights' range. With balance_work the
  // candidates around the first come before those around the second: work
  // gathers where the skin's sections are widest, whose heights hold the
  // most critical points, and a target there may admit no cut (crambin at
  // probe 0 in 8 slabs kept 1 instead of 3 without them).
  std::vector<double> work_target;
  if (opt.balance_work) {
    const WorkProfile work = work_profile(skin, ms.height_direction.normalized(), run.threads);
    for (int i = 0; i < slabs; ++i)
      work_target.push_back(std::clamp(work.height_at(static_cast<double>(i) / slabs), lo, hi));
  }
  const int reach = static_cast<int>(std::floor(opt.search_reach / opt.search_step));
  const int per_target = 2 * reach + 1;
  const int candidates = opt.balance_work ? 2 * per_target : per_target;
  const CriticalByHeight by_height(ms, sweep.disc_factor);
  // Candidates from a target outwards: 0, +1, -1, +2, -2, … steps.
  auto candidate = [&](int i, int j) {
    const bool by_work = opt.balance_work && j < per_target;
    if (j >= per_target) j -= per_target;
    const int step = (j + 1) / 2 * (j % 2 ? 1 : -1);
    const double target = by_work ? work_target[static_cast<std::size_t>(i)] : lo + i * slab_height;
    return target + step * opt.search_step * slab_height;
  };
  // The level cut of target i: the first candidate, outwards from the
  // target, that is admissible and thick enough above `previous`.
  auto level_cut = [&](int i, const Cut* previous) -> std::optional<Cut> {
    for (int j = 0; j < candidates; ++j) {
      const double c = candidate(i, j);
      if (previous != nullptr && c <= previous->height) continue;
      if (!window_clear(ms, by_height, c, opt, sweep.disc_factor)) continue;
      Cut cut{c, {}, {}};
      try {
        cut.curves = morse::level_curves(skin, ms, c, opt.curves);
      } catch (const GeometryError&) {
        continue;  // the curve passes next to a critical point: not regular enough
      }
      if (cut.curves.empty() || !clear_of_spheres(ms, by_height, c, cut.curves, opt, sweep.disc_factor)) continue;
      if (previous != nullptr && !thick_enough(*previous, cut, opt, sweep.disc_factor)) continue;
      return cut;
    }
    return std::nullopt;
  };
  // Which targets get detoured cuts: every one with opt.detours; with
  // opt.detour_fallback, those without a level cut (the level walk, serial
  // and cheap, says which).
  std::vector<std::optional<Cut>> level(static_cast<std::size_t>(slabs));
  std::vector<char> detoured(static_cast<std::size_t>(slabs), opt.detours ? 1 : 0);
  if (!opt.detours) {
    const Cut* previous = nullptr;
    for (int i = 1; i < slabs; ++i) {
      std::optional<Cut>& cut = level[static_cast<std::size_t>(i)];
      cut = level_cut(i, previous);
      if (cut) previous = &*cut;
      detoured[static_cast<std::size_t>(i)] = !cut && opt.detour_fallback;
    }
  }
  // The first candidate of each detoured target that admits a cut is
  // traced for every such target at once, on the threads: which candidate
  // that is depends on its height alone. The walk below then takes it if it
  // lies above and apart from the cut before, as it would have reached it
  // one candidate after the other (every earlier candidate admits no cut),
  // and traces the later candidates only if it does not: the cuts are the
  // same for every thread count.
  std::vector<std::size_t> to_trace;
  for (int i = 1; i < slabs; ++i)
    if (detoured[static_cast<std::size_t>(i)]) to_trace.push_back(static_cast<std::size_t>(i));
  std::vector<std::pair<int, std::optional<Cut>>> first(static_cast<std::size_t>(slabs));
  parallel_for(to_trace.size(), thread_count(run.threads), 1, [&](std::size_t k) {
    const int i = static_cast<int>(to_trace[k]);
    for (int j = 0; j < candidates; ++j)
      if (std::optional<Cut> cut = detoured_cut(skin, ms, candidate(i, j), opt)) {
        first[static_cast<std::size_t>(i)] = {j, std::move(cut)};
        return;
      }
    first[static_cast<std::size_t>(i)] = {candidates, std::nullopt};
  });
  const Vec3 e = ms.height_direction.normalized();
  // A cut above `a` that is thick enough: by heights between level cuts, by
  // every sample where either detours.
  auto fits = [&](const Cut& a, const Cut& b) {
    return b.height > a.height && (a.detoured || b.detoured ? apart(a, b, e, opt, sweep.disc_factor)
                                                            : thick_enough(a, b, opt, sweep.disc_factor));
  };
  for (int i = 1; i < slabs; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (!detoured[k]) {
      // A level cut found above the level cut before it; a detoured cut
      // placed between them may leave it too close.
      if (level[k] && (cuts.empty() || fits(cuts.back(), *level[k]))) cuts.push_back(std::move(*level[k]));
      continue;
    }
    // The detoured cut fits below the next level cut as well: level cuts are
    // kept wherever the skin admits them.
    const Cut* next = nullptr;
    for (std::size_t m = k + 1; m < level.size() && next == nullptr; ++m)
      if (level[m]) next = &*level[m];
    for (int j = first[k].first; j < candidates; ++j) {
      const double c = candidate(i, j);
      if ((!cuts.empty() && c <= cuts.back().height) || (next != nullptr && c >= next->height)) continue;
      std::optional<Cut> cut = j == first[k].first ? std::move(first[k].second) : detoured_cut(skin, ms, c, opt);
      if (!cut || (!cuts.empty() && !fits(cuts.back(), *cut)) || (next != nullptr && !fits(*cut, *next))) continue;
      cuts.push_back(std::move(*cut));
      break;
    }
  }
  return cuts;
}

namespace {

/// The slabs between the kept cuts `live` (increasing), bottom to top.
std::vector<SlabKey> slab_keys(const std::vector<std::size_t>& live) {
  std::vector<SlabKey> keys;
  for (std::size_t k = 0; k <= live.size(); ++k)
    keys.emplace_back(k == 0 ? kNoCut : live[k - 1], k == live.size() ? kNoCut : live[k]);
  return keys;
}

/// The region of the slab `key` of `cuts`. `below[c]` says which critical
/// points lie below cut c (below_cut(); needed where a cut detours): a slab
/// between detoured cuts owns the points between.
Region slab_region(const morse::MorseSmaleComplex& ms, const std::vector<Cut>& cuts,
                   const std::vector<std::vector<char>>& below, const SlabKey& key, const DecompositionOptions& opt) {
  Region slab;
  slab.park_factor = opt.park_factor;
  const auto [lower, upper] = key;
  slab.holds_before_parking = opt.detours || (upper != kNoCut && cuts[upper].detoured);
  if (lower != kNoCut) slab.lower = cuts[lower].height, slab.lower_curves = cuts[lower].curves;
  if (upper != kNoCut) slab.upper = cuts[upper].height, slab.upper_curves = cuts[upper].curves;
  if ((lower != kNoCut && !cuts[lower].detours.empty()) || (upper != kNoCut && !cuts[upper].detours.empty())) {
    slab.owns.assign(ms.critical.size(), 1);
    for (std::size_t p = 0; p < ms.critical.size(); ++p)
      if ((upper != kNoCut && !below[upper][p]) || (lower != kNoCut && below[lower][p])) slab.owns[p] = 0;
    if (upper != kNoCut) slab.upper_detours = cuts[upper].detours;
  }
  return slab;
}

/// Per cut, which critical points lie below it (below_cut()), where some cut
/// detours; empty vectors otherwise.
std::vector<std::vector<char>> below_cuts(const std::vector<Cut>& cuts, const morse::MorseSmaleComplex& ms) {
  std::vector<std::vector<char>> below(cuts.size());
  if (std::any_of(cuts.begin(), cuts.end(), [](const Cut& c) { return !c.detours.empty(); }))
    for (std::size_t c = 0; c < cuts.size(); ++c) below[c] = below_cut(cuts[c], ms);
  return below;
}

/// The glued mesh of the slabs `keys` and the bands under the kept cuts
/// `live`, or where the glue failed: the position in `live` of the cut
/// whose band does not glue or whose seam is open or pinched, and why.
struct Glued {
  std::optional<SweepResult> mesh;
  /// The faces at the seams: the bands' triangles and the triangles around
  /// their corners (DecomposedSweep::seams).
  std::vector<geometry::Face> seams;
  std::vector<SlabCost> slabs;  ///< per slab, bottom to top
  std::size_t failed = 0;
  std::string why;
};

/// The glue: every slab's mesh appended in slab order, its vertex data with
/// it, then the bands' triangles on the shared vertices. The slabs' meshes
/// are taken from `swept` (erased as they are appended).
Glued glue(std::map<SlabKey, SlabOutcome>& swept, const std::vector<SlabKey>& keys,
           const std::vector<std::vector<Band>>& bands) {
  Glued out;
  SweepResult glued;
  // The lowest slab's mesh is taken as it is (garbage-collected, with the
  // vertex data as its only properties: what appending it to an empty mesh
  // would make, without a second copy of it at the peak); every other
  // slab's is appended and then freed, so the peak holds one copy of one
  // slab at a time.
  geometry::SurfaceMesh& mesh = glued.mesh;
  {
    std::size_t nv = 0, nf = 0;
    for (const SlabKey& key : keys) {
      const RegionResult& r = *swept.at(key).result;
      nv += r.mesh.vertices_size(), nf += r.mesh.faces_size();
    }
    for (const std::vector<Band>& cut_bands : bands)
      for (const Band& band : cut_bands) nf += band.triangles.size();
    SlabOutcome& lowest = swept.at(keys[0]);
    out.slabs.push_back({lowest.seconds, lowest.result->mesh.n_faces()});
    add_stats(glued.stats, lowest.result->stats);
    mesh = std::move(lowest.result->mesh);
    swept.erase(keys[0]);
    mesh.reserve(nv, nf);
  }
  std::vector<Index> base(keys.size(), 0);
  for (std::size_t k = 1; k < keys.size(); ++k) {
    SlabOutcome& o = swept.at(keys[k]);
    RegionResult& r = *o.result;
    out.slabs.push_back({o.seconds, r.mesh.n_faces()});
    add_stats(glued.stats, r.stats);
    base[k] = append_with_vertex_data(mesh, r.mesh);
    swept.erase(keys[k]);
  }
  // Each slab's mesh is a surface whose boundary is its lower curves'
  // samples and its rims, one rim per upper curve (sweep_region), and every
  // band covers its rim's and its curve's edges: only the bands' corners
  // can be left open or pinched, so only they are tested (the check of
  // the whole mesh later tests every vertex).
  std::vector<std::pair<geometry::Vertex, std::size_t>> seam;  // a band's corner, the cut's position in live
  for (std::size_t k = 0; k < bands.size(); ++k)
    for (const Band& band : bands[k])
      for (const std::array<BandVertex, 3>& t : band.triangles) {
        std::array<geometry::Vertex, 3> g;
        for (int i = 0; i < 3; ++i) {
          g[i] = geometry::Vertex(base[t[i].above ? k + 1 : k] + t[i].index);
          seam.emplace_back(g[i], k);
        }
        try {
          mesh.add_triangle(g[0], g[1], g[2]);
        } catch (const TopologyError& e) {
          out.failed = k;
          out.why = std::string("a band's triangle does not glue at the cut: ") + e.what();
          return out;
        }
      }
  for (const auto& [v, k] : seam)
    if (mesh.is_boundary(v) || !mesh.is_manifold(v)) {
      std::ostringstream os;
      os << "the glued mesh is " << (mesh.is_boundary(v) ? "open" : "not manifold") << " at ("
         << mesh.position(v).transpose() << ")";
      out.failed = k;
      out.why = os.str();
      return out;
    }
  for (const auto& [v, k] : seam)
    for (geometry::Face f : mesh.faces(v)) out.seams.push_back(f);
  std::sort(out.seams.begin(), out.seams.end(), [](geometry::Face a, geometry::Face b) { return a.idx() < b.idx(); });
  out.seams.erase(std::unique(out.seams.begin(), out.seams.end()), out.seams.end());
  out.mesh = std::move(glued);
  return out;
}

/// The slabs `keys` not refined yet, refined on up to run.threads threads
/// (refine_region()), and the vertices of `bands` (per kept cut, bottom to
/// top) renumbered with them. The refinement has no failure of its own: what
/// it throws is thrown, as from the pipeline's refinement of a whole mesh.
void refine_slabs(const skin::SkinSurface& skin, std::map<SlabKey, SlabOutcome>& swept,
                  const std::vector<SlabKey>& keys, std::vector<std::vector<Band>>& bands,
                  const DecompositionOptions& opt, const skin::RunContext& run) {
  std::vector<std::vector<Index>> to(keys.size());
  parallel_for(keys.size(), run.threads, 1, [&](std::size_t k) {
    if (SlabOutcome& o = swept.at(keys[k]); !o.refined) to[k] = refine_region(skin, o, opt, run);
  });
  for (std::size_t k = 0; k < bands.size(); ++k)
    for (Band& band : bands[k])
      for (std::array<BandVertex, 3>& t : band.triangles)
        for (BandVertex& v : t)
          if (const std::vector<Index>& map = to[v.above ? k + 1 : k]; !map.empty()) v.index = map[v.index];
}

/// The ladder's rung of regions: the slabs between `cuts` swept on the
/// threads, their bands closed and the whole glued. A slab that fails gives
/// up the cut above it (below it for the top slab, and the cut where it
/// failed for a failure at its lower cut); a band without a strip, or a glue
/// that fails, gives up its cut; the two slabs become one, swept again, the
/// others kept. Every cut given up goes to out.dropped with why; the costs
/// and the kept cuts go to `out`. Nothing when every cut was given up: the
/// next rung sweeps everything at once.
std::optional<SweepResult> sweep_regions(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms,
                                         const std::vector<Cut>& cuts, const DecompositionOptions& opt,
                                         const SweepOptions& sweep, const skin::RunContext& run,
                                         std::map<SlabKey, SlabOutcome> swept, DecomposedSweep& out) {
  const std::size_t n_cuts = cuts.size();
  // `swept`: every slab swept so far (given ones first), kept when a cut is
  // dropped since the slabs away from it stay as they were.
  std::vector<char> kept(n_cuts, 1);
  const auto drop = [&](std::size_t c, const std::string& why) {
    kept[c] = 0;
    out.dropped.push_back({cuts[c].height, why});
  };
  // Per cut, which critical points lie below it (for the slabs' ownership
  // where cuts detour).
  const std::vector<std::vector<char>> below = below_cuts(cuts, ms);
  // Per slab between two consecutive cuts (the slab under cut c is number c,
  // the top one n_cuts), the seconds its first sweep took: a merged slab of
  // a later round is predicted to take the sum of its parts, and a round's
  // slabs are handed out longest first, so that no long slab starts last
  // while the other threads have nothing left (the slabs of one round are
  // about equal in predicted work; those swept again after drops are not).
  std::vector<double> first_seconds(n_cuts + 1, 0.0);
  const auto elementary = [](const SlabKey& key) {
    const std::size_t first = key.first == kNoCut ? 0 : key.first + 1;
    return std::pair<std::size_t, std::size_t>{first, key.second == kNoCut ? std::size_t(-1) : key.second};
  };

  // The predicted seconds of a slab: the sum of its parts' first sweeps.
  const auto predict = [&](const SlabKey& key, const std::vector<double>& seconds) {
    const auto [first, last] = elementary(key);
    double s = 0;
    for (std::size_t e = first; e <= std::min(last, n_cuts); ++e) s += seconds[e];
    return s;
  };
  // Which cut a failed slab gives up (step 2 below).
  const auto cut_given_up = [](const SlabKey& key, const SlabOutcome& o) {
    return (o.at_lower_cut && key.first != kNoCut) || key.second == kNoCut ? key.first : key.second;
  };

  // The slabs' threads. A thread with no slab of the round left to start
  // sweeps ahead a merged slab a later round may ask for (the guess below).
  // Each slab's own region and the sweep's options, nothing else, make its
  // outcome.
  SlabPool pool(run.threads,
                [&](const SlabKey& key, const std::atomic<bool>& cancel, const std::function<void(double)>& progress) {
                  skin::RunContext slab_run = run.quiet();
                  slab_run.cancel = &cancel;
                  if (progress) slab_run.progress = [&progress](const std::string&, double f) { progress(f); };
                  return sweep_one(skin, ms, slab_region(ms, cuts, below, key, opt), sweep, slab_run);
                });
  const auto report = [&run](double f) {
    if (run.progress) run.progress("sweep", f);
  };
  // Bands closed while a round runs, as soon as their two slabs are done, on
  // the calling thread (which would otherwise wait), by their two slabs'
  // keys: a band depends on its two slabs only, so step 3 takes it from
  // here, and a band without a strip is known in time for the pool to sweep
  // the merged slab ahead. The slabs are refined only once their round
  // glues, so the bands' vertex indices hold until then.
  struct EarlyBand {
    std::vector<Band> bands;
    std::string error;
  };
  std::map<std::pair<SlabKey, SlabKey>, EarlyBand> early;
  std::mutex early_mutex;  // the guess reads `early` on the pool's threads
  double early_seconds = 0;

  for (;;) {
    std::vector<std::size_t> live;  // the kept cuts' indices, increasing
    for (std::size_t c = 0; c < n_cuts; ++c)
      if (kept[c]) live.push_back(c);
    if (live.empty()) return std::nullopt;
    const std::vector<SlabKey> keys = slab_keys(live);
    // A slab swept ahead that this round does not ask for is given up.
    pool.forget([&](const SlabKey& key) { return std::find(keys.begin(), keys.end(), key) != keys.end(); });

    // The slabs of dropped cuts are not needed any more: their time is lost.
    for (auto it = swept.begin(); it != swept.end();) {
      if (std::find(keys.begin(), keys.end(), it->first) != keys.end()) {
        ++it;
        continue;
      }
      out.costs.retried += it->second.seconds;
      it = swept.erase(it);
    }

    // 1. The slabs not swept yet.
    std::vector<SlabKey> todo;
    for (const SlabKey& key : keys)
      if (!swept.count(key)) todo.push_back(key);
    std::vector<double> predicted(todo.size(), 0.0);
    for (std::size_t i = 0; i < todo.size(); ++i) predicted[i] = predict(todo[i], first_seconds);
    std::vector<std::size_t> order(todo.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return predicted[a] > predicted[b]; });
    // The guess, asked when every slab of the round has started: first the
    // slabs of the cuts kept once the failures known so far, of slabs and of
    // bands, give up theirs (needed unless a slab still running fails beside
    // them), then, per slab still running, the slabs it would leave if
    // it failed at its upper cut (needed if it does: about one slab in five
    // fails on a large body, and a round's last slab is the one the next
    // round waits for). Each group longest first; only reads.
    const SlabPool::Guess guess = [&](const std::vector<const SlabOutcome*>& known) {
      std::vector<char> after = kept;
      std::vector<double> seconds = first_seconds;
      for (std::size_t i = 0; i < todo.size(); ++i) {
        if (!known[i]) continue;
        if (!known[i]->result) after[cut_given_up(todo[i], *known[i])] = 0;
        if (const auto [first, last] = elementary(todo[i]); first == std::min(last, n_cuts))
          seconds[first] = known[i]->seconds;
      }
      {
        const std::lock_guard<std::mutex> lock(early_mutex);
        for (std::size_t k = 0; k < live.size(); ++k)
          if (auto it = early.find({keys[k], keys[k + 1]}); it != early.end() && !it->second.error.empty())
            after[live[k]] = 0;
      }
      std::vector<SlabKey> ahead;
      const auto add_slabs = [&](const std::vector<char>& cuts_kept) {
        std::vector<std::size_t> left;
        for (std::size_t c = 0; c < n_cuts; ++c)
          if (cuts_kept[c]) left.push_back(c);
        const std::size_t from = ahead.size();
        for (const SlabKey& key : slab_keys(left))
          if (std::find(keys.begin(), keys.end(), key) == keys.end() &&
              std::find(ahead.begin(), ahead.end(), key) == ahead.end())
            ahead.push_back(key);
        std::stable_sort(ahead.begin() + static_cast<std::ptrdiff_t>(from), ahead.end(),
                         [&](const SlabKey& a, const SlabKey& b) { return predict(a, seconds) > predict(b, seconds); });
      };
      add_slabs(after);
      for (std::size_t i = 0; i < todo.size(); ++i)
        if (!known[i]) {
          std::vector<char> failed = after;
          failed[cut_given_up(todo[i], SlabOutcome{})] = 0;
          add_slabs(failed);
        }
      return ahead;
    };
    // The watch: the bands of the cuts whose two slabs are done.
    const SlabPool::Watch watch = [&](const std::vector<const SlabOutcome*>& known) {
      const auto outcome = [&](const SlabKey& key) -> const SlabOutcome* {
        if (auto it = swept.find(key); it != swept.end()) return &it->second;
        return known[static_cast<std::size_t>(std::find(todo.begin(), todo.end(), key) - todo.begin())];
      };
      for (std::size_t k = 0; k < live.size(); ++k) {
        const SlabOutcome *lower = outcome(keys[k]), *upper = outcome(keys[k + 1]);
        if (!lower || !upper || !lower->result || !upper->result) continue;
        const std::pair<SlabKey, SlabKey> pair{keys[k], keys[k + 1]};
        {
          const std::lock_guard<std::mutex> lock(early_mutex);
          if (early.count(pair)) continue;
        }
        const auto start = std::chrono::steady_clock::now();
        EarlyBand band;
        try {
          band.bands = close_bands(skin.mixed_complex(), *lower->result, *upper->result, cuts[live[k]].height);
        } catch (const TopologyError& e) {
          band.error = e.what();
        }
        early_seconds += seconds_since(start);
        const std::lock_guard<std::mutex> lock(early_mutex);
        early.emplace(pair, std::move(band));
      }
    };
    std::vector<SlabOutcome> fresh = pool.sweep(todo, order, guess, report, watch);
    for (std::size_t i = 0; i < todo.size(); ++i) {
      if (const auto [first, last] = elementary(todo[i]); first == std::min(last, n_cuts))
        first_seconds[first] = fresh[i].seconds;
      swept.emplace(todo[i], std::move(fresh[i]));
    }

    // 2. A slab that failed is merged with the slab above (the top one with
    // the slab below, and one that failed at its lower cut with the slab
    // below) by dropping the cut between them, and swept again.
    bool dropped = false;
    for (const SlabKey& key : keys) {
      const SlabOutcome& o = swept.at(key);
      if (o.result) continue;
      const std::size_t c = cut_given_up(key, o);
      if (!kept[c]) continue;  // the slab below dropped it already
      drop(c, o.error);
      dropped = true;
    }

    // 3. The bands: under each kept cut, each parked rim of the slab below
    // with its curve's samples in the slab above. In a round that dropped
    // cuts, only the cuts whose two slabs stay as they are: their band is
    // the one the next round would close, so a band without a strip is
    // dropped now and its slabs swept again in the same round as the failed
    // slabs' (what the round gains is one round's tail on the threads).
    const auto stays = [&](std::size_t k) {  // live[k]'s two slabs are kept as they are
      return kept[live[k]] && (k == 0 || kept[live[k - 1]]) && (k + 1 == live.size() || kept[live[k + 1]]);
    };
    std::vector<std::vector<Band>> bands(live.size());
    std::vector<std::string> band_error(live.size());
    const auto bands_start = std::chrono::steady_clock::now();
    parallel_for(live.size(), run.threads, 1, [&](std::size_t k) {
      if (!stays(k) || !swept.at(keys[k]).result || !swept.at(keys[k + 1]).result) return;
      if (auto it = early.find({keys[k], keys[k + 1]}); it != early.end()) {
        bands[k] = it->second.bands;  // a copy: a later round may take it again
        band_error[k] = it->second.error;
        return;
      }
      const RegionResult& lower = *swept.at(keys[k]).result;
      const RegionResult& upper = *swept.at(keys[k + 1]).result;
      try {
        bands[k] = close_bands(skin.mixed_complex(), lower, upper, cuts[live[k]].height);
      } catch (const TopologyError& e) {
        band_error[k] = e.what();
      }
    });
    const double bands_seconds = seconds_since(bands_start);
    for (std::size_t k = 0; k < live.size(); ++k)
      if (!band_error[k].empty()) drop(live[k], band_error[k]), dropped = true;
    if (dropped) {
      out.costs.retried += bands_seconds;
      continue;
    }
    // These slabs glue unless the glue fails: what is still swept ahead is
    // given up, its thread free for the regions' refinement.
    pool.forget([](const SlabKey&) { return false; });

    // 3b. The regions refined on the threads, once their bands are known
    // (a slab swept again after a drop is refined once, in the round that
    // glues), and the bands' vertices renumbered with them.
    if (opt.refine_regions) refine_slabs(skin, swept, keys, bands, opt, run);

    // 4. The glue. What the slabs' walks made of the complex goes back
    // first (no thread reads it now): the glue's copies are the sweep's peak.
    if (run.release_made_cells) skin.mixed_complex().release_made();
    refine::RefineStats refinement;
    for (const SlabKey& key : keys) refine::add_refine_stats(refinement, swept.at(key).refinement);
    const auto glue_start = std::chrono::steady_clock::now();
    Glued glued = glue(swept, keys, bands);
    if (!glued.mesh) {
      // Every slab went into the failed glue: all are swept again.
      for (const SlabCost& c : glued.slabs) out.costs.retried += c.seconds;
      out.costs.retried += bands_seconds + seconds_since(glue_start);
      swept.clear();
      early.clear();
      drop(live[glued.failed], "decomposed sweep: " + glued.why);
      continue;
    }
    out.costs.slabs = std::move(glued.slabs);
    out.region_refinement = refinement;
    out.costs.bands = bands_seconds + early_seconds;
    for (std::size_t c : live) {
      out.cut_heights.push_back(cuts[c].height);
      std::size_t balls = 0;
      for (const morse::CutDetour& d : cuts[c].detours) balls += d.balls.size();
      out.cut_balls.push_back(balls);
    }
    out.costs.glue = seconds_since(glue_start);
    if (opt.refine_regions) out.seams = std::move(glued.seams);
    out.costs.ahead_used = pool.ahead_used();
    out.costs.ahead_unused = pool.ahead_unused_seconds();
    return std::move(glued.mesh);
  }
}

}  // namespace

std::vector<SlabKey> slabs_between(std::size_t cuts) {
  std::vector<std::size_t> live(cuts);
  std::iota(live.begin(), live.end(), std::size_t{0});
  return slab_keys(live);
}

SlabOutcome sweep_slab(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const std::vector<Cut>& cuts,
                       const SlabKey& key, const DecompositionOptions& opt, const SweepOptions& sweep,
                       const skin::RunContext& run) {
  if ((key.first != kNoCut && key.first >= cuts.size()) || (key.second != kNoCut && key.second >= cuts.size()) ||
      (key.first != kNoCut && key.second != kNoCut && key.first >= key.second))
    throw std::invalid_argument("sweep_slab: no slab between cuts " + std::to_string(key.first) + " and " +
                                std::to_string(key.second) + " of " + std::to_string(cuts.size()));
  return sweep_one(skin, ms, slab_region(ms, cuts, below_cuts(cuts, ms), key, opt), sweep, run.quiet());
}

DecomposedSweep sweep_decomposed(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms,
                                 const std::vector<Cut>& cuts, const DecompositionOptions& opt,
                                 const SweepOptions& sweep, const skin::RunContext& context,
                                 std::map<SlabKey, SlabOutcome> swept) {
  DecomposedSweep out;
  // The observers and the trace see one slab at a time, in order.
  const int threads = sweep.observer || sweep.trace ? 1 : thread_count(context.threads);
  const skin::RunContext run = context.with_threads(threads);
  // The ladder, each rung's failure a value that sends the sweep to the
  // next: regions (merged where one fails), groups of whole components, one
  // sweep. The last rung's errors are thrown; the whole-skin fallback below
  // it is the pipeline's. An observer or a trace replays one front in one
  // mesh: they get the one sweep of everything.
  if (!cuts.empty())
    if (std::optional<SweepResult> regions = sweep_regions(skin, ms, cuts, opt, sweep, run, std::move(swept), out)) {
      out.sweep = std::move(*regions);
      return out;
    }
  if (opt.components && out.dropped.empty() && !sweep.observer && !sweep.trace)
    if (std::optional<SweepResult> groups = sweep_components(skin, ms, sweep, run, out.costs, out.components_fallback,
                                                             opt.glue_groups ? nullptr : &out.groups)) {
      out.sweep = std::move(*groups);
      return out;
    }
  out.sweep = sweep_mesh(skin, ms, sweep, run);
  return out;
}

}  // namespace skinmesh::decompose
