// refine/local_refinement.cpp: flips, contraction and insertion (Cheng & Shi
// 2004 §4.3; papers/front/open_questions.md §9).
#include "refine/local_refinement.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "core/parallel.h"
#include "geometry/check/mesh_checks.h"
#include "geometry/triangulation/point_grid.h"
#include "skin/restricted_delaunay.h"
#include "skin/vertex_data.h"

namespace skinmesh::refine {

using geometry::Edge;
using geometry::Face;
using geometry::Halfedge;
using geometry::min_angle;
using geometry::SurfaceMesh;
using geometry::Vertex;

namespace {

/// Elements per block of a parallel scan. [chosen] large enough that a
/// block's list and its hand-out cost little beside its tests.
constexpr std::size_t kScanGrain = 8192;
/// Suspect edges per block of the first Lawson pass's verdicts. [chosen]
/// each verdict may project up to four circumcentres onto the skin.
constexpr std::size_t kVerdictGrain = 512;

class Refiner {
 public:
  Refiner(const skin::SkinSurface& skin, SurfaceMesh& mesh, const RefineOptions& opt, const skin::RunContext& run,
          const std::vector<Face>* seeds)
      : skin_(skin), mesh_(mesh), opt_(opt), run_(run), seeds_(seeds) {
    cell_ = mesh_.vertex_property(skin::kVertexCell, kInvalidIndex);
    inserted_ = mesh_.vertex_property(skin::kVertexInserted, 0);
    for (Vertex v : mesh_.vertices())
      if (cell_[v] == kInvalidIndex) cell_[v] = skin_.sample(mesh_.position(v)).cell;
    normal_ = skin::VertexNormals(skin_.mixed_complex(), mesh_);
    // rho is read at every edge and face of every scan: computed once here
    // (the values skin::VertexRhos gives) and kept while the pass runs.
    const skin::VertexRhos rho(skin_.mixed_complex(), mesh_);
    rho_.resize(mesh_.vertices_size());
    parallel_for((rho_.size() + kScanGrain - 1) / kScanGrain, run_.threads, 1, [&](std::size_t b) {
      for (std::size_t i = b * kScanGrain, end = std::min(rho_.size(), i + kScanGrain); i < end; ++i)
        if (!mesh_.is_deleted(Vertex(static_cast<Index>(i)))) rho_[i] = rho[Vertex(static_cast<Index>(i))];
    });
    // Grid of the vertices inserted here, for the separation test of insert():
    // cells of the mean edge length (the scale of R), hashed, so its size
    // follows the inserted vertices only. The mean of about 4,096 edges spread
    // over the index range is plenty for a cell size (and the test's verdicts
    // do not depend on it).
    double mean_edge = 0;
    std::size_t ne = 0;
    constexpr std::size_t kEdgeSamples = 4096;  // [measured] enough edges for a mean that sets a cell size
    const std::size_t stride = std::max<std::size_t>(1, mesh_.edges_size() / kEdgeSamples);
    for (std::size_t i = 0; i < mesh_.edges_size(); i += stride) {
      const Edge e(static_cast<Index>(i));
      if (mesh_.is_deleted(e)) continue;
      mean_edge += (pos(mesh_.vertex(e, 0)) - pos(mesh_.vertex(e, 1))).norm(), ++ne;
    }
    constexpr double kFallbackCell = 1e-3;  // [derived] times L, for a mesh without edges
    inserted_grid_.emplace(ne && mean_edge > 0 ? mean_edge / double(ne) : skin_.length_scale() * kFallbackCell);
  }

  RefineStats run();

