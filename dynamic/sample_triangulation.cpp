// dynamic/sample_triangulation.cpp: samples, their Delaunay triangulation and
// the restricted Delaunay triangulation, with [L]/[U] refinement.
// Notes: papers/dynamic/dynamic_skin.md
#include "dynamic/sample_triangulation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.h"
#include "skin/mixed_complex.h"

namespace skinmesh::dynamic {

using geometry::DelaunayTriangulation;

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

}  // namespace

SampleTriangulation::SampleTriangulation(const skin::SkinSurface& skin, double c, const skin::SizeConstants& size)
    : skin_(&skin), level_(skin, c), size_(size), dt_(level_.hull_lo(), level_.hull_hi()) {
  ensure_capacity();
  dt_.for_each_tet([&](Index t) { classify(t); });
}

void SampleTriangulation::ensure_capacity() {
  const std::size_t nv = dt_.vertex_capacity(), nt = dt_.tet_capacity();
  if (rho_.size() < nv) {
    rho_.resize(nv, 0.0);
    cell_.resize(nv, kInvalidIndex);
    seed_.resize(nv, 0);
    ringed_.resize(nv, 0);
  }
  if (cc_.size() < nt) {
    const std::size_t n = std::max(nt, cc_.size() * 3 / 2);
    cc_.resize(n, Vec3::Zero());
    value_.resize(n, 1.0);
    birth_.resize(n, 0);
    op_mark_.resize(n, 0);
  }
}

void SampleTriangulation::classify(Index t) {
  const auto& v = dt_.tet(t);
  Index hint = kInvalidIndex;
  for (const Index u : v)
    if (!DelaunayTriangulation::is_bounding(u)) {
      hint = cell_[u];
      break;
    }
  cc_[t] = dt_.circumcentre(t);
  value_[t] = level_.value(cc_[t], hint);
  birth_[t] = ++births_;
  ++stats_.tets_classified;
}

void SampleTriangulation::set_level(double c) {
  level_ = LevelSet(*skin_, c);
  if (batch_) return;
  ensure_capacity();
  queue_ = {};
  dt_.for_each_tet([&](Index t) { classify(t); });
  dt_.for_each_tet([&](Index t) {
    for (int f = 0; f < 4; ++f) {
      const Index n = dt_.neighbor(t, f);
      if (n != kInvalidIndex && n < t) continue;  // each facet once
      queue_if_bad(t, f);
    }
  });
}

void SampleTriangulation::begin_batch() { batch_ = true; }

void SampleTriangulation::end_batch() {
  batch_ = false;
  set_level(level_.level());
}

void SampleTriangulation::after_operation() {
  ensure_capacity();
  if (batch_) return;
  // Marks of this operation: op_ = evaluated, op_ + 1 = its facets queued.
  if (op_ >= 0xFFFFFFF0u) {
    std::fill(op_mark_.begin(), op_mark_.end(), 0u);
    op_ = 0;
  }
  op_ += 2;
  const auto& created = dt_.last_created();
  for (const Index t : created) {
    if (!dt_.is_live(t) || op_mark_[t] == op_) continue;
    op_mark_[t] = op_;
    classify(t);
  }
  for (const Index t : created) {
    if (!dt_.is_live(t) || op_mark_[t] != op_) continue;
    op_mark_[t] = op_ + 1;
    for (int f = 0; f < 4; ++f) {
      const Index n = dt_.neighbor(t, f);
      if (n != kInvalidIndex && op_mark_[n] == op_ + 1) continue;  // queued from n
      queue_if_bad(t, f);
    }
  }
}

bool SampleTriangulation::restricted(Index t, int face) const {
  const Index n = dt_.neighbor(t, face);
  if (n == kInvalidIndex) return false;
  return (value_[t] < 0) != (value_[n] < 0);
}

double SampleTriangulation::facet_ratio(Index t, int face) const {
  const auto& v = dt_.tet(t);
  const auto& fv = DelaunayTriangulation::kFaceVertices[face];
  double rmin = kInfinity;
  for (const int k : fv) {
    const Index u = v[k];
    if (DelaunayTriangulation::is_bounding(u)) return kInfinity;
    rmin = std::min(rmin, rho_[u]);
  }
  const double R = skin::circumradius(dt_.point(v[fv[0]]), dt_.point(v[fv[1]]), dt_.point(v[fv[2]]));
  return R / (size_.C * size_.Q * std::max(rmin, rho_floor_));
}

