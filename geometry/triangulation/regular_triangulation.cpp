// geometry/triangulation/regular_triangulation.cpp: incremental construction of the regular
// triangulation (see regular_triangulation.h for the ideas and references).
#include "geometry/triangulation/regular_triangulation.h"
#include "geometry/triangulation/walk.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <utility>

#include "core/assert.h"
#include "core/errors.h"
#include "geometry/kernel/predicates.h"

namespace skinmesh::geometry {

// Hilbert Curve Definitions ---------------------------------------------------

namespace detail {

std::uint64_t hilbert_key(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  // Skilling (2004): transform the coordinates in place into the "transposed"
  // Hilbert index, then interleave its bits (most significant first).
  std::uint32_t X[3] = {x & kHilbertMask, y & kHilbertMask, z & kHilbertMask};
  const std::uint32_t top = 1u << (kHilbertBits - 1);
  // Undo the excess work of the recursive construction (rotations/reflections),
  // branch-free: if bit q of X[i] is set, invert the low bits of X[0], else
  // exchange the low bits of X[0] and X[i] (a no-op for i = 0).
  for (std::uint32_t q = top; q > 1; q >>= 1) {
    const std::uint32_t p = q - 1;
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t set = 0u - ((X[i] & q) != 0);  // all ones iff the bit is set
      const std::uint32_t t = (X[0] ^ X[i]) & p & ~set;
      X[0] ^= t | (p & set);
      X[i] ^= t;
    }
  }
  // Gray encode.
  X[1] ^= X[0];
  X[2] ^= X[1];
  std::uint32_t t = 0;
  for (std::uint32_t q = top; q > 1; q >>= 1)
    if (X[2] & q) t ^= q - 1;
  for (auto& c : X) c ^= t;
  std::uint64_t key = 0;
  for (int b = kHilbertBits - 1; b >= 0; --b)
    for (int i = 0; i < 3; ++i) key = (key << 1) | ((X[i] >> b) & 1u);
  return key;
}

}  // namespace detail

// RegularTriangulation Method Definitions -------------------------------------

namespace {

// Throws InputError for the constructor (no file: the caller passed the points).
[[noreturn]] void throw_input_error(const std::string& problem) {
  throw InputError("", 0, "regular triangulation: " + problem);
}

// Minimum size of the first BRIO round.
constexpr Index kBrioFirstRound = 64;

}  // namespace