 private:
  const Vec3& pos(Vertex v) const { return mesh_.position(v); }
  /// True if triangle (a, b, c), counter-clockwise, faces along the skin
  /// normal at each of its corners.
  bool face_ok(Vertex a, Vertex b, Vertex c) const { return face_ok(pos(a), pos(b), pos(c), a, b, c); }
  bool face_ok(const Vec3& pa, const Vec3& pb, const Vec3& pc, Vertex a, Vertex b, Vertex c) const {
    const Vec3 nt = (pb - pa).cross(pc - pa);
    return nt.dot(normal_[a]) > 0 && nt.dot(normal_[b]) > 0 && nt.dot(normal_[c]) > 0;
  }
  /// True if d lies strictly inside the surface Delaunay ball of abc (the
  /// circumsphere of abc if the dual line misses the skin).
  bool inside_ball(Vertex a, Vertex b, Vertex c, Vertex d) const;
  /// True if the edge is not locally restricted Delaunay and flipping it
  /// gives two triangles that face outwards and are locally Delaunay: a
  /// test of the edge's two faces alone (their four vertices and the skin).
  bool flips_locally(Edge e) const;
  /// flips_locally(), and the new edge does not exist yet (is_flip_ok()).
  bool should_flip(Edge e) const;
  void lawson();
  /// The rounds of contraction and insertion passes, from the violators
  /// `short_edges` and `big` (every element's verdict if `full`).
  RefineStats rounds(std::vector<Edge> short_edges, std::vector<Face> big, bool full);
  void push_edges_around(Vertex v);
  bool violates_L(Edge e) const {
    const Vertex a = mesh_.vertex(e, 0), b = mesh_.vertex(e, 1);
    return !skin::satisfies_L(pos(a), pos(b), rho_[a.idx()], rho_[b.idx()], run_.size);
  }
  bool violates_U(Face f) const {
    Vertex v[3];
    int i = 0;
    for (Vertex x : mesh_.vertices(f)) v[i++] = x;
    return !skin::satisfies_U(pos(v[0]), pos(v[1]), pos(v[2]), rho_[v[0].idx()], rho_[v[1].idx()], rho_[v[2].idx()],
                              run_.size);
  }
  bool contract(Edge e);
  bool insert(Face f);
  /// Records the edges and faces around v as touched.
  void touch_around(Vertex v) {
    for (Halfedge h : mesh_.halfedges(v)) {
      touched_edges_.push_back(mesh_.edge(h));
      if (!mesh_.is_boundary(h)) touched_faces_.push_back(mesh_.face(h));
    }
  }
  /// The edges violating [L], in index order (as a scan of mesh_.edges()
  /// gives them): the previous list `prev` and the touched edges, re-tested;
  /// every edge if `full`. Clears the touched edges.
  std::vector<Edge> scan_L(const std::vector<Edge>& prev, bool full);
  /// The same for the faces violating [U].
  std::vector<Face> scan_U(const std::vector<Face>& prev, bool full);