void SampleTriangulation::queue_if_bad(Index t, int face) {
  if (!restricted(t, face)) return;
  ++stats_.facets_tested;
  const double ratio = facet_ratio(t, face);
  if (ratio < 1.0) return;
  queue_.push(Facet{ratio, t, face, birth_[t]});
}

bool SampleTriangulation::insert_centre(Index t, int face) {
  const Index n = dt_.neighbor(t, face);
  Index hint = kInvalidIndex;
  for (const int k : DelaunayTriangulation::kFaceVertices[face]) {
    const Index u = dt_.tet(t)[k];
    if (!DelaunayTriangulation::is_bounding(u)) {
      hint = cell_[u];
      break;
    }
  }
  Vec3 m;
  double rho = 0;
  if (!level_.crossing(cc_[t], cc_[n], value_[t], value_[n], m, hint, rho)) {
    ++stats_.failed_insertions;
    return false;
  }
  Index v = kInvalidIndex;
  try {
    v = dt_.insert(m, t);
  } catch (const InputError&) {  // equal to a sample
    ++stats_.failed_insertions;
    return false;
  }
  ensure_capacity();
  rho_[v] = rho;
  cell_[v] = hint;
  seed_[v] = 0;
  after_operation();
  return true;
}

Index SampleTriangulation::add_sample(const Vec3& x, Index cell, double rho, bool seed) {
  Index v = kInvalidIndex;
  try {
    v = dt_.insert(x);
  } catch (const InputError&) {
    return kInvalidIndex;
  }
  ensure_capacity();
  rho_[v] = rho;
  cell_[v] = cell;
  seed_[v] = seed ? 1 : 0;
  if (seed) ++stats_.seeds;
  after_operation();
  return v;
}

void SampleTriangulation::remove_sample(Index v) {
  dt_.remove(v);
  after_operation();
}

bool SampleTriangulation::move_sample(Index v, const Vec3& x, Index cell, double rho) {
  try {
    dt_.move(v, x);
  } catch (const InputError&) {
    return false;
  }
  rho_[v] = rho;
  cell_[v] = cell;
  ++stats_.moves;
  after_operation();
  return true;
}

void SampleTriangulation::mark_all_as_seeds() {
  for (Index v = DelaunayTriangulation::kNumBounding; v < dt_.vertex_capacity(); ++v)
    if (dt_.is_vertex(v)) seed_[v] = 1;
}

std::size_t SampleTriangulation::add_ring(Index v) {
  const skin::MixedComplex& mc = skin_->mixed_complex();
  const Vec3 x = dt_.point(v);
  const Vec3 n = mc.gradient(cell_[v], x).normalized();
  const Vec3 u = n.unitOrthogonal(), w = n.cross(u);
  // Six samples at half the local length scale around v in its tangent plane:
  // [chosen] a regular hexagon of edge d, which the refinement then adjusts.
  constexpr int kRingSamples = 6;
  constexpr double kRingRadius = 0.5;  // times max(rho, the floor)
  const double d = kRingRadius * std::max(rho_[v], rho_floor_);
  std::size_t added = 0;
  for (int k = 0; k < kRingSamples; ++k) {
    const double a = k * (kPi / 3);
    Vec3 y;
    Index cell = cell_[v];
    double rho = 0;
    if (!level_.project(x + d * (std::cos(a) * u + std::sin(a) * w), y, cell, rho)) continue;
    if (add_sample(y, cell, rho, true) != kInvalidIndex) {
      ++stats_.ring_samples;
      ++added;
    }
  }
  return added;
}

std::vector<Index> SampleTriangulation::samples() const {
  std::vector<Index> out;
  out.reserve(dt_.num_vertices());
  for (Index v = DelaunayTriangulation::kNumBounding; v < dt_.vertex_capacity(); ++v)
    if (dt_.is_vertex(v)) out.push_back(v);
  return out;
}