RegularTriangulation::RegularTriangulation(std::span<const WeightedPoint> points, std::uint64_t seed) {
  // Validate the input ----------------------------------------------------
  if (points.empty()) {
    throw_input_error("no points");
  }
  if (points.size() > std::size_t(kInvalidIndex) / 8) {
    throw_input_error("too many points");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const WeightedPoint& p = points[i];
    if (!std::isfinite(p.z.x()) || !std::isfinite(p.z.y()) || !std::isfinite(p.z.z()) || !std::isfinite(p.w)) {
      throw_input_error("point " + std::to_string(i) + " has a non-finite coordinate or weight");
    }
    if (p.z.cwiseAbs().maxCoeff() > kMaxCoordinate || std::abs(p.w) > kMaxWeight) {
      std::ostringstream os;
      os << "point " << i << " (" << p.z.x() << ", " << p.z.y() << ", " << p.z.z() << "; weight " << p.w
         << ") is outside the supported range: coordinates within ±" << kMaxCoordinate << " Å, weights within ±"
         << kMaxWeight << " Å²";
      throw_input_error(os.str());
    }
  }
  n_input_ = static_cast<Index>(points.size());

  // Compute the bounding tetrahedron: centre c, circumradius D = 50 L' ----
  Vec3 lo = points[0].z, hi = points[0].z;
  for (const auto& p : points) {
    lo = lo.cwiseMin(p.z);
    hi = hi.cwiseMax(p.z);
  }
  const Vec3 c = 0.5 * (lo + hi);
  double extent = 0.0;  // L' (Å)
  for (const auto& p : points) {
    extent = std::max(extent, (p.z - c).norm() + std::sqrt(std::max(p.w, 0.0)));
  }
  constexpr double kMinExtent = 1.0;        // Å: L' >= 1 Å (e.g. coincident points)
  constexpr double kBoundingFactor = 50.0;  // D / L' (> ~7 needed, see the header)
  extent = std::max(extent, kMinExtent);
  bounding_centre_ = c;
  bounding_radius_ = kBoundingFactor * extent;
  points_.assign(points.begin(), points.end());
  // Regular tetrahedron: alternate corners of a cube, |corner| = D.
  const double s = bounding_radius_ / std::sqrt(3.0);
  const Vec3 corners[4] = {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)};
  for (const Vec3& corner : corners) points_.push_back(WeightedPoint{c + s * corner, 0.0});

  // Initial triangulation: the bounding tetrahedron -----------------------
  const Index n = n_input_;
  const std::size_t expected_tets = 7 * std::size_t(n) + 64;
  cells_.reserve(expected_tets);
  tet_mark_.reserve(expected_tets);
  // During construction, vertices are numbered in insertion order (bounding
  // points 0..3, then the inputs in BRIO order) for memory locality; work_ids_
  // maps these back to the input indices, which SoS uses, so the result does
  // not depend on the order. compact() renumbers to input indices.
  const std::vector<Index> order = insertion_order(seed);
  work_ids_ = {n, n + 1, n + 2, n + 3};
  work_ids_.insert(work_ids_.end(), order.begin(), order.end());
  work_points_.resize(n + 4);
  for (Index k = 0; k < n + 4; ++k) work_points_[k] = points_[work_ids_[k]];
  vertex_tet_.assign(n + 4, kInvalidIndex);
  vertex_state_.assign(n + 4, PointState::NotInserted);
  vertex_mark_.assign(n + 4, 0);
  std::array<Index, 4> first = {0, 1, 2, 3};
  if (orient3d(work_points_[0].z, work_points_[1].z, work_points_[2].z, work_points_[3].z) != Sign::Positive) {
    std::swap(first[0], first[1]);
  }
  SKINMESH_ASSERT(orient3d(work_points_[first[0]].z, work_points_[first[1]].z, work_points_[first[2]].z,
                           work_points_[first[3]].z) == Sign::Positive);
  cells_.push_back(Cell{first, {kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex}});
  tet_mark_.push_back(0);
  for (Index v = 0; v < 4; ++v) {
    vertex_tet_[v] = 0;
    vertex_state_[v] = PointState::Vertex;
  }

  // Insert the inputs in BRIO order ----------------------------------------
  walk_rng_ = seed * 0x9E3779B97F4A7C15ULL + 0x632BE59BD9B4E019ULL;
  if (walk_rng_ == 0) walk_rng_ = 1;
  stack_.reserve(64);
  conflict_.reserve(64);
  boundary_.reserve(128);
  cavity_vertices_.reserve(64);
  for (Index v = 4; v < n + 4; ++v) insert(v);

  compact();
}

// Insertion order: BRIO rounds, each sorted along the Hilbert curve.
std::vector<Index> RegularTriangulation::insertion_order(std::uint64_t seed) const {
  const Index n = n_input_;
  std::vector<Index> order(n);
  std::iota(order.begin(), order.end(), Index{0});
  // Fisher-Yates with a fully specified generator (std::shuffle is not
  // specified, so it would not be reproducible across standard libraries).
  std::mt19937_64 rng(seed);
  for (Index i = n; i > 1; --i) {
    const Index j = static_cast<Index>(rng() % i);
    std::swap(order[i - 1], order[j]);
  }
  // Hilbert keys on a 2^16 grid over the inputs' bounding box.
  Vec3 lo = points_[0].z, hi = points_[0].z;
  for (Index v = 0; v < n; ++v) {
    lo = lo.cwiseMin(points_[v].z);
    hi = hi.cwiseMax(points_[v].z);
  }
  const double span = std::max((hi - lo).maxCoeff(), 1e-300);
  const double scale = double(detail::kHilbertMask) / span;
  auto key = [&](Index v) {
    const Vec3 q = (points_[v].z - lo) * scale;
    auto cell = [](double x) { return static_cast<std::uint32_t>(std::clamp(x, 0.0, double(detail::kHilbertMask))); };
    return detail::hilbert_key(cell(q.x()), cell(q.y()), cell(q.z()));
  };
  // Rounds: [0, m0), [m0, 2 m0), ..., [n/2, n): the last round holds half the
  // points, the one before it a quarter, and so on (Amenta et al.).
  std::vector<std::pair<std::uint64_t, Index>> keyed;
  Index end = n;
  std::vector<std::pair<Index, Index>> rounds;
  while (end > kBrioFirstRound) {
    rounds.emplace_back(end / 2, end);
    end /= 2;
  }
  rounds.emplace_back(0, end);
  std::reverse(rounds.begin(), rounds.end());
  for (const auto& [b, e] : rounds) {
    keyed.clear();
    for (Index k = b; k < e; ++k) keyed.emplace_back(key(order[k]), order[k]);
    std::sort(keyed.begin(), keyed.end());
    for (Index k = b; k < e; ++k) order[k] = keyed[k - b].second;
  }
  return order;
}