  const skin::SkinSurface& skin_;
  SurfaceMesh& mesh_;
  const RefineOptions& opt_;
  const skin::RunContext& run_;
  /// refine_seams(): the faces where the flips and the first scans start;
  /// null: every element.
  const std::vector<Face>* seeds_;
  geometry::VertexProperty<Index> cell_;
  skin::VertexNormals normal_;  ///< from the cell
  /// rho per vertex index (Å), the values skin::VertexRhos gives (0 at
  /// deleted vertices), kept up to date by insert().
  std::vector<double> rho_;
  geometry::VertexProperty<std::uint8_t> inserted_;  ///< 1: inserted by this refinement
  std::optional<geometry::PointGrid> inserted_grid_;
  std::vector<Edge> stack_;
  /// The edges and faces whose corners changed (flip, contraction, insertion)
  /// since the last scan for [L] (edges) or [U] (faces). The verdicts depend
  /// only on the corners' positions and rho, which never change for a vertex,
  /// so a scan needs only these and the previous scan's violators
  /// (scan_L, scan_U); handles are never reused (deleted elements stay).
  std::vector<Edge> touched_edges_;
  std::vector<Face> touched_faces_;
  /// During the first Lawson pass: per edge, flips_locally()'s verdict on
  /// the mesh before the pass (kFlip, kKeep), kUnknown once a flip changed a
  /// face of the edge, or if never taken; empty otherwise.
  std::vector<std::uint8_t> first_verdict_;
  static constexpr std::uint8_t kUnknown = 0, kKeep = 1, kFlip = 2;
  RefineStats stats_;
};

bool Refiner::inside_ball(Vertex a, Vertex b, Vertex c, Vertex d) const {
  // Filter with the same answer: d outside every ball the projection could
  // give (most tests of a Lawson pass; 3x less refinement time on crambin).
  if (skin::outside_every_surface_ball(pos(a), pos(b), pos(c), pos(d), skin_.length_scale())) return false;
  Vec3 m;
  Index cell = cell_[a];
  if (!skin::surface_delaunay_centre(skin_, pos(a), pos(b), pos(c), m, cell))
    m = skin::circumcentre(pos(a), pos(b), pos(c));
  constexpr double kStrictlyInside = 1e-9;  // [derived] relative: d on the ball's sphere is not inside
  return (m - pos(d)).norm() < (m - pos(a)).norm() * (1 - kStrictlyInside);
}

bool Refiner::flips_locally(Edge e) const {
  if (mesh_.is_deleted(e) || mesh_.is_boundary(e)) return false;
  const Halfedge h0 = mesh_.halfedge(e, 0), h1 = mesh_.halfedge(e, 1);
  const Vertex a = mesh_.from_vertex(h0), b = mesh_.to_vertex(h0);
  const Vertex c = mesh_.to_vertex(mesh_.next(h0)), d = mesh_.to_vertex(mesh_.next(h1));
  // Faces (a, b, c) and (b, a, d).
  if (!inside_ball(a, b, c, d) && !inside_ball(b, a, d, c)) return false;
  if (!face_ok(a, d, c) || !face_ok(b, c, d)) return false;
  // Flip only towards a locally Delaunay pair (no flip cycles).
  return !inside_ball(a, d, c, b) && !inside_ball(b, c, d, a);
}

bool Refiner::should_flip(Edge e) const { return flips_locally(e) && mesh_.is_flip_ok(e); }

void Refiner::lawson() {
  constexpr std::size_t kMinFlipCap = 100;  // [measured] room for the flips of a tiny mesh
  const std::size_t cap = static_cast<std::size_t>(opt_.max_flips_factor * double(mesh_.n_edges())) + kMinFlipCap;
  std::size_t flips = 0;
  while (!stack_.empty()) {
    const Edge e = stack_.back();
    stack_.pop_back();
    // A verdict of flips_locally() taken on the threads before the first
    // pass holds while neither face of e has changed since (flips mark the
    // edges of their quad). Whether the new edge exists already depends on
    // the whole mesh, so is_flip_ok() is asked now.
    const bool flip = e.idx() < first_verdict_.size() && first_verdict_[e.idx()] != kUnknown
                          ? first_verdict_[e.idx()] == kFlip && mesh_.is_flip_ok(e)
                          : should_flip(e);
    if (!flip) continue;
    if (++flips > cap) {
      ++stats_.flip_caps;
      stack_.clear();
      break;
    }
    mesh_.flip(e);
    ++stats_.flips;
    if (opt_.observer) opt_.observer(RefineOperation::Flip, mesh_);
    touched_edges_.push_back(e);
    touched_faces_.push_back(mesh_.face(mesh_.halfedge(e, 0)));
    touched_faces_.push_back(mesh_.face(mesh_.halfedge(e, 1)));
    if (e.idx() < first_verdict_.size()) first_verdict_[e.idx()] = kUnknown;
    for (unsigned i = 0; i < 2; ++i) {
      const Halfedge h = mesh_.halfedge(e, i);
      for (const Edge g : {mesh_.edge(mesh_.next(h)), mesh_.edge(mesh_.prev(h))}) {
        if (g.idx() < first_verdict_.size()) first_verdict_[g.idx()] = kUnknown;
        stack_.push_back(g);
      }
    }
  }
}

void Refiner::push_edges_around(Vertex v) {
  for (Halfedge h : mesh_.halfedges(v)) {
    stack_.push_back(mesh_.edge(h));
    if (!mesh_.is_boundary(h)) stack_.push_back(mesh_.edge(mesh_.next(h)));
  }
}

bool Refiner::contract(Edge e) {
  // Keep the endpoint whose new star has the better minimum angle, among the
  // collapses that pass the link condition and turn no triangle over (Q9.3 (contraction for [L])).
  // A vertex inserted by this refinement is never the one deleted
  // ("Termination": it keeps contractions and insertions from undoing each
  // other).
  double best = -1;
  Halfedge pick;
  bool protected_vertex = false;
  for (unsigned i = 0; i < 2; ++i) {
    const Halfedge h = mesh_.halfedge(e, i);
    if (inserted_[mesh_.from_vertex(h)]) {
      protected_vertex = true;
      continue;
    }
    // A region's boundary (its cut curves' samples and parked rims) is
    // shared with the band and the region next to it: it stays as it is.
    if (mesh_.is_boundary(mesh_.from_vertex(h))) continue;
    if (!mesh_.is_collapse_ok(h)) continue;
    const Vertex v0 = mesh_.from_vertex(h), v1 = mesh_.to_vertex(h);
    double q = 4;
    bool ok = true;
    for (Halfedge g : mesh_.halfedges(v0)) {
      if (mesh_.is_boundary(g)) continue;
      const Vertex x = mesh_.to_vertex(g), y = mesh_.to_vertex(mesh_.next(g));
      if (x == v1 || y == v1) continue;  // the faces of e disappear
      if (!face_ok(pos(v1), pos(x), pos(y), v1, x, y)) {
        ok = false;
        break;
      }
      q = std::min(q, min_angle(pos(v1), pos(x), pos(y)));
    }
    if (ok && q > best) best = q, pick = h;
  }
  if (!pick.is_valid()) {
    ++stats_.refused_contractions;
    stats_.protected_contractions += protected_vertex;
    return false;
  }
  const Vertex keep = mesh_.to_vertex(pick);
  mesh_.collapse(pick);
  ++stats_.contractions;
  if (opt_.observer) opt_.observer(RefineOperation::Contraction, mesh_);
  touch_around(keep);
  push_edges_around(keep);
  lawson();
  return true;
}

bool Refiner::insert(Face f) {
  Vertex v[3];
  {
    int i = 0;
    for (Vertex x : mesh_.vertices(f)) v[i++] = x;
  }
  Vec3 m;
  Index cell = cell_[v[0]];
  if (!skin::surface_delaunay_centre(skin_, pos(v[0]), pos(v[1]), pos(v[2]), m, cell)) {
    ++stats_.refused_insertions;
    return false;
  }
  const double radius = (m - pos(v[0])).norm();
  // Separation from the vertices inserted before ("Termination").
  {
    bool crowded = false;
    inserted_grid_->for_each_near(m, opt_.min_inserted_separation * radius,
                                  [&](Index id, const Vec3&) { crowded = crowded || !mesh_.is_deleted(Vertex(id)); });
    if (crowded) {
      ++stats_.refused_insertions;
      ++stats_.crowded_insertions;
      return false;
    }
  }
  // Walk from f to the triangle whose prism contains m (barycentric
  // coordinates in the triangle's plane).
  Face t = f;
  std::array<double, 3> lam{};
  std::array<Halfedge, 3> hs{};  // hs[i]: the half-edge opposite corner i
  std::array<Vertex, 3> x{};
  bool found = false;
  Face came_from;                    // the face the walk just left
  constexpr int kMaxWalkSteps = 64;  // [measured] the limit of the walk over the surface triangles
  for (int step = 0; step < kMaxWalkSteps && !found; ++step) {
    int i = 0;
    for (Halfedge h : mesh_.halfedges(t)) {
      x[i] = mesh_.from_vertex(h);
      hs[(i + 2) % 3] = h;  // h = x[i] -> x[i+1] is opposite corner i+2
      ++i;
    }
    const Vec3 nf = (pos(x[1]) - pos(x[0])).cross(pos(x[2]) - pos(x[0]));
    const double n2 = nf.squaredNorm();
    if (n2 == 0) break;
    int worst = 0;
    for (int k = 0; k < 3; ++k) {
      const Vec3& p1 = pos(x[(k + 1) % 3]);
      const Vec3& p2 = pos(x[(k + 2) % 3]);
      lam[k] = (p2 - p1).cross(m - p1).dot(nf) / n2;
      if (lam[k] < lam[worst]) worst = k;
    }
    if (lam[worst] >= 0) {
      found = true;
      break;
    }
    const Halfedge across = mesh_.opposite(hs[worst]);
    if (mesh_.is_boundary(across)) break;
    if (mesh_.face(across) == came_from) {
      // m lies outside both prisms, in the wedge between two faces that are
      // not coplanar, next to their shared edge: the walk would go back and
      // forth. m belongs to that edge; the edge split below takes it
      // (lam[worst] < 0 < split_edge_barycentric).
      found = true;
      break;
    }
    came_from = t;
    t = mesh_.face(across);
  }
  if (!found) {
    ++stats_.refused_insertions;
    return false;
  }
  for (int k = 0; k < 3; ++k)
    if ((pos(x[k]) - m).norm() < opt_.min_insertion_clearance * radius) {  // the ball is far from empty
      ++stats_.refused_insertions;
      return false;
    }
  // The new vertex's normal, for the orientation tests.
  const skin::SkinSample s = skin_.sample(m, cell);
  const Vec3 nm = s.gradient.normalized();
  auto ok_with_m = [&](Vertex a, Vertex b) {  // triangle (a, b, m)
    const Vec3 nt = (pos(b) - pos(a)).cross(m - pos(a));
    return nt.dot(normal_[a]) > 0 && nt.dot(normal_[b]) > 0 && nt.dot(nm) > 0;
  };
  int small = 0;
  for (int k = 1; k < 3; ++k)
    if (lam[k] < lam[small]) small = k;
  Vertex nv;
  if (lam[small] < opt_.split_edge_barycentric) {
    // m is near the edge opposite corner `small`: split that edge.
    const Halfedge h = hs[small];
    const Halfedge o = mesh_.opposite(h);
    if (mesh_.is_boundary(o)) {
      ++stats_.refused_insertions;
      return false;
    }
    const Vertex p = mesh_.from_vertex(h), q = mesh_.to_vertex(h);
    const Vertex apex_t = x[small], apex_o = mesh_.to_vertex(mesh_.next(o));
    // Faces after the split: (p, m, apex_t)... written as (a, b, m).
    if (!ok_with_m(apex_t, p) || !ok_with_m(q, apex_t) || !ok_with_m(p, apex_o) || !ok_with_m(apex_o, q)) {
      ++stats_.refused_insertions;
      return false;
    }
    nv = mesh_.split_edge(mesh_.edge(h), m);
  } else {
    if (!ok_with_m(x[0], x[1]) || !ok_with_m(x[1], x[2]) || !ok_with_m(x[2], x[0])) {
      ++stats_.refused_insertions;
      return false;
    }
    nv = mesh_.split_face(t, m);
  }
  cell_[nv] = s.cell;  // and with it nm and s.rho
  rho_.resize(mesh_.vertices_size());
  rho_[nv.idx()] = s.rho;
  inserted_[nv] = 1;
  inserted_grid_->insert(nv.idx(), m);
  ++stats_.insertions;
  if (opt_.observer) opt_.observer(RefineOperation::Insertion, mesh_);
  touch_around(nv);
  push_edges_around(nv);
  lawson();
  return true;
}

/// The elements of the `all` first handles of their kind (deleted ones
/// skipped) for which `violates` holds, in index order: every one if `full`, else those of `prev`
/// and `touched` (sorted, without repeats, not deleted). Clears `touched`.
/// A full scan runs on `threads` threads (core/parallel.h: the same list).
template <class Handle, class Violates>
std::vector<Handle> rescan(const SurfaceMesh& mesh, std::size_t all, const std::vector<Handle>& prev,
                           std::vector<Handle>& touched, bool full, int threads, Violates violates) {
  std::vector<Handle> out;
  if (full) {
    const std::vector<std::size_t> hit = parallel_select(all, threads, kScanGrain, [&](std::size_t i) {
      const Handle x(static_cast<Index>(i));
      return !mesh.is_deleted(x) && violates(x);
    });
    out.reserve(hit.size());
    for (std::size_t i : hit) out.emplace_back(static_cast<Index>(i));
  } else {
    std::vector<Handle> cand = prev;
    cand.insert(cand.end(), touched.begin(), touched.end());
    std::sort(cand.begin(), cand.end(), [](Handle a, Handle b) { return a.idx() < b.idx(); });
    cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
    for (Handle x : cand)
      if (!mesh.is_deleted(x) && violates(x)) out.push_back(x);
  }
  touched.clear();
  return out;
}

std::vector<Edge> Refiner::scan_L(const std::vector<Edge>& prev, bool full) {
  return rescan(mesh_, mesh_.edges_size(), prev, touched_edges_, full, run_.threads,
                [&](Edge e) { return violates_L(e); });
}

std::vector<Face> Refiner::scan_U(const std::vector<Face>& prev, bool full) {
  return rescan(mesh_, mesh_.faces_size(), prev, touched_faces_, full, run_.threads,
                [&](Face f) { return violates_U(f); });
}

RefineStats Refiner::run() {
  std::vector<Edge> short_edges;
  std::vector<Face> big;
  if (seeds_) {
    // refine_seams(): the seeds' edges are the only suspects, and the first
    // scans test the seeds and what the flips touched.
    for (Face f : *seeds_) {
      if (mesh_.is_deleted(f)) continue;
      big.push_back(f);
      for (Halfedge h : mesh_.halfedges(f)) short_edges.push_back(mesh_.edge(h));
    }
    std::sort(big.begin(), big.end(), [](Face a, Face b) { return a.idx() < b.idx(); });
    big.erase(std::unique(big.begin(), big.end()), big.end());
    std::sort(short_edges.begin(), short_edges.end(), [](Edge a, Edge b) { return a.idx() < b.idx(); });
    short_edges.erase(std::unique(short_edges.begin(), short_edges.end()), short_edges.end());
    stack_.assign(short_edges.begin(), short_edges.end());
    lawson();
    return rounds(std::move(short_edges), std::move(big), false);
  }
  // The first Lawson pass. An edge flips only if the apex across it lies in
  // the surface ball of one of its faces (should_flip), which needs the
  // filter to fail first: each face's filter is set up once for the apexes
  // across its three edges, and only the edges where it fails go on the
  // stack, in index order (the others would be popped and dropped).
  {
    // Per face, which of its three edges are suspect (bit i: the edge of
    // the face's i-th half-edge): set on the threads, each face its own
    // slot, then marked on the edges.
    std::vector<std::uint8_t> mask(mesh_.faces_size(), 0);
    const std::size_t blocks = (mask.size() + kScanGrain - 1) / kScanGrain;
    parallel_for(blocks, run_.threads, 1, [&](std::size_t b) {
      for (std::size_t i = b * kScanGrain, end = std::min(mask.size(), i + kScanGrain); i < end; ++i) {
        const Face f(static_cast<Index>(i));
        if (mesh_.is_deleted(f)) continue;
        const Halfedge h0 = mesh_.halfedge(f), h1 = mesh_.next(h0), h2 = mesh_.next(h1);
        const skin::SurfaceBallFilter ball(pos(mesh_.from_vertex(h0)), pos(mesh_.to_vertex(h0)),
                                           pos(mesh_.to_vertex(h1)), skin_.length_scale());
        int bit = 0;
        for (Halfedge h : {h0, h1, h2}) {
          const Halfedge o = mesh_.opposite(h);
          if (!mesh_.is_boundary(o) && !ball.outside(pos(mesh_.to_vertex(mesh_.next(o))))) mask[i] |= 1u << bit;
          ++bit;
        }
      }
    });
    std::vector<char> suspect(mesh_.edges_size(), 0);
    for (Face f : mesh_.faces()) {
      const Halfedge h0 = mesh_.halfedge(f), h1 = mesh_.next(h0), h2 = mesh_.next(h1);
      const Halfedge hs[3] = {h0, h1, h2};
      for (int bit = 0; bit < 3; ++bit)
        if (mask[f.idx()] >> bit & 1u) suspect[mesh_.edge(hs[bit]).idx()] = 1;
    }
    for (Edge e : mesh_.edges())
      if (suspect[e.idx()]) stack_.push_back(e);
    // The suspects' verdicts on the mesh as it is, on the threads (the
    // exact surface Delaunay balls are most of this pass's time).
    first_verdict_.assign(mesh_.edges_size(), kUnknown);
    const std::size_t n = stack_.size(), blocks_s = (n + kVerdictGrain - 1) / kVerdictGrain;
    if (run_.threads > 1)
      parallel_for(blocks_s, run_.threads, 1, [&](std::size_t b) {
        for (std::size_t i = b * kVerdictGrain, end = std::min(n, i + kVerdictGrain); i < end; ++i)
          first_verdict_[stack_[i].idx()] = flips_locally(stack_[i]) ? kFlip : kKeep;
      });
  }
  lawson();
  std::vector<std::uint8_t>().swap(first_verdict_);
  return rounds(std::move(short_edges), std::move(big), true);
}

RefineStats Refiner::rounds(std::vector<Edge> short_edges, std::vector<Face> big, bool full) {
  // The first scans read every element (full) or the given lists; later ones
  // the previous violators and what changed since (touched_edges_,
  // touched_faces_): the same lists. Started from seeds, the rounds end with
  // one scan of every element, which takes up any violation the seeds did
  // not reach, so the result holds for the whole mesh either way.
  bool verified = full;
  for (int round = 0; round < opt_.max_rounds; ++round) {
    ++stats_.rounds;
    bool changed = false;
    short_edges = scan_L(short_edges, full);
    for (Edge e : short_edges)
      if (!mesh_.is_deleted(e) && violates_L(e) && contract(e)) changed = true;
    big = scan_U(big, full);
    full = false;
    for (Face f : big)
      if (!mesh_.is_deleted(f) && violates_U(f) && insert(f)) changed = true;
    if (!changed) {
      if (verified) break;
      verified = full = true;
    }
  }
  stats_.L_left = scan_L(short_edges, full).size();
  stats_.U_left = scan_U(big, full).size();
  return stats_;
}

}  // namespace

void add_refine_stats(RefineStats& a, const RefineStats& b) {
  a.flips += b.flips, a.contractions += b.contractions, a.insertions += b.insertions;
  a.rounds = std::max(a.rounds, b.rounds);
  a.refused_contractions += b.refused_contractions, a.refused_insertions += b.refused_insertions;
  a.crowded_insertions += b.crowded_insertions, a.protected_contractions += b.protected_contractions;
  a.flip_caps += b.flip_caps;
  a.L_left += b.L_left, a.U_left += b.U_left;
}

const char* operation_name(RefineOperation op) {
  switch (op) {
    case RefineOperation::Flip:
      return "flip";
    case RefineOperation::Contraction:
      return "contraction";
    case RefineOperation::Insertion:
      return "insertion";
  }
  return "?";
}

RefineStats refine_mesh(const skin::SkinSurface& skin, SurfaceMesh& mesh, const RefineOptions& opt,
                        const skin::RunContext& run) {
  const skin::RunContext resolved = run.with_threads(thread_count(run.threads));
  Refiner r(skin, mesh, opt, resolved, nullptr);
  return r.run();
}

RefineStats refine_seams(const skin::SkinSurface& skin, SurfaceMesh& mesh, const std::vector<Face>& seeds,
                         const RefineOptions& opt, const skin::RunContext& run) {
  const skin::RunContext resolved = run.with_threads(thread_count(run.threads));
  Refiner r(skin, mesh, opt, resolved, &seeds);
  return r.run();
}

}  // namespace skinmesh::refine