void SampleTriangulation::process_queue() {
  while (!queue_.empty()) {
    const Facet e = queue_.top();
    queue_.pop();
    if (!dt_.is_live(e.tet) || birth_[e.tet] != e.birth || !restricted(e.tet, e.face)) continue;
    const bool bounding = e.ratio == kInfinity;
    if (insert_centre(e.tet, e.face)) ++(bounding ? stats_.bounding_insertions : stats_.u_insertions);
  }
}

SampleTriangulation::RoundReport SampleTriangulation::scan() const {
  RoundReport rep;
  // Directed link edges (v, a, b): triangle (v, a, b) counter-clockwise.
  struct Link {
    Index v, a, b;
    bool operator<(const Link& o) const { return v != o.v ? v < o.v : a < o.a; }
  };
  std::vector<Link> links;
  std::vector<std::uint8_t> used(dt_.vertex_capacity(), 0);
  for_each_restricted_facet([&](Index t, int f, const std::array<Index, 3>& tri) {
    if (const double ratio = facet_ratio(t, f); !(ratio < 1.0)) {
      ++rep.u;
      rep.u_facets.push_back(Facet{ratio, t, f, birth_[t]});
    }
    for (int k = 0; k < 3; ++k) {
      const Index p = tri[k], q = tri[(k + 1) % 3], r = tri[(k + 2) % 3];
      links.push_back({p, q, r});
      used[p] = 1;
      if (p < q && !DelaunayTriangulation::is_bounding(p) && !DelaunayTriangulation::is_bounding(q) &&
          !skin::satisfies_L(dt_.point(p), dt_.point(q), rho_[p], rho_[q], size_))
        rep.l_edges.push_back({p, q});
    }
  });
  std::sort(links.begin(), links.end());
  // A vertex's star is a disc iff its directed link edges a -> b form one
  // cycle: every a once as a source, every b once as a target, one orbit.
  for (std::size_t i = 0; i < links.size();) {
    std::size_t j = i;
    while (j < links.size() && links[j].v == links[i].v) ++j;
    const Index v = links[i].v;
    bool disc = j - i >= 3 && !DelaunayTriangulation::is_bounding(v);
    for (std::size_t k = i + 1; disc && k < j; ++k)
      if (links[k].a == links[k - 1].a) disc = false;  // a source twice
    if (disc) {
      // Follow the cycle from links[i].
      Index cur = links[i].b;
      std::size_t steps = 1;
      while (cur != links[i].a && steps <= j - i) {
        const auto it = std::lower_bound(links.begin() + i, links.begin() + j, Link{v, cur, 0});
        if (it == links.begin() + j || it->a != cur) {
          disc = false;
          break;
        }
        cur = it->b;
        ++steps;
      }
      if (cur != links[i].a || steps != j - i) disc = false;
    }
    if (!disc && !DelaunayTriangulation::is_bounding(v)) rep.bad_vertices.push_back(v);
    i = j;
  }
  for (Index v = DelaunayTriangulation::kNumBounding; v < dt_.vertex_capacity(); ++v)
    if (dt_.is_vertex(v) && !used[v]) rep.isolated.push_back(v);
  return rep;
}