Index RegularTriangulation::new_tet() {
  if (!free_tets_.empty()) {
    const Index t = free_tets_.back();
    free_tets_.pop_back();
    return t;
  }
  cells_.push_back({});
  tet_mark_.push_back(0);
  return static_cast<Index>(cells_.size() - 1);
}

// Inserts input v: locate, test for redundancy, grow the conflict region,
// re-triangulate the cavity as the cone from v over its boundary.
void RegularTriangulation::insert(Index v) {
  const WeightedPoint& p = work_points_[v];
  const Index start = walk(work_points_, p.z, last_tet_, walk_rng_, &stats_.walk_steps, &stats_.walk_fallbacks);
  SKINMESH_ASSERT_MSG(start != kInvalidIndex, "input point outside the bounding tetrahedron");
  if (work_conflict(start, v) != Sign::Positive) {
    // The lifted point lies above the lower hull: redundant, never inserted.
    vertex_state_[v] = PointState::Redundant;
    last_tet_ = start;
    return;
  }

  // Grow the conflict region: depth-first search over neighbours -------------
  ++generation_;
  const std::uint32_t in_cavity = 2 * generation_, outside = 2 * generation_ + 1;
  cavity_vertices_.clear();
  cavity::grow(
      cells_, tet_mark_, in_cavity, outside, start, v, [&](Index u) { return work_conflict(u, v); },
      [&](Index t) {
        for (const Index w : cells_[t].v) {
          if (vertex_mark_[w] != in_cavity) {
            vertex_mark_[w] = in_cavity;
            cavity_vertices_.push_back(w);
          }
        }
      },
      stack_, conflict_, boundary_);
  stats_.conflict_tets += conflict_.size();

  // Delete the conflict tetrahedra ---------------------------------------------
  for (const Index t : conflict_) {
    cells_[t].v[0] = kInvalidIndex;  // dead
    free_tets_.push_back(t);
  }

  // Create the cone from v over the cavity boundary ---------------------------
  const auto mask_shift = cavity::prepare_edge_table(edge_table_, boundary_.size());
  const std::uint32_t on_boundary = outside;  // vertex mark: vertex of a new tet
  Index nt = kInvalidIndex;
  for (const cavity::Facet& f : boundary_) {
    nt = new_tet();
    cells_[nt].v = f.vertices;
    cells_[nt].n[f.i] = f.outside;
    if (f.outside != kInvalidIndex) cells_[f.outside].n[f.outside_face] = nt;
    SKINMESH_DEBUG_ASSERT(orient3d(work_points_[f.vertices[0]].z, work_points_[f.vertices[1]].z,
                                   work_points_[f.vertices[2]].z, work_points_[f.vertices[3]].z) == Sign::Positive);
    for (const Index w : f.vertices) {
      vertex_tet_[w] = nt;
      vertex_mark_[w] = on_boundary;
    }
    // Link the three faces through v with the neighbouring new tetrahedra,
    // matched by their edge on the cavity boundary.
    cavity::link_cone_faces(cells_, edge_table_, mask_shift, generation_, nt, f);
  }

  // Vertices of the old cavity that are not on its boundary are now hidden ----
  for (const Index w : cavity_vertices_) {
    if (vertex_mark_[w] != on_boundary) {
      vertex_state_[w] = PointState::Hidden;
      vertex_tet_[w] = kInvalidIndex;
      ++stats_.hidden_vertices;
    }
  }
  vertex_state_[v] = PointState::Vertex;
  last_tet_ = nt;
}

// The remembering stochastic visibility walk (geometry/triangulation/walk.h).
Index RegularTriangulation::walk(std::span<const WeightedPoint> pts, const Vec3& p, Index start, std::uint64_t& rng,
                                 std::uint64_t* steps, std::uint64_t* fallbacks) const {
  return walk::locate(cells_, pts, p, start, rng, steps, fallbacks, [&] { return locate_by_scan(pts, p); });
}

