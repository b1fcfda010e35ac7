// front/patch.cpp: patch_hole(), the sweep's fallback where the front tangles
// (not in the paper). The faces of a region around a hole that the seal cannot
// close are removed and the region is re-meshed by the restricted Delaunay
// triangulation of a sample of the skin, conforming to the region's boundary
// loop: the vertices around the region stay as fixed samples, the region's own
// vertices are the free ones, and surface Delaunay centres are inserted until
// the restricted facets inside the loop form one embedded piece of surface
// that meets [U] and joins the rest edge for edge. The region grows by rings
// of faces until that holds.
// Notes: papers/front/patch.md
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <unordered_map>

#include <Eigen/Geometry>

#include "core/errors.h"
#include "front/operations.h"
#include "geometry/kernel/triangle_intersection.h"
#include "geometry/triangulation/delaunay_triangulation.h"
#include "skin/size_conditions.h"

namespace skinmesh::front::detail {

namespace {

using geometry::DelaunayTriangulation;

/// The largest number of rings of faces around the hole that the region grows
/// to when no local growth is asked for (1, 2, 3, 4, 6, 9, then stop), and the
/// attempts in all. [measured] the cage-in-shell holes close after a few
/// local growths of a one-ring region; 12 rings are about 2 rho, far beyond
/// any tangle the stress inputs make.
constexpr int kMaxRings = 12;
constexpr int kMaxAttempts = 24;
/// Rings of kept vertices around the region that are fixed samples: they make
/// the Delaunay triangulation near the loop that of the kept mesh's side too.
/// [measured]
constexpr int kGuardRings = 2;
/// Free samples closer than this times the disc radius to an accepted sample
/// are dropped: the region's old vertices may lie on two overlapping sheets.
/// [derived] 0.55 r > 0.52 r, the shortest edge [L] allows with the default
/// constants (2 C/Q rho = 0.097 rho over r = 0.185 rho).
constexpr double kThinning = 0.55;
/// Refinement rounds per attempt, and the insertions allowed per free sample
/// or loop edge of the region (plus a floor): the bounds that keep the
/// fallback from running on. [measured]
constexpr int kMaxRounds = 40;
constexpr std::size_t kInsertionsPerSample = 8, kInsertionFloor = 256;
/// Bisection steps of the surface Delaunay centre on its dual Voronoi edge
/// (2^-60 of the edge, far below rounding). [derived]
constexpr int kBisectionSteps = 60;

/// A sample of the region's restricted Delaunay triangulation.
struct Sample {
  Vec3 p;
  Index cell = kInvalidIndex;
  double rho = 0;
  Vec3 normal = Vec3::Zero();
  Vertex v;           ///< the mesh vertex of a fixed sample; invalid for a free one
  bool loop = false;  ///< a fixed sample on the region's boundary loop
};

/// A restricted facet (a, b, c) counter-clockwise seen from outside, with the
/// tetrahedra inside (circumcentre with f < 0) and outside it.
struct RFacet {
  std::array<Index, 3> s;  ///< sample indices
  Index inner, outer;
};

std::uint64_t edge_key(Index a, Index b) { return (static_cast<std::uint64_t>(a) << 32) | b; }

/// The region's patch problem at one growth level.
class Patcher {
 public:
  /// `hull_lo`, `hull_hi`: a box holding every atom's unshrunk ball (Å),
  /// outside which f > 0.
  Patcher(FrontState& fs, std::vector<Face> region, const Vec3& hull_lo, const Vec3& hull_hi)
      : fs_(fs), region_(std::move(region)), hull_lo_(hull_lo), hull_hi_(hull_hi) {}

  /// True if the region's patch was found; then apply() glues it in.
  bool solve();
  /// Replaces the region's faces by the patch; returns the faces added.
  std::size_t apply();
  /// Why solve() failed.
  const std::string& why() const { return why_; }
  /// Where the region should grow after a failed solve(): the kept vertices
  /// that the restricted facets of the hole reached, and the ends of loop
  /// edges that are not restricted Delaunay edges (may be empty).
  std::vector<Vertex> grow_at() const {
    std::vector<Vertex> g = grow_at_;
    g.insert(g.end(), loose_.begin(), loose_.end());
    return g;
  }

 private:
  bool collect_samples();
  Index add_free(const Vec3& p, Index cell, double rho, const Vec3& n);
  void classify();
  /// Flood fill of the restricted facets from the loop; fills patch_ and
  /// trouble_ (facets whose surface Delaunay centre may help). True if the
  /// patch closes against the loop.
  bool extract();
  bool valid_geometry() const;
  bool surface_centre(const RFacet& f, Vec3& x, Index& cell) const;

