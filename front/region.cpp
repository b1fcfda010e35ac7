// front/region.cpp: the sweep of one region (front/region.h). The sweep's front is
// the boundary of its partial mesh, so a bare loop of cut-curve samples is no
// front: below each lower curve goes a ghost strip of triangles, which makes
// the curve the rim of a meshed part exactly like a bowl's. The ghosts are
// interior vertices (they never depart) that the collision net still sees;
// the strip is deleted at the end. Near the upper cut departure vertices are
// parked (sweep.cpp), and the seal leaves the parked rims open.
// Notes: papers/decompose/README.md ("The sweep of a region")
#include "front/region.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "core/errors.h"
#include "front/operations.h"
#include "geometry/triangulation/point_grid.h"

namespace skinmesh::front {
namespace detail {
namespace {

/// Depth of the ghost strip below a lower cut curve, over the sample's disc
/// radius r. [derived] Only the directions from a sample to its neighbours
/// and ghosts matter (its hole angle, the fold check), so the strip can be
/// shallow: the ghosts of neighbouring samples cross where the depth exceeds
/// the curve's radius of curvature in the tangent plane, which near a
/// saddle below the cut falls to a fraction of rho (HIV protease at probe
/// 1.4 folded at a depth of one r, 0.185 rho; a quarter of it does not).
constexpr double kGhostDepth = 0.25;

/// Adds the lower curves' samples as front vertices (in curve order, so that
/// they are the mesh's first vertices) and a ghost strip below each: one
/// ghost per sample, kGhostDepth · r down the skin's slope, and the faces
/// (p_j, p_j+1, g_j+1), (p_j, g_j+1, g_j). A curve oriented by n × e has
/// the skin below it on its left seen from outside, so these faces are
/// counter-clockwise and the half-edges p_j+1 -> p_j are the front's, with
/// the region on their left. Returns the ghost faces.
std::vector<Face> attach_lower_curves(FrontState& fs, const std::vector<morse::LevelCurve>& curves) {
  std::vector<std::vector<Vertex>> samples;
  for (const morse::LevelCurve& curve : curves) {
    std::vector<Vertex>& p = samples.emplace_back();
    for (std::size_t j = 0; j < curve.points.size(); ++j) p.push_back(new_vertex(fs, curve.points[j], curve.cells[j]));
  }
  std::vector<Face> ghost_faces;
  for (std::size_t ci = 0; ci < samples.size(); ++ci) {
    const std::vector<Vertex>& p = samples[ci];
    const morse::LevelCurve& curve = curves[ci];
    std::vector<Vertex> g;
    for (std::size_t j = 0; j < p.size(); ++j) {
      const Vertex x = p[j];
      // Down the slope: the tangent-plane direction of -e. A regular cut
      // (Region's precondition) keeps the skin's normal away from ±e there.
      // Next to a detour (an edge on a ball's circle) the cut is no level
      // curve: the ghost goes to the cut's left, n × t for its tangent t,
      // which is down the slope on a level curve. t bisects the directions
      // of the two edges at the sample: at a junction the curve turns by up
      // to about 125° between edges of unequal lengths, and a chord's
      // tangent there (p[j+1] - p[j-1]) turns the ghost past its
      // neighbour's and folds the strip.
      const Vec3 n = fs.normal[x];
      const std::size_t jp = (j + p.size() - 1) % p.size();
      const bool detoured =
          j < curve.detour.size() && (curve.detour[j] != kInvalidIndex || curve.detour[jp] != kInvalidIndex);
      Vec3 down = -(fs.e - fs.e.dot(n) * n);
      if (detoured) {
        const Vec3 t = (fs.mesh.position(p[(j + 1) % p.size()]) - fs.mesh.position(x)).normalized() +
                       (fs.mesh.position(x) - fs.mesh.position(p[jp])).normalized();
        down = n.cross(t - t.dot(n) * n);
      }
      if (!(down.norm() > 1e-6)) {
        std::ostringstream os;
        os << "region: the lower cut passes through a critical point near (" << fs.mesh.position(x).transpose()
           << "): the skin's normal is vertical there";
        throw LowerCutError(os.str());
      }
      Index cell = kInvalidIndex;
      const Vec3 q = project_tangent(fs, x, down.normalized(), kGhostDepth * fs.disc_radius(x), &cell);
      const Vertex gx = new_vertex(fs, q, cell);
      fs.set_state(gx, VState::Interior);
      g.push_back(gx);
    }
    for (Vertex gx : g) fs.region.mark(gx, RegionRole::Ghost, fs.mesh.vertices_size());
    const std::size_t k = p.size();
    for (std::size_t j = 0; j < k; ++j) {
      const std::size_t j1 = (j + 1) % k;
      const Vec3 pj = fs.mesh.position(p[j]);
      const Vec3 nt = (fs.mesh.position(p[j1]) - pj).cross(fs.mesh.position(g[j1]) - pj);
      if (!(nt.dot(fs.normal[p[j]]) > 0)) {
        std::ostringstream os;
        os << "region: the lower cut curve through (" << pj.transpose()
           << ") is not oriented as n x e (morse::level_curves), or its ghost strip folds";
        throw LowerCutError(os.str());
      }
      ghost_faces.push_back(fs.add_triangle(p[j], p[j1], g[j1]));
      ghost_faces.push_back(fs.add_triangle(p[j], g[j1], g[j]));
    }
    for (Vertex x : p) push(fs, x);
  }
  // The strips must not fold: each sample's tangent angles and hole angle make
  // a full turn, as at a bowl's rim.
  for (const std::vector<Vertex>& p : samples)
    for (Vertex x : p)
      if (std::abs(fold_excess(fs, x)) > fs.opt.fold_tolerance_deg * kDegree) {
        std::ostringstream os;
        os << "region: the ghost strip below the lower cut folds at (" << fs.mesh.position(x).transpose()
           << "): the cut curve bends more sharply than the strip is deep";
        throw LowerCutError(os.str());
      }
  return ghost_faces;
}

/// The nearest cut curve to a point, from a geometry::PointGrid over the
/// curves' samples with cells four disc radii wide (a rim lies within about
/// park_factor + 1 disc radii of its curve); a point with no sample that
/// near is compared with every sample.
class CurveLocator {
 public:
  CurveLocator(const std::vector<morse::LevelCurve>& curves, double disc_factor)
      : curves_(curves), reach_(std::max(4 * disc_factor * rho_max(curves), 1e-6)), grid_(reach_) {
    for (std::size_t k = 0; k < curves.size(); ++k)
      for (const Vec3& p : curves[k].points) {
        grid_.insert(static_cast<Index>(curve_of_.size()), p);
        curve_of_.push_back(k);
      }
  }
  /// The index of the curve with the sample nearest to x.
  std::size_t nearest(const Vec3& x) const {
    double best = std::numeric_limits<double>::infinity();
    std::size_t curve = curves_.size();
    grid_.for_each_near(x, reach_, [&](Index id, const Vec3& p) {
      if (const double d = (p - x).squaredNorm(); d < best) best = d, curve = curve_of_[id];
    });
    if (curve < curves_.size()) return curve;
    for (std::size_t k = 0; k < curves_.size(); ++k)
      for (const Vec3& p : curves_[k].points)
        if (const double d = (p - x).squaredNorm(); d < best) best = d, curve = k;
    return curve;
  }
  /// The curve nearest to most of the loop's vertices.
  std::size_t vote(const FrontState& fs, const std::vector<Vertex>& loop, std::size_t* votes_out = nullptr) const {
    std::vector<std::size_t> votes(curves_.size(), 0);
    for (Vertex x : loop) ++votes[nearest(fs.mesh.position(x))];
    const auto best = std::max_element(votes.begin(), votes.end());
    if (votes_out) *votes_out = *best;
    return static_cast<std::size_t>(best - votes.begin());
  }