bool SampleTriangulation::refine(int max_rounds) {
  std::vector<Index> star;
  for (int round = 0; round < max_rounds; ++round) {
    process_queue();
    const RoundReport rep = scan();
    stats_.L_left = rep.l_edges.size();
    stats_.U_left = rep.u;
    stats_.nonmanifold_left = rep.bad_vertices.size();
    if (rep.l_edges.empty() && rep.bad_vertices.empty() && rep.isolated.empty() && rep.u == 0) return true;
    ++stats_.rounds;
    std::size_t actions = 0;
    // [U] facets the queue does not hold (e.g. after set_rho_floor()).
    for (const Facet& f : rep.u_facets) queue_.push(f);
    actions += rep.u_facets.size();
    // [L]: contract by deleting a seed endpoint (the later one of two seeds).
    for (const auto& [a, b] : rep.l_edges) {
      if (!dt_.is_vertex(a) || !dt_.is_vertex(b)) continue;
      const Index v = seed_[a] && seed_[b] ? std::max(a, b) : seed_[a] ? a : seed_[b] ? b : kInvalidIndex;
      if (v == kInvalidIndex) continue;
      remove_sample(v);
      ++stats_.l_deletions;
      ++actions;
    }
    // A star that is not a disc: insert the centre of its largest restricted facet.
    for (const Index v : rep.bad_vertices) {
      if (!dt_.is_vertex(v)) continue;
      dt_.incident_tets(v, star);
      double best = -1;
      Index bt = kInvalidIndex;
      int bf = -1;
      for (const Index t : star) {
        const int lv = dt_.local_index(t, v);
        for (int f = 0; f < 4; ++f) {
          if (f == lv || !restricted(t, f) || !(value_[t] < 0)) continue;
          const auto& tv = dt_.tet(t);
          const auto& fv = DelaunayTriangulation::kFaceVertices[f];
          const double R = skin::circumradius(dt_.point(tv[fv[0]]), dt_.point(tv[fv[1]]), dt_.point(tv[fv[2]]));
          if (R > best) best = R, bt = t, bf = f;
        }
      }
      if (bt != kInvalidIndex && insert_centre(bt, bf)) {
        ++stats_.manifold_insertions;
        ++actions;
      }
    }
    // A sample no restricted facet uses (e.g. the only samples of a small
    // cavity): first a ring of six samples around it, at 0.5 rho in its
    // tangent plane, projected onto the level set (on the same sheet: the
    // sandwiching balls of radius rho); if it is still unused, it goes.
    for (const Index v : rep.isolated) {
      if (!dt_.is_vertex(v)) continue;
      if (!ringed_[v]) {
        ringed_[v] = 1;
        actions += add_ring(v);
        continue;
      }
      if (!seed_[v]) continue;
      remove_sample(v);
      ++stats_.isolated_deletions;
      ++actions;
    }
    if (actions == 0 && queue_.empty()) return false;
  }
  process_queue();
  const RoundReport rep = scan();
  stats_.L_left = rep.l_edges.size();
  stats_.U_left = rep.u;
  stats_.nonmanifold_left = rep.bad_vertices.size();
  return rep.l_edges.empty() && rep.bad_vertices.empty() && rep.u == 0;
}

geometry::IndexedMesh SampleTriangulation::extract(std::vector<Index>* vertex_ids, skin::SkinVertexData* data) const {
  geometry::IndexedMesh mesh;
  if (data != nullptr) *data = skin::SkinVertexData();
  std::vector<Index> local(dt_.vertex_capacity(), kInvalidIndex);
  std::vector<std::array<Index, 3>> tris;
  for_each_restricted_facet([&](Index, int, const std::array<Index, 3>& tri) {
    tris.push_back(tri);
    for (const Index u : tri) local[u] = 0;
  });
  if (vertex_ids) vertex_ids->clear();
  const skin::MixedComplex& mc = skin_->mixed_complex();
  for (Index v = 0; v < dt_.vertex_capacity(); ++v) {
    if (local[v] == kInvalidIndex) continue;
    local[v] = static_cast<Index>(mesh.positions.size());
    const Vec3& x = dt_.point(v);
    mesh.positions.push_back(x);
    const bool bounding = DelaunayTriangulation::is_bounding(v);
    mesh.normals.push_back(bounding ? Vec3::UnitZ() : Vec3(mc.gradient(cell_[v], x).normalized()));
    // The vertex data only when asked: the recorder extracts a mesh per frame without it.
    if (data != nullptr) {
      data->atom.push_back(bounding ? -1 : static_cast<std::int32_t>(skin_->atom_of(cell_[v], x)));
      data->rho.push_back(bounding ? 0 : rho_[v]);
      data->patch.push_back(bounding ? 0 : mc.cell(cell_[v]).dim);
    }
    if (vertex_ids) vertex_ids->push_back(v);
  }
  mesh.triangles.reserve(tris.size());
  for (const auto& t : tris) mesh.triangles.push_back({local[t[0]], local[t[1]], local[t[2]]});
  return mesh;
}

}  // namespace skinmesh::dynamic