  FrontState& fs_;
  std::vector<Face> region_;  // sorted
  std::vector<Sample> samples_;
  std::unordered_map<Index, Index> sample_of_vertex_;  // mesh vertex index -> sample
  std::vector<Index> dt_sample_;                       // Delaunay id -> sample (kInvalidIndex: bounding)
  std::vector<std::array<Index, 2>> loop_;             // directed loop edges the patch must hold (samples)
  std::vector<Face> kept_near_;                        // kept faces at the fixed samples (embedding test)
  std::unique_ptr<DelaunayTriangulation> dt_;
  std::vector<double> value_;  // per tetrahedron: f at its circumcentre
  std::vector<Vec3> cc_;
  std::vector<RFacet> facets_;
  std::vector<Index> patch_, trouble_;
  std::vector<Vertex> grow_at_, loose_;
  std::size_t free_count_ = 0;
  std::string why_;
  const Vec3 hull_lo_, hull_hi_;
};

bool Patcher::collect_samples() {
  const SurfaceMesh& mesh = fs_.mesh;
  auto in_region = [&](Face f) { return std::binary_search(region_.begin(), region_.end(), f); };
  // The region's vertices: interior ones (every face in the region) are free,
  // the others are on its boundary loop. A vertex whose kept faces are not one
  // fan would be pinched: the region must grow.
  std::vector<Vertex> corners;
  for (Face f : region_)
    for (Vertex x : mesh.vertices(f)) corners.push_back(x);
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  std::vector<Vertex> loop_vertices, interior;
  // Every pinched corner and every vertex the open side reaches outside the
  // region is where the region must grow (grow_at): all of them at once, so
  // that one growth clears them.
  grow_at_.clear();
  for (Vertex x : corners) {
    int runs = 0, slots = 0, kept = 0;
    bool prev = false, first = false;
    for (Halfedge h : mesh.halfedges(x)) {
      const bool open = mesh.is_boundary(h) || in_region(mesh.face(h));
      if (slots == 0)
        first = open;
      else if (open && !prev)
        ++runs;
      prev = open, ++slots, kept += !open;
    }
    if (first && !prev) ++runs;
    if (kept == 0) {
      interior.push_back(x);
    } else {
      if (runs != 1) grow_at_.push_back(x);  // pinched
      loop_vertices.push_back(x);
    }
  }
  if (!grow_at_.empty()) return false;
  auto add_fixed = [&](Vertex x, bool loop) {
    if (sample_of_vertex_.count(x.idx())) return;
    Sample s;
    s.p = mesh.position(x), s.cell = fs_.cell[x], s.rho = fs_.rho[x], s.normal = fs_.normal[x], s.v = x;
    s.loop = loop;
    sample_of_vertex_.emplace(x.idx(), static_cast<Index>(samples_.size()));
    samples_.push_back(s);
  };
  for (Vertex x : loop_vertices) add_fixed(x, true);
  // The loop's directed edges: a kept face's half-edge whose twin is open
  // (boundary or in the region) is glued to a patch facet holding its reverse.
  for (Vertex x : loop_vertices)
    for (Halfedge h : mesh.halfedges(x)) {
      // h: x -> y; the kept face on the left of h, the open side on the left of its twin.
      if (mesh.is_boundary(h) || in_region(mesh.face(h))) continue;
      const Halfedge t = mesh.opposite(h);
      if (!(mesh.is_boundary(t) || in_region(mesh.face(t)))) continue;
      const Vertex y = mesh.to_vertex(h);
      if (!sample_of_vertex_.count(y.idx())) {  // the open side reaches a vertex outside the region
        grow_at_.push_back(y);
        continue;
      }
      loop_.push_back({sample_of_vertex_[y.idx()], sample_of_vertex_[x.idx()]});
    }
  if (!grow_at_.empty() || loop_.empty()) return false;
  // Guards: the kept vertices kGuardRings rings around the loop.
  std::vector<Vertex> ring = loop_vertices;
  for (int r = 0; r < kGuardRings; ++r) {
    std::vector<Vertex> next;
    for (Vertex x : ring)
      for (Face f : mesh.faces(x)) {
        if (in_region(f)) continue;
        kept_near_.push_back(f);
        for (Vertex y : mesh.vertices(f))
          if (!sample_of_vertex_.count(y.idx())) {
            add_fixed(y, false);
            next.push_back(y);
          }
      }
    ring.swap(next);
  }
  std::sort(kept_near_.begin(), kept_near_.end());
  kept_near_.erase(std::unique(kept_near_.begin(), kept_near_.end()), kept_near_.end());
  // Free samples: the region's interior vertices, thinned.
  for (Vertex x : interior) {
    const Vec3& p = mesh.position(x);
    const double d = kThinning * fs_.disc_radius(x);
    bool near = false;
    for (const Sample& s : samples_)
      if ((s.p - p).squaredNorm() < d * d) {
        near = true;
        break;
      }
    if (!near) add_free(p, fs_.cell[x], fs_.rho[x], fs_.normal[x]);
  }
  return true;
}

Index Patcher::add_free(const Vec3& p, Index cell, double rho, const Vec3& n) {
  Sample s;
  s.p = p, s.cell = cell, s.rho = rho, s.normal = n;
  samples_.push_back(s);
  ++free_count_;
  return static_cast<Index>(samples_.size() - 1);
}

void Patcher::classify() {
  value_.assign(dt_->tet_capacity(), 1.0);
  cc_.assign(dt_->tet_capacity(), Vec3::Zero());
  dt_->for_each_tet([&](Index t) {
    const auto& v = dt_->tet(t);
    const Vec3 c = dt_->circumcentre(t);
    cc_[t] = c;
    // Outside the box of the atoms' unshrunk balls f > 0: no need to locate.
    if ((c.array() < hull_lo_.array()).any() || (c.array() > hull_hi_.array()).any() || !c.allFinite()) return;
    Index hint = kInvalidIndex;
    for (Index x : v)
      if (!DelaunayTriangulation::is_bounding(x)) hint = samples_[dt_sample_[x]].cell;
    value_[t] = fs_.skin.sample(c, hint).f;
  });
  facets_.clear();
  dt_->for_each_tet([&](Index t) {
    if (!(value_[t] < 0)) return;
    const auto& v = dt_->tet(t);
    for (int i = 0; i < 4; ++i) {
      const Index n = dt_->neighbor(t, i);
      if (n == kInvalidIndex || value_[n] < 0) continue;
      const auto& fv = DelaunayTriangulation::kFaceVertices[i];
      // (v[fv0], v[fv1], v[fv2]) has its normal into t (inside): reversed, outward.
      const std::array<Index, 3> d{v[fv[0]], v[fv[2]], v[fv[1]]};
      if (DelaunayTriangulation::is_bounding(d[0]) || DelaunayTriangulation::is_bounding(d[1]) ||
          DelaunayTriangulation::is_bounding(d[2]))
        continue;
      facets_.push_back({{dt_sample_[d[0]], dt_sample_[d[1]], dt_sample_[d[2]]}, t, n});
    }
  });
}

bool Patcher::extract() {
  patch_.clear();
  trouble_.clear();
  loose_.clear();
  std::unordered_map<std::uint64_t, std::vector<Index>> by_edge;
  for (Index i = 0; i < facets_.size(); ++i) {
    const auto& s = facets_[i].s;
    for (int k = 0; k < 3; ++k) by_edge[edge_key(s[k], s[(k + 1) % 3])].push_back(i);
  }
  std::unordered_map<std::uint64_t, char> is_loop;
  for (const auto& e : loop_) is_loop[edge_key(e[0], e[1])] = 1;
  std::vector<char> taken(facets_.size(), 0);
  std::vector<Index> queue;
  bool ok = true;
  auto take = [&](Index f) {
    if (taken[f]) return;
    taken[f] = 1;
    queue.push_back(f);
  };
  for (const auto& e : loop_) {
    auto it = by_edge.find(edge_key(e[0], e[1]));
    if (it == by_edge.end() || it->second.size() != 1) {
      ok = false;  // the loop edge is not (or not once) a restricted Delaunay edge on the hole's side
      if (it != by_edge.end())
        for (Index f : it->second) trouble_.push_back(f);
      loose_.push_back(samples_[e[0]].v);
      loose_.push_back(samples_[e[1]].v);
      continue;
    }
    take(it->second[0]);
  }
  for (std::size_t qi = 0; qi < queue.size(); ++qi) {
    const Index f = queue[qi];
    const auto& s = facets_[f].s;
    bool leak = false;
    for (Index x : s)
      if (samples_[x].v.is_valid() && !samples_[x].loop) leak = true;  // reaches past the loop
    if (leak) {
      ok = false;
      trouble_.push_back(f);
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const Index a = s[k], b = s[(k + 1) % 3];
      if (is_loop.count(edge_key(a, b))) continue;
      auto it = by_edge.find(edge_key(b, a));
      if (it == by_edge.end() || it->second.size() != 1) {
        ok = false;  // a boundary or non-manifold edge inside the patch
        trouble_.push_back(f);
        if (it != by_edge.end())
          for (Index g : it->second) trouble_.push_back(g);
        continue;
      }
      take(it->second[0]);
    }
  }
  patch_ = queue;
  if (!ok) return false;
  // Each directed edge once, and every vertex's fan one disc with the kept faces.
  std::unordered_map<std::uint64_t, int> uses;
  for (Index f : patch_) {
    const auto& s = facets_[f].s;
    for (int k = 0; k < 3; ++k)
      if (++uses[edge_key(s[k], s[(k + 1) % 3])] > 1) return false;
  }
  return true;
}

bool Patcher::surface_centre(const RFacet& f, Vec3& x, Index& cell) const {
  Vec3 a = cc_[f.inner], b = cc_[f.outer];  // f(a) < 0 <= f(b)
  if (!a.allFinite() || !b.allFinite()) return false;
  // The outer circumcentre may be far away: clip the dual edge to the box.
  Index hint = samples_[f.s[0]].cell;
  for (int i = 0; i < kBisectionSteps; ++i) {
    const Vec3 m = 0.5 * (a + b);
    const bool outside_box = (m.array() < hull_lo_.array()).any() || (m.array() > hull_hi_.array()).any();
    if (outside_box || fs_.skin.sample(m, hint).f >= 0)
      b = m;
    else
      a = m;
  }
  cell = hint;
  x = fs_.skin.pull_back(0.5 * (a + b), cell);
  return x.allFinite();
}

bool Patcher::valid_geometry() const {
  // Outward at every corner, and no two triangles (patch or kept nearby) cross.
  std::vector<Vec3> positions;
  for (const Sample& s : samples_) positions.push_back(s.p);
  std::vector<std::array<Index, 3>> ids;
  for (Index f : patch_) {
    const auto& s = facets_[f].s;
    const Vec3 n = (positions[s[1]] - positions[s[0]]).cross(positions[s[2]] - positions[s[0]]);
    for (Index x : s)
      if (!(n.dot(samples_[x].normal) > 0)) return false;
    ids.push_back(s);
  }
  const std::size_t n_patch = ids.size();
  // Kept vertices that are not samples get indices after the samples'.
  std::unordered_map<Index, Index> extra;
  for (Face f : kept_near_) {
    std::array<Index, 3> id{};
    int k = 0;
    for (Vertex x : fs_.mesh.vertices(f)) {
      auto it = sample_of_vertex_.find(x.idx());
      if (it != sample_of_vertex_.end()) {
        id[k++] = it->second;
        continue;
      }
      auto [e, fresh] = extra.emplace(x.idx(), static_cast<Index>(positions.size()));
      if (fresh) positions.push_back(fs_.mesh.position(x));
      id[k++] = e->second;
    }
    ids.push_back(id);
  }
  std::vector<Eigen::AlignedBox3d> boxes(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i)
    for (Index x : ids[i]) boxes[i].extend(positions[x]);
  for (std::size_t i = 0; i < n_patch; ++i)
    for (std::size_t j = i + 1; j < ids.size(); ++j)
      if (boxes[i].intersects(boxes[j]) && geometry::mesh_triangles_intersect(ids[i], ids[j], positions)) return false;
  return true;
}

bool Patcher::solve() {
  if (!collect_samples()) {
    why_ = "the region pinches or its boundary leaves it";
    return false;
  }
  // The Delaunay box: the samples' box, padded by its own size and the
  // largest rho among them.
  Eigen::AlignedBox3d box;
  double rho_high = 0;
  for (const Sample& s : samples_) box.extend(s.p), rho_high = std::max(rho_high, s.rho);
  const Vec3 pad = Vec3::Constant(box.diagonal().norm() + rho_high);
  dt_ = std::make_unique<DelaunayTriangulation>(box.min() - pad, box.max() + pad);
  dt_sample_.assign(DelaunayTriangulation::kNumBounding, kInvalidIndex);
  auto insert = [&](Index s) {
    const Index id = dt_->insert(samples_[s].p);
    if (dt_sample_.size() <= id) dt_sample_.resize(id + 1, kInvalidIndex);
    dt_sample_[id] = s;
  };
  try {
    for (Index s = 0; s < samples_.size(); ++s) insert(s);
  } catch (const InputError&) {
    why_ = "two samples at the same point";
    return false;
  }
  const std::size_t budget = kInsertionFloor + kInsertionsPerSample * std::max<std::size_t>(free_count_, loop_.size());
  std::size_t inserted = 0;
  const double CQ = fs_.run.size.C * fs_.run.size.Q;
  for (int round = 0; round < kMaxRounds; ++round) {
    classify();
    const bool closed = extract();
    // Facets to refine: the trouble spots, then every patch facet that breaks [U].
    std::vector<Index> todo = trouble_;
    if (closed) {
      for (Index f : patch_) {
        const auto& s = facets_[f].s;
        const double bound = CQ * std::min({samples_[s[0]].rho, samples_[s[1]].rho, samples_[s[2]].rho});
        if (skin::circumradius(samples_[s[0]].p, samples_[s[1]].p, samples_[s[2]].p) >= bound) todo.push_back(f);
      }
      if (todo.empty()) {
        if (valid_geometry()) return true;
        why_ = "the patch is not embedded among the kept faces";
        return false;
      }
    }
    std::sort(todo.begin(), todo.end());
    todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
    if (fs_.tracing)
      fs_.tracef(
          "patch:   round %d: %zu samples, %zu restricted facets, patch %zu, %s, %zu trouble, %zu to refine (loop "
          "%zu)\n",
          round, samples_.size(), facets_.size(), patch_.size(), closed ? "closed" : "open", trouble_.size(),
          todo.size(), loop_.size());
    // Only facets with a free corner or inside the loop are refined: a centre
    // over the kept mesh would put a second sample layer there.
    std::vector<std::pair<Vec3, Index>> centres;
    grow_at_.clear();
    for (Index f : todo) {
      bool guard = false;
      for (Index x : facets_[f].s)
        if (samples_[x].v.is_valid() && !samples_[x].loop) {
          guard = true;
          grow_at_.push_back(samples_[x].v);
        }
      if (guard) continue;
      Vec3 x;
      Index cell;
      if (surface_centre(facets_[f], x, cell)) centres.emplace_back(x, cell);
    }
    if (centres.empty() || inserted + centres.size() > budget) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "%s after %d rounds (%zu facets to refine, %zu of them away from the kept mesh)",
                    centres.empty() ? "no refinement left" : "the insertion budget ran out", round, todo.size(),
                    centres.size());
      why_ = buf;
      return false;
    }
    const std::size_t inserted_before = inserted;
    for (const auto& [x, cell] : centres) {
      const skin::SkinSample at = fs_.skin.sample(x, cell);
      const Index s = add_free(x, at.cell, at.rho, at.gradient.normalized());
      try {
        insert(s);
      } catch (const InputError&) {
        samples_.pop_back();  // the same centre twice
        --free_count_;
        continue;
      }
      ++inserted;
    }
    // Every centre was a sample already: the next round would be this one
    // again (the rounds are deterministic), so stop here.
    if (inserted == inserted_before) {
      why_ = "no refinement left after " + std::to_string(round) + " rounds (every centre is a sample already)";
      return false;
    }
  }
  why_ = "too many refinement rounds";
  return false;
}

