// front/decomposed.cpp: the cut choice and the glue of the decomposed sweep
// (front/decomposed.h). Every slab's mesh keeps its own vertices; the cut
// samples are vertices of the slab above (its first ones, in curve order),
// which the band below reuses, so the glued mesh shares them exactly.
// Notes: papers/mesher/decomposition.md ("Increments", 4)
#include "front/decomposed.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/errors.h"
#include "front/band.h"
#include "skin/vertex_data.h"

namespace skinmesh::front {
namespace {

/// True if no critical point lies in the height window that the cut at c
/// forbids it (DecompositionOptions::window_below, window_above).
bool window_clear(const morse::MorseSmaleComplex& ms, double c, const DecompositionOptions& opt, double disc_factor) {
  for (std::size_t i = 0; i < ms.critical.size(); ++i) {
    const morse::CriticalPoint& p = ms.critical[i];
    const double r = disc_factor * p.rho;
    if (p.height >= c - opt.window_below * r && p.height <= c + opt.window_above * r) return false;
  }
  return true;
}

/// True if every sample of `curves` lies sphere_margin disc radii outside
/// every live protecting sphere.
bool clear_of_spheres(const morse::MorseSmaleComplex& ms, double c, const std::vector<morse::LevelCurve>& curves,
                      const DecompositionOptions& opt, double disc_factor) {
  double rho_max = 0;
  for (const morse::LevelCurve& curve : curves)
    for (double rho : curve.rho) rho_max = std::max(rho_max, rho);
  const double reach = opt.sphere_margin * disc_factor * rho_max;
  for (std::size_t i = 0; i < ms.critical.size(); ++i) {
    if (i >= ms.live.size() || !ms.live[i] || i >= ms.protect_radius.size()) continue;
    const double s = ms.protect_radius[i];
    const morse::CriticalPoint& p = ms.critical[i];
    // A sample is at least |h(p) - c| from p: only the spheres near the
    // plane can come within the margin.
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

void add_stats(SweepStats& a, const SweepStats& b) {
  a.creations += b.creations, a.creeps += b.creeps, a.wings += b.wings, a.bridges += b.bridges;
  a.seals += b.seals, a.held += b.held, a.deferred += b.deferred, a.bridge_rows += b.bridge_rows;
  a.contacts += b.contacts, a.stuck += b.stuck, a.enlarged_holes += b.enlarged_holes;
  a.reopened_holes += b.reopened_holes, a.collisions += b.collisions, a.released += b.released;
  a.merged_minima += b.merged_minima, a.left_holes += b.left_holes, a.folds += b.folds;
  a.patched_holes += b.patched_holes, a.patch_faces += b.patch_faces, a.parked += b.parked;
}

/// The glued mesh under construction: positions, triangles and the skin's
/// data per vertex.
struct Soup {
  geometry::IndexedMesh mesh;
  std::vector<Vec3> normal;
  std::vector<double> rho;
  std::vector<Index> cell;
};

}  // namespace

std::vector<Cut> choose_cuts(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms,
                             const DecompositionOptions& opt, const SweepOptions& sweep) {
  if (opt.slabs < 1) throw std::invalid_argument("choose_cuts: at least one slab");
  std::vector<Cut> cuts;
  if (opt.slabs == 1 || ms.critical.empty()) return cuts;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const morse::CriticalPoint& p : ms.critical) lo = std::min(lo, p.height), hi = std::max(hi, p.height);
  const double slab_height = (hi - lo) / opt.slabs;
  const int reach = static_cast<int>(std::floor(opt.search_reach / opt.search_step));
  for (int i = 1; i < opt.slabs; ++i) {
    const double target = lo + i * slab_height;
    // Candidates from the target outwards: 0, +1, -1, +2, -2, … steps.
    for (int j = 0; j <= 2 * reach; ++j) {
      const int step = (j + 1) / 2 * (j % 2 ? 1 : -1);
      const double c = target + step * opt.search_step * slab_height;
      if (!cuts.empty() && c <= cuts.back().height) continue;
      if (!window_clear(ms, c, opt, sweep.disc_factor)) continue;
      Cut cut{c, {}};
      try {
        cut.curves = morse::level_curves(skin, ms, c, opt.curves);
      } catch (const GeometryError&) {
        continue;  // the curve passes next to a critical point: not regular enough
      }
      if (cut.curves.empty() || !clear_of_spheres(ms, c, cut.curves, opt, sweep.disc_factor)) continue;
      if (!cuts.empty() && !thick_enough(cuts.back(), cut, opt, sweep.disc_factor)) continue;
      cuts.push_back(std::move(cut));
      break;
    }
  }
  return cuts;
}

SweepResult sweep_decomposed(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms,
                             const std::vector<Cut>& cuts, const DecompositionOptions& opt, const SweepOptions& sweep) {
  if (cuts.empty()) return sweep_mesh(skin, ms, sweep);
  const std::size_t n_cuts = cuts.size();
  Soup soup;
  SweepResult out;
  // ids[c][k][j]: the glued mesh's vertex of sample j of curve k of cut c.
  std::vector<std::vector<std::vector<Index>>> ids(n_cuts);
  // rims[s]: the parked rims of slab s (below cut s), as glued vertices;
  // rim_curve[s]: the curve of cut s that each bounds the band with.
  std::vector<std::vector<std::vector<Index>>> rims(n_cuts);
  std::vector<std::vector<std::size_t>> rim_curve(n_cuts);

  for (std::size_t s = 0; s <= n_cuts; ++s) {
    Slab slab;
    slab.park_factor = opt.park_factor;
    if (s > 0) slab.lower = cuts[s - 1].height, slab.lower_curves = cuts[s - 1].curves;
    if (s < n_cuts) slab.upper = cuts[s].height, slab.upper_curves = cuts[s].curves;
    SweepOptions slab_sweep = sweep;
    if (sweep.progress)
      slab_sweep.progress = [&sweep, s, n_cuts](const std::string& stage, double f) {
        sweep.progress(stage, (static_cast<double>(s) + f) / static_cast<double>(n_cuts + 1));
      };
    SlabResult r = sweep_slab(skin, ms, slab, slab_sweep);
    add_stats(out.stats, r.stats);

    const auto normal = r.mesh.get_vertex_property(skin::kVertexNormal);
    const auto rho = r.mesh.get_vertex_property(skin::kVertexRho);
    const auto cell = r.mesh.get_vertex_property(skin::kVertexCell);
    std::vector<Index> glued(r.mesh.vertices_size(), kInvalidIndex);
    for (geometry::Vertex v : r.mesh.vertices()) {
      glued[v.idx()] = static_cast<Index>(soup.mesh.positions.size());
      soup.mesh.positions.push_back(r.mesh.position(v));
      soup.normal.push_back(normal[v]);
      soup.rho.push_back(rho[v]);
      soup.cell.push_back(cell[v]);
    }
    if (s > 0)
      for (const std::vector<Index>& loop : r.lower_loops) {
        std::vector<Index>& g = ids[s - 1].emplace_back();
        for (Index v : loop) g.push_back(glued[v]);
      }
    for (geometry::Face f : r.mesh.faces()) {
      std::array<Index, 3> t{};
      geometry::Halfedge h = r.mesh.halfedge(f);
      for (int i = 0; i < 3; ++i, h = r.mesh.next(h)) t[i] = glued[r.mesh.from_vertex(h).idx()];
      soup.mesh.triangles.push_back(t);
    }
    if (s < n_cuts) {
      for (const std::vector<Index>& rim : r.upper_rims) {
        std::vector<Index>& g = rims[s].emplace_back();
        for (Index v : rim) g.push_back(glued[v]);
      }
      rim_curve[s] = std::move(r.rim_curve);
    }
  }

  // The bands: each parked rim with its cut curve (one rim per curve,
  // sweep_slab's match), by the max-min-angle strip.
  for (std::size_t c = 0; c < n_cuts; ++c) {
    const std::vector<std::size_t>& match = rim_curve[c];
    for (std::size_t i = 0; i < rims[c].size(); ++i) {
      const std::vector<Index>& curve = ids[c][match[i]];
      // The strip starts at rim vertex 0 and the curve sample nearest to it;
      // where that sample lies across a narrow gap (another stretch of the
      // same curve), no outward strip starts there: the rim is tried from
      // other starts, a quarter of it apart, before the band is given up.
      std::vector<Index> rim;
      std::vector<StripTriangle> strip;
      for (int attempt = 0; attempt < 4 && strip.empty(); ++attempt) {
        const std::vector<Index>& whole = rims[c][i];
        const std::size_t shift = attempt * whole.size() / 4;
        rim.assign(whole.begin() + static_cast<std::ptrdiff_t>(shift), whole.end());
        rim.insert(rim.end(), whole.begin(), whole.begin() + static_cast<std::ptrdiff_t>(shift));
        std::vector<Vec3> a, an, b, bn;
        for (Index v : rim) a.push_back(soup.mesh.positions[v]), an.push_back(soup.normal[v]);
        for (Index v : curve) b.push_back(soup.mesh.positions[v]), bn.push_back(soup.normal[v]);
        // The corridor: a few dozen edges of slack in arc-length fraction.
        const double corridor = std::min(1.0, 24.0 / static_cast<double>(std::min(a.size(), b.size())));
        strip = strip_triangulation(a, an, b, bn, corridor);
      }
      if (strip.empty()) {
        std::ostringstream os;
        os << "decomposed sweep: the band between a parked rim and the cut curve at height " << cuts[c].height
           << " through (" << soup.mesh.positions[curve.front()].transpose() << ") has no outward strip";
        throw TopologyError(os.str());
      }
      const Index n_rim = static_cast<Index>(rim.size());
      for (const StripTriangle& t : strip) {
        std::array<Index, 3> g{};
        for (int k = 0; k < 3; ++k) g[k] = t[k] < n_rim ? rim[t[k]] : curve[t[k] - n_rim];
        soup.mesh.triangles.push_back(g);
      }
    }
  }

  out.mesh = geometry::SurfaceMesh::from_indexed_mesh(soup.mesh);
  for (geometry::Vertex v : out.mesh.vertices())
    if (out.mesh.is_boundary(v)) {
      std::ostringstream os;
      os << "decomposed sweep: the glued mesh is open at (" << out.mesh.position(v).transpose() << ")";
      throw TopologyError(os.str());
    }
  auto normal = out.mesh.add_vertex_property(skin::kVertexNormal, Vec3::Zero());
  auto rho = out.mesh.add_vertex_property(skin::kVertexRho, 0.0);
  auto cell = out.mesh.add_vertex_property(skin::kVertexCell, kInvalidIndex);
  for (geometry::Vertex v : out.mesh.vertices()) {
    normal[v] = soup.normal[v.idx()];
    rho[v] = soup.rho[v.idx()];
    cell[v] = soup.cell[v.idx()];
  }
  return out;
}

}  // namespace skinmesh::front