 private:
  static double rho_max(const std::vector<morse::LevelCurve>& curves) {
    double r = 0;
    for (const morse::LevelCurve& c : curves)
      for (double rho : c.rho) r = std::max(r, rho);
    return r;
  }
  const std::vector<morse::LevelCurve>& curves_;
  double reach_;
  geometry::PointGrid grid_;
  std::vector<std::size_t> curve_of_;  ///< the curve of each sample, by its id in grid_
};

/// The open loops with a parked vertex and no ghost, each as its vertices.
std::vector<std::vector<Vertex>> parked_loops(const FrontState& fs) {
  std::vector<std::vector<Vertex>> loops;
  std::vector<char> seen(fs.mesh.vertices_size(), 0);
  for (Vertex v : fs.mesh.vertices()) {
    if (seen[v.idx()] || !fs.region.is_parked(v) || fs.mesh.is_isolated(v) || !fs.mesh.is_boundary(v)) continue;
    std::vector<Vertex> loop;
    bool ghost = false;
    for (Halfedge g : fs.mesh.boundary_loop(fs.mesh.halfedge(v))) {
      const Vertex x = fs.mesh.to_vertex(g);
      seen[x.idx()] = 1;
      ghost = ghost || fs.region.is_ghost(x);
      loop.push_back(x);
    }
    if (!ghost) loops.push_back(std::move(loop));
  }
  return loops;
}

/// Seals every open loop with parked vertices but the one per upper curve
/// that lies nearest to it (the most votes of its vertices' nearest samples;
/// ties: the longer loop). The others are holes the front pinched off in
/// the band, with no critical point inside: discs, sealed like any hole.
void seal_stray_rims(FrontState& fs, const CurveLocator& locator, std::size_t n_curves) {
  const std::vector<std::vector<Vertex>> loops = parked_loops(fs);
  std::vector<std::size_t> keep(n_curves, loops.size()), keep_votes(n_curves, 0);
  for (std::size_t i = 0; i < loops.size(); ++i) {
    std::size_t votes = 0;
    const std::size_t k = locator.vote(fs, loops[i], &votes);
    if (keep[k] == loops.size() || votes > keep_votes[k] ||
        (votes == keep_votes[k] && loops[i].size() > loops[keep[k]].size()))
      keep[k] = i, keep_votes[k] = votes;
  }
  std::vector<char> kept(loops.size(), 0);
  for (std::size_t k = 0; k < n_curves; ++k)
    if (keep[k] < loops.size()) kept[keep[k]] = 1;
  for (std::size_t i = 0; i < loops.size(); ++i) {
    if (kept[i]) continue;
    const Vertex x = loops[i].front();
    // An earlier seal's enlargement may have closed it already.
    if (fs.mesh.is_deleted(x) || fs.mesh.is_isolated(x) || !fs.mesh.is_boundary(x)) continue;
    const std::size_t f0 = fs.mesh.faces_size(), seals = fs.stats.seals;
    seal_loop(fs, fs.mesh.halfedge(x), fs.opt.max_hole_enlargements);
    if (fs.stats.seals > seals) fs.notify(SweepOperation::Seal, Vertex(), kInvalidIndex, f0);
  }
}

/// Closes the sharp corners of the parked rims by wings (front angle below
/// 90°, Figure 7), as the sweep would have had their vertices departed: a
/// rim that turns back on itself (a zigzag the last creeps left) has an edge
/// that no outward triangle can join to the cut curve, and the band's strip
/// would not exist.
void wing_rims(FrontState& fs) {
  for (const std::vector<Vertex>& loop : parked_loops(fs))
    for (Vertex x : loop) {
      fs.set_state(x, VState::Front);
      fs.wing_worklist.push_back(x);
    }
  drain_wings(fs);
}

}  // namespace
}  // namespace detail

SweepResult sweep_mesh(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const Region& region,
                       const SweepOptions& opt, const skin::RunContext& run) {
  if (std::isfinite(region.lower) || std::isfinite(region.upper) || !region.lower_curves.empty() ||
      !region.upper_curves.empty() || !region.upper_detours.empty())
    throw std::invalid_argument("sweep_mesh: a region with cuts is swept by sweep_region");
  if (!region.owns.empty() && region.owns.size() != ms.critical.size())
    throw std::invalid_argument("sweep_mesh: `owns` needs one entry per critical point");
  detail::FrontState fs(skin, ms, opt, run, region);
  return detail::run_sweep(fs);
}

RegionResult sweep_region(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const Region& region,
                          const SweepOptions& opt, const skin::RunContext& run) {
  using namespace detail;
  if (!(region.lower < region.upper))
    throw std::invalid_argument("sweep_region: the lower cut must lie below the upper cut");
  if (!(region.park_factor >= 1)) throw std::invalid_argument("sweep_region: park_factor must be at least 1");
  std::size_t n_samples = 0;
  for (const morse::LevelCurve& c : region.lower_curves) {
    if (c.points.size() < 3 || c.cells.size() != c.points.size() || c.rho.size() != c.points.size())
      throw std::invalid_argument(
          "sweep_region: a lower curve needs at least three samples, each with its cell and rho");
    // A sample within park_factor · r of the upper cut would be parked at
    // once: the region would have no triangle there, only the band.
    for (double rho : c.rho)
      if (region.lower + (region.park_factor + 1) * opt.disc_factor * rho > region.upper) {
        std::ostringstream os;
        os << "sweep_region: the region [" << region.lower << ", " << region.upper
           << "] is thinner than park_factor + 1 = " << region.park_factor + 1 << " disc radii ("
           << (region.park_factor + 1) * opt.disc_factor * rho << " A) at a sample of its lower curves";
        throw std::invalid_argument(os.str());
      }
    n_samples += c.points.size();
  }
  if (!region.owns.empty() && region.owns.size() != ms.critical.size())
    throw std::invalid_argument("sweep_region: `owns` needs one entry per critical point");
  const bool detours = std::any_of(region.upper_detours.begin(), region.upper_detours.end(),
                                   [](const morse::CutDetour& d) { return !d.balls.empty(); });
  if (detours && region.upper_curves.empty())
    throw std::invalid_argument("sweep_region: an upper cut with detours needs its curves");
  FrontState fs(skin, ms, opt, run, region);
  const std::vector<Face> ghost_faces = attach_lower_curves(fs, region.lower_curves);
  create_initial_front(fs);
  sweep_and_seal(fs);
  std::optional<CurveLocator> locator;
  if (!region.upper_curves.empty()) {
    locator.emplace(region.upper_curves, opt.disc_factor);
    seal_stray_rims(fs, *locator, region.upper_curves.size());
  }
  wing_rims(fs);

  // The ghost strips must have survived the repairs of the front: a
  // re-opened, enlarged or patched region that reached below the lower cut
  // would have changed the region's boundary.
  for (Face f : ghost_faces)
    if (fs.mesh.is_deleted(f))
      throw LowerCutError("region: a repair of the front reached below the lower cut (a ghost face was deleted)");
  for (Face f : ghost_faces) fs.mesh.delete_face(f);

  // The boundary: each lower curve one loop, every other loop a parked rim.
  RegionResult res;
  std::vector<Index> curve_of(n_samples, kInvalidIndex);
  {
    Index next = 0;
    for (std::size_t k = 0; k < region.lower_curves.size(); ++k) {
      std::vector<Index>& loop = res.lower_loops.emplace_back();
      for (std::size_t j = 0; j < region.lower_curves[k].points.size(); ++j, ++next)
        loop.push_back(next), curve_of[next] = static_cast<Index>(k);
    }
  }
  std::vector<char> curve_seen(region.lower_curves.size(), 0);
  std::vector<std::vector<Vertex>> rims;
  for (const std::vector<Halfedge>& loop : fs.mesh.boundary_loops()) {
    const Index k0 = fs.mesh.to_vertex(loop.front()).idx() < n_samples ? curve_of[fs.mesh.to_vertex(loop.front()).idx()]
                                                                       : kInvalidIndex;
    bool whole_curve = k0 != kInvalidIndex && loop.size() == res.lower_loops[k0].size() && !curve_seen[k0];
    bool parked = false;
    for (Halfedge h : loop) {
      const Vertex x = fs.mesh.to_vertex(h);
      if (x.idx() >= n_samples || curve_of[x.idx()] != k0) whole_curve = false;
      if (fs.region.is_parked(x)) parked = true;
    }
    if (whole_curve) {
      curve_seen[k0] = 1;
      continue;
    }
    if (!parked) {
      std::ostringstream os;
      os << "region: a hole of " << loop.size() << " vertices near ("
         << fs.mesh.position(fs.mesh.to_vertex(loop.front())).transpose()
         << ") was left open: it is neither a lower cut curve nor a parked rim";
      throw TopologyError(os.str());
    }
    std::vector<Vertex>& rim = rims.emplace_back();
    for (Halfedge h : loop) rim.push_back(fs.mesh.to_vertex(h));
  }
  for (std::size_t k = 0; k < curve_seen.size(); ++k)
    if (!curve_seen[k])
      throw LowerCutError("region: a lower cut curve is no longer one boundary loop of the region's mesh");
  if (locator) {
    std::vector<int> rims_of(region.upper_curves.size(), 0);
    for (const std::vector<Vertex>& rim : rims) ++rims_of[res.rim_curve.emplace_back(locator->vote(fs, rim))];
    for (std::size_t k = 0; k < rims_of.size(); ++k)
      if (rims_of[k] != 1) {
        std::ostringstream os;
        const morse::LevelCurve& c = region.upper_curves[k];
        const bool island = !c.detour.empty() &&
                            std::all_of(c.detour.begin(), c.detour.end(), [](Index d) { return d != kInvalidIndex; });
        os << "region: the upper cut curve through (" << c.points.front().transpose() << ") has " << rims_of[k]
           << " parked rims below it instead of one" << (island ? " (a loop around balls only, " : " (")
           << c.points.size() << " samples)";
        throw TopologyError(os.str());
      }
  }

  // Garbage collection keeps the order of the surviving vertices, and the
  // samples (the first vertices) survive: a vertex's new index is its old one
  // less the deleted vertices before it.
  std::vector<Index> new_index(fs.mesh.vertices_size(), kInvalidIndex);
  {
    Index next = 0;
    for (std::size_t i = 0; i < new_index.size(); ++i)
      if (!fs.mesh.is_deleted(Vertex(static_cast<Index>(i)))) new_index[i] = next++;
  }
  for (const std::vector<Vertex>& rim : rims) {
    std::vector<Index>& out = res.upper_rims.emplace_back();
    for (Vertex x : rim) out.push_back(new_index[x.idx()]);
  }
  for (std::size_t i = 0; i < fs.region.role.size(); ++i)
    if (fs.region.role[i] == RegionRole::Parked && !fs.mesh.is_deleted(Vertex(static_cast<Index>(i)))) ++res.parked;
  drop_sweep_properties(fs);
  fs.mesh.garbage_collection();
  res.mesh = std::move(fs.mesh);
  res.stats = fs.stats;
  return res;
}

}  // namespace skinmesh::front