std::size_t Patcher::apply() {
  for (Face f : region_)
    if (!fs_.mesh.is_deleted(f)) fs_.mesh.delete_face(f);
  std::vector<Vertex> vertex(samples_.size());
  for (Index i = 0; i < samples_.size(); ++i) vertex[i] = samples_[i].v;
  for (Index f : patch_)
    for (Index x : facets_[f].s)
      if (!vertex[x].is_valid()) vertex[x] = new_vertex(fs_, samples_[x].p, samples_[x].cell);
  for (Index f : patch_) {
    const auto& s = facets_[f].s;
    fs_.add_triangle(vertex[s[0]], vertex[s[1]], vertex[s[2]]);
  }
  for (Index f : patch_)
    for (Index x : facets_[f].s)
      if (!fs_.mesh.is_boundary(vertex[x])) fs_.set_state(vertex[x], VState::Interior);
  return patch_.size();
}

/// The faces within `rings` rings of the vertices `seeds`.
std::vector<Face> faces_around(const SurfaceMesh& mesh, const std::vector<Vertex>& seeds, int rings) {
  std::vector<Vertex> ring, all;
  for (Vertex v : seeds)
    if (!mesh.is_deleted(v) && !mesh.is_isolated(v)) ring.push_back(v);
  all = ring;
  std::vector<Face> faces;
  for (int r = 0; r < rings; ++r) {
    std::vector<Vertex> next;
    for (Vertex v : ring)
      for (Face f : mesh.faces(v)) {
        faces.push_back(f);
        for (Vertex y : mesh.vertices(f)) next.push_back(y);
      }
    std::sort(next.begin(), next.end());
    next.erase(std::unique(next.begin(), next.end()), next.end());
    std::vector<Vertex> fresh;
    std::sort(all.begin(), all.end());
    std::set_difference(next.begin(), next.end(), all.begin(), all.end(), std::back_inserter(fresh));
    all.insert(all.end(), fresh.begin(), fresh.end());
    ring.swap(fresh);
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

}  // namespace

bool patch_hole(FrontState& fs, const std::vector<Vertex>& around, const Vec3& near) {
  if (!fs.opt.patch_fallback) return false;
  std::vector<Vertex> seeds;
  for (Vertex v : around)
    if (!fs.mesh.is_deleted(v) && !fs.mesh.is_isolated(v)) seeds.push_back(v);
  if (seeds.empty()) {
    // An enlargement deleted the hole's whole neighbourhood: start from the
    // boundary vertices nearest to where it was, within growing distances.
    const double r = fs.opt.disc_factor * std::max(fs.skin.sample(near).rho, kMinGridCell);
    for (double reach = 2 * r; seeds.empty() && reach < 64 * r; reach *= 2)
      fs.front_grid->for_each_near(near, reach, 0.0, std::numeric_limits<double>::infinity(),
                                   fs.mesh.positions().vector(), [&](Index xi, const Vec3&) {
                                     const Vertex x(xi);
                                     if (!fs.mesh.is_deleted(x) && !fs.mesh.is_isolated(x) && fs.mesh.is_boundary(x))
                                       seeds.push_back(x);
                                   });
    std::sort(seeds.begin(), seeds.end());
  }
  if (seeds.empty()) return false;
  Vec3 hull_lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hull_hi = -hull_lo;
  for (const auto& wp : fs.skin.points()) {
    const double r = std::sqrt(std::max(wp.w, 0.0));
    hull_lo = hull_lo.cwiseMin(wp.z - Vec3::Constant(r));
    hull_hi = hull_hi.cwiseMax(wp.z + Vec3::Constant(r));
  }
  // The region: the faces around the hole, grown where the last attempt's
  // restricted facets reached past it, else by one more ring.
  std::vector<Face> region = faces_around(fs.mesh, seeds, 1);
  int rings = 1;
  for (int attempt = 0; attempt < kMaxAttempts && !region.empty(); ++attempt) {
    Patcher patcher(fs, region, hull_lo, hull_hi);
    if (patcher.solve()) {
      const std::size_t added = patcher.apply();
      ++fs.stats.patched_holes;
      fs.stats.patch_faces += added;
      if (fs.tracing) fs.tracef("patch: re-meshed a region of %zu faces with %zu faces\n", region.size(), added);
      return true;
    }
    std::vector<Vertex> grow = patcher.grow_at();
    if (fs.tracing)
      fs.tracef("patch: no patch of a region of %zu faces: %s; growing it at %zu vertices\n", region.size(),
                patcher.why().c_str(), grow.size());
    std::vector<Face> more;
    if (!grow.empty()) {
      more = faces_around(fs.mesh, grow, 1);
    } else {
      rings = rings < 4 ? rings + 1 : rings * 3 / 2;
      if (rings > kMaxRings) break;
      more = faces_around(fs.mesh, seeds, rings);
    }
    const std::size_t before = region.size();
    region.insert(region.end(), more.begin(), more.end());
    std::sort(region.begin(), region.end());
    region.erase(std::unique(region.begin(), region.end()), region.end());
    if (region.size() == before) {  // nothing new where it reached: one more ring
      rings = rings < 4 ? rings + 1 : rings * 3 / 2;
      if (rings > kMaxRings) break;
      more = faces_around(fs.mesh, seeds, rings);
      region.insert(region.end(), more.begin(), more.end());
      std::sort(region.begin(), region.end());
      region.erase(std::unique(region.begin(), region.end()), region.end());
    }
  }
  return false;
}

}  // namespace skinmesh::front::detail