bool RegularTriangulation::contains(std::span<const WeightedPoint> pts, Index t, const Vec3& p) const {
  const std::array<Index, 4>& tv = cells_[t].v;
  for (const auto& f : kFaceVertices) {
    if (orient3d(pts[tv[f[0]]].z, pts[tv[f[1]]].z, pts[tv[f[2]]].z, p) == Sign::Negative) return false;
  }
  return true;
}

Index RegularTriangulation::locate_by_scan(std::span<const WeightedPoint> pts, const Vec3& p) const {
  for (Index t = 0; t < cells_.size(); ++t) {
    if (cells_[t].v[0] != kInvalidIndex && contains(pts, t, p)) return t;
  }
  return kInvalidIndex;
}

// Removes the deleted tetrahedra and renumbers the others (order preserved);
// renumbers the vertices from insertion order to input indices.
void RegularTriangulation::compact() {
  const Index total = static_cast<Index>(cells_.size());
  std::vector<Index> remap(total, kInvalidIndex);
  Index alive = 0;
  for (Index t = 0; t < total; ++t) {
    if (cells_[t].v[0] != kInvalidIndex) remap[t] = alive++;
  }
  for (Index t = 0; t < total; ++t) {
    const Index r = remap[t];
    if (r == kInvalidIndex) continue;
    std::array<Index, 4> nb = cells_[t].n;
    for (Index& u : nb) {
      if (u != kInvalidIndex) u = remap[u];
    }
    for (int k = 0; k < 4; ++k) cells_[r].v[k] = work_ids_[cells_[t].v[k]];
    cells_[r].n = nb;
  }
  cells_.resize(alive);
  cells_.shrink_to_fit();
  const Index np = static_cast<Index>(points_.size());
  std::vector<Index> vertex_tet(np, kInvalidIndex);
  std::vector<PointState> vertex_state(np, PointState::NotInserted);
  for (Index k = 0; k < np; ++k) {
    const Index t = vertex_tet_[k];
    vertex_tet[work_ids_[k]] = t == kInvalidIndex ? kInvalidIndex : remap[t];
    vertex_state[work_ids_[k]] = vertex_state_[k];
  }
  vertex_tet_ = std::move(vertex_tet);
  vertex_state_ = std::move(vertex_state);
  work_ids_ = {};
  work_points_ = {};
  // Release the construction scratch.
  free_tets_ = {};
  tet_mark_ = {};
  vertex_mark_ = {};
  stack_ = {};
  conflict_ = {};
  cavity_vertices_ = {};
  boundary_ = {};
  edge_table_ = {};
  last_tet_ = 0;
}

// Accessors and queries ---------------------------------------------------------

bool RegularTriangulation::is_vertex(Index v) const {
  SKINMESH_DEBUG_ASSERT(v < points_.size());
  return vertex_state_[v] == PointState::Vertex;
}

std::vector<Index> RegularTriangulation::redundant_points() const {
  std::vector<Index> out;
  for (Index v = 0; v < n_input_; ++v) {
    if (vertex_state_[v] != PointState::Vertex) out.push_back(v);
  }
  return out;
}

Index RegularTriangulation::vertex_tet(Index v) const {
  SKINMESH_DEBUG_ASSERT(v < vertex_tet_.size());
  return vertex_tet_[v];
}

Index RegularTriangulation::locate(const Vec3& p, Index hint) const {
  if (cells_.empty()) return kInvalidIndex;
  const Index start = (hint == kInvalidIndex || hint >= num_tets()) ? 0 : hint;
  std::uint64_t rng = 0x9E3779B97F4A7C15ULL ^ (std::uint64_t(start) << 17);
  return walk(points_, p, start, rng, nullptr, nullptr);
}

Sign RegularTriangulation::work_conflict(Index t, Index v) const {
  const std::array<Index, 4>& tv = cells_[t].v;
  const WeightedPoint* p = work_points_.data();
  const Index* id = work_ids_.data();
  return power_test_sos(p[tv[0]], p[tv[1]], p[tv[2]], p[tv[3]], p[v], id[tv[0]], id[tv[1]], id[tv[2]], id[tv[3]],
                        id[v]);
}

Sign RegularTriangulation::conflict(Index t, Index v) const {
  const std::array<Index, 4>& tv = cells_[t].v;
  return power_test_sos(points_[tv[0]], points_[tv[1]], points_[tv[2]], points_[tv[3]], points_[v], tv[0], tv[1], tv[2],
                        tv[3], v);
}

}  // namespace skinmesh::geometry
