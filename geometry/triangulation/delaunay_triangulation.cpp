// geometry/triangulation/delaunay_triangulation.cpp: dynamic Delaunay triangulation (see
// delaunay_triangulation.h for the ideas and references, and
// papers/geometry/triangulation/delaunay_triangulation.md for the deletion argument).
#include "geometry/triangulation/delaunay_triangulation.h"
#include "geometry/triangulation/walk.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <sstream>
#include <unordered_set>
#include <utility>

#include "core/assert.h"
#include "core/errors.h"
#include "geometry/kernel/predicates.h"

namespace skinmesh::geometry {

namespace {

[[noreturn]] void throw_input_error(const std::string& problem) {
  throw InputError("", 0, "delaunay triangulation: " + problem);
}

std::string format_point(const Vec3& p) {
  std::ostringstream os;
  os.precision(17);
  os << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return os.str();
}

std::uint64_t walk_seed(Index start) {
  const std::uint64_t s = 0x9E3779B97F4A7C15ULL ^ (std::uint64_t(start) << 17);
  return s == 0 ? 1 : s;
}

// True iff (a, b, c) is a cyclic rotation of (x, y, z), which must hold the
// same three values: the two triangles have the same orientation.
bool same_orientation(const std::array<Index, 3>& abc, const std::array<Index, 3>& xyz) {
  int p = 0;
  while (xyz[p] != abc[0]) ++p;
  return xyz[(p + 1) % 3] == abc[1];
}

// Key of an unordered triangle of vertex numbers < 2^21.
constexpr Index kMaxLinkVertices = Index(1) << 21;
std::uint64_t triangle_key(Index a, Index b, Index c) {
  if (a > b) std::swap(a, b);
  if (b > c) std::swap(b, c);
  if (a > b) std::swap(a, b);
  return (std::uint64_t(a) << 42) | (std::uint64_t(b) << 21) | std::uint64_t(c);
}

}  // namespace

// Mesh Method Definitions ---------------------------------------------------------

void DelaunayTriangulation::Mesh::reset(const std::array<Vec3, 4>& corners) {
  points.clear();
  sos.clear();
  vertex_tet.clear();
  cells.clear();
  free_cells.clear();
  cell_mark.clear();
  created.clear();
  for (Index k = 0; k < 4; ++k) {
    points.push_back(WeightedPoint{corners[k], 0.0});
    sos.push_back(k);
    vertex_tet.push_back(0);
  }
  std::array<Index, 4> first = {0, 1, 2, 3};
  if (orient3d(corners[0], corners[1], corners[2], corners[3]) != Sign::Positive) std::swap(first[0], first[1]);
  SKINMESH_ASSERT(orient3d(corners[first[0]], corners[first[1]], corners[first[2]], corners[first[3]]) ==
                  Sign::Positive);
  cells.push_back(Cell{first, {kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex}});
  cell_mark.push_back(0);
  live_cells = 1;
  last_cell = 0;
}

Index DelaunayTriangulation::Mesh::add_vertex(const Vec3& p, Index sos_index) {
  points.push_back(WeightedPoint{p, 0.0});
  sos.push_back(sos_index);
  vertex_tet.push_back(kInvalidIndex);
  return static_cast<Index>(points.size() - 1);
}

Index DelaunayTriangulation::Mesh::new_cell() {
  ++live_cells;
  if (!free_cells.empty()) {
    const Index t = free_cells.back();
    free_cells.pop_back();
    created.push_back(t);
    return t;
  }
  created.push_back(static_cast<Index>(cells.size()));
  SKINMESH_ASSERT_MSG(cells.size() < std::size_t(kInvalidIndex) - 1, "too many tetrahedra");
  cells.push_back(Cell{});
  cell_mark.push_back(0);
  return static_cast<Index>(cells.size() - 1);
}

void DelaunayTriangulation::Mesh::kill_cell(Index t) {
  cells[t].v[0] = kInvalidIndex;
  free_cells.push_back(t);
  --live_cells;
}

std::uint32_t DelaunayTriangulation::Mesh::next_generation() {
  // Marks 2g (inside) and 2g + 1 (outside) for generation g >= 1.
  if (generation >= 0x7FFFFFFEu) {
    std::fill(cell_mark.begin(), cell_mark.end(), 0u);
    for (cavity::EdgeSlot& e : edge_table) e.stamp = 0;
    generation = 0;
  }
  return ++generation;
}

Sign DelaunayTriangulation::Mesh::conflict_with(Index t, Index v) const {
  const std::array<Index, 4>& tv = cells[t].v;
  return power_test_sos(points[tv[0]], points[tv[1]], points[tv[2]], points[tv[3]], points[v], sos[tv[0]], sos[tv[1]],
                        sos[tv[2]], sos[tv[3]], sos[v]);
}

bool DelaunayTriangulation::Mesh::contains(Index t, const Vec3& p) const {
  const std::array<Index, 4>& tv = cells[t].v;
  for (const auto& f : kFaceVertices) {
    if (orient3d(points[tv[f[0]]].z, points[tv[f[1]]].z, points[tv[f[2]]].z, p) == Sign::Negative) return false;
  }
  return true;
}

Index DelaunayTriangulation::Mesh::scan(const Vec3& p) const {
  for (Index t = 0; t < cells.size(); ++t) {
    if (cells[t].v[0] != kInvalidIndex && contains(t, p)) return t;
  }
  return kInvalidIndex;
}

// Remembering stochastic visibility walk: leave the current tetrahedron
// through a face whose plane separates it strictly from p; faces are tried in
// a random cyclic order, and the face just crossed is not tested again (p is
// strictly on this side of it).
Index DelaunayTriangulation::Mesh::walk(const Vec3& p, Index start, std::uint64_t& rng, std::uint64_t* steps,
                                        std::uint64_t* fallbacks) const {
  // The remembering stochastic visibility walk (geometry/triangulation/walk.h);
  // a cycle is not expected for Delaunay, but scan() decides if one occurs.
  return walk::locate(cells, points, p, start, rng, steps, fallbacks, [&] { return scan(p); });
}

// Bowyer-Watson: `start` is a live cell whose closed hull contains the new
// vertex v (not a vertex of the mesh at the same position). Grows the
// conflict region by depth-first search, kills it and fills it with the cone
// from v over its boundary.
void DelaunayTriangulation::Mesh::insert_vertex(Index v, Index start, std::uint64_t* conflict_count) {
  // A point in the closed hull of t that is not a vertex of t lies strictly
  // inside t's circumsphere, so the start is in conflict without SoS.
  SKINMESH_ASSERT_MSG(conflict_with(start, v) == Sign::Positive,
                      "the located tetrahedron is not in conflict with the new point");
  const std::uint32_t g = next_generation();
  const std::uint32_t inside = 2 * g, outside = 2 * g + 1;
  cavity::grow(
      cells, cell_mark, inside, outside, start, v, [&](Index u) { return conflict_with(u, v); }, [](Index) {}, stack,
      conflict, cavity_facets);
  if (conflict_count) *conflict_count += conflict.size();
  for (const Index t : conflict) kill_cell(t);

  // The cavity boundary is a triangulated sphere: every edge is in exactly two
  // facets, and the two cone tetrahedra on them share the face (v, edge).
  // They are matched through an open-addressing table keyed by the edge.
  const auto mask_shift = cavity::prepare_edge_table(edge_table, cavity_facets.size());
  Index nt = kInvalidIndex;
  for (const cavity::Facet& f : cavity_facets) {
    nt = new_cell();
    Cell& c = cells[nt];
    c.v = f.vertices;
    c.n = {kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex};
    c.n[f.i] = f.outside;
    if (f.outside != kInvalidIndex) cells[f.outside].n[f.outside_face] = nt;
    SKINMESH_DEBUG_ASSERT(orient3d(points[c.v[0]].z, points[c.v[1]].z, points[c.v[2]].z, points[c.v[3]].z) ==
                          Sign::Positive);
    for (const Index w : c.v) vertex_tet[w] = nt;
    cavity::link_cone_faces(cells, edge_table, mask_shift, g, nt, f);
  }
  last_cell = nt;
}

// DelaunayTriangulation Method Definitions ------------------------------------------

DelaunayTriangulation::DelaunayTriangulation(const Vec3& lo, const Vec3& hi) : lo_(lo), hi_(hi) {
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(lo[k]) || !std::isfinite(hi[k]))
      throw_input_error("non-finite box " + format_point(lo) + " - " + format_point(hi));
    if (std::abs(lo[k]) > kMaxCoordinate || std::abs(hi[k]) > kMaxCoordinate) {
      std::ostringstream os;
      os << "box " << format_point(lo) << " - " << format_point(hi)
         << " is outside the supported range: coordinates within ±" << kMaxCoordinate << " Å";
      throw_input_error(os.str());
    }
    if (lo[k] > hi[k]) throw_input_error("empty box " + format_point(lo) + " - " + format_point(hi));
  }
  // Bounding tetrahedron: RegularTriangulation's, with L' = half the box
  // diagonal (every point of the box is within L' of its centre).
  constexpr double kMinExtent = 1.0;        // Å
  constexpr double kBoundingFactor = 50.0;  // D / L'
  centre_ = 0.5 * (lo + hi);
  const double extent = std::max(0.5 * (hi - lo).norm(), kMinExtent);
  radius_ = kBoundingFactor * extent;
  const double s = radius_ / std::sqrt(3.0);
  const Vec3 signs[4] = {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)};
  for (int k = 0; k < 4; ++k) corners_[k] = centre_ + s * signs[k];
  mesh_.reset(corners_);
}

void DelaunayTriangulation::check_point(const Vec3& p, const char* what) const {
  if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
    throw_input_error(std::string(what) + ": non-finite point " + format_point(p));
  if ((p.array() < lo_.array()).any() || (p.array() > hi_.array()).any())
    throw_input_error(std::string(what) + ": point " + format_point(p) + " outside the box " + format_point(lo_) +
                      " - " + format_point(hi_));
}

// Locates p (in the box) and refuses it if it coincides with a live vertex
// other than `ignore`.
Index DelaunayTriangulation::locate_checked(const Vec3& p, Index hint, Index ignore) {
  const Index start = mesh_.live(hint) ? hint : mesh_.last_cell;
  const Index t = mesh_.walk(p, start, rng_, &stats_.walk_steps, &stats_.walk_fallbacks);
  SKINMESH_ASSERT_MSG(t != kInvalidIndex, "a point of the box is outside the bounding tetrahedron");
  // A live vertex at p is a vertex of every closed tetrahedron containing p.
  for (const Index w : mesh_.cells[t].v) {
    if (w != ignore && mesh_.points[w].z == p)
      throw_input_error("point " + format_point(p) + " coincides with vertex " + std::to_string(w));
  }
  return t;
}

Index DelaunayTriangulation::insert(const Vec3& p, Index hint) {
  check_point(p, "insert");
  if (mesh_.points.size() >= std::size_t(kInvalidIndex) - 1) throw_input_error("too many vertices");
  const Index t = locate_checked(p, hint, kInvalidIndex);
  mesh_.created.clear();
  const Index v = static_cast<Index>(mesh_.points.size());
  mesh_.add_vertex(p, v);
  mesh_.insert_vertex(v, t, &stats_.conflict_tets);
  ++num_live_vertices_;
  ++stats_.insertions;
  return v;
}

void DelaunayTriangulation::remove(Index v) {
  if (!is_vertex(v) || is_bounding(v))
    throw_input_error("remove: " + std::to_string(v) + " is not a live non-bounding vertex");
  mesh_.created.clear();
  remove_vertex(v);
  --num_live_vertices_;
}

void DelaunayTriangulation::move(Index v, const Vec3& p) {
  if (!is_vertex(v) || is_bounding(v))
    throw_input_error("move: " + std::to_string(v) + " is not a live non-bounding vertex");
  check_point(p, "move");
  if (mesh_.points[v].z == p) {
    mesh_.created.clear();
    return;
  }
  // Refuse a duplicate before changing anything.
  locate_checked(p, mesh_.vertex_tet[v], v);
  mesh_.created.clear();
  // Kinetic fast path: if the star of v, with v at p, is still positively
  // oriented and every facet of it is locally Delaunay, the triangulation of
  // the new point set is the old one (the local Delaunay property of every
  // facet implies the global one; facets outside the star did not change).
  {
    incident_tets(v, star_);
    const Vec3 old = mesh_.points[v].z;
    mesh_.points[v].z = p;
    bool same = true;
    for (const Index t : star_) {
      const auto& c = mesh_.cells[t].v;
      if (orient3d(mesh_.points[c[0]].z, mesh_.points[c[1]].z, mesh_.points[c[2]].z, mesh_.points[c[3]].z) !=
          Sign::Positive) {
        same = false;
        break;
      }
    }
    for (std::size_t k = 0; same && k < star_.size(); ++k) {
      const Index t = star_[k];
      for (int i = 0; i < 4 && same; ++i) {
        const Index u = mesh_.cells[t].n[i];
        if (u == kInvalidIndex) continue;
        int j = 0;
        while (mesh_.cells[u].n[j] != t) ++j;
        if (mesh_.conflict_with(t, mesh_.cells[u].v[j]) != Sign::Negative) same = false;
      }
    }
    if (same) {
      mesh_.created.assign(star_.begin(), star_.end());
      ++stats_.kinetic_moves;
      return;
    }
    mesh_.points[v].z = old;
  }
  remove_vertex(v);
  // Re-insert with the same id (and so the same SoS index).
  mesh_.points[v].z = p;
  const Index t = mesh_.walk(p, mesh_.last_cell, rng_, &stats_.walk_steps, &stats_.walk_fallbacks);
  SKINMESH_ASSERT(t != kInvalidIndex);
  mesh_.insert_vertex(v, t, &stats_.conflict_tets);
  ++stats_.insertions;
}

// Removal (Devillers 2002). The star of v is a ball whose boundary facets are
// faces of the new triangulation; the link vertices L (plus the 4 bounding
// points) are triangulated with the same SoS indices; the tetrahedra of that
// triangulation on v's side of the boundary facets, and those reachable from
// them without crossing a boundary facet, fill the hole exactly (see the note).
void DelaunayTriangulation::remove_vertex(Index v) {
  Mesh& m = mesh_;
  // 1. The star of v (breadth-first over the faces through v).
  star_.clear();
  {
    const std::uint32_t g = m.next_generation();
    const Index t0 = m.vertex_tet[v];
    m.cell_mark[t0] = 2 * g;
    star_.push_back(t0);
    for (std::size_t k = 0; k < star_.size(); ++k) {
      const Index t = star_[k];
      for (int i = 0; i < 4; ++i) {
        if (m.cells[t].v[i] == v) continue;
        const Index u = m.cells[t].n[i];
        SKINMESH_ASSERT(u != kInvalidIndex);  // a face through v is interior
        if (m.cell_mark[u] != 2 * g) {
          m.cell_mark[u] = 2 * g;
          star_.push_back(u);
        }
      }
    }
  }
  stats_.star_tets += star_.size();

  // 2. Local numbering of the link: bounding points keep 0..3, the other link
  // vertices get 4, 5, ... in order of discovery; SoS index = global id.
  if (++removal_stamp_ == 0) {
    std::fill(local_stamp_.begin(), local_stamp_.end(), 0);
    removal_stamp_ = 1;
  }
  if (local_of_.size() < m.points.size()) {
    local_of_.resize(m.points.size(), 0);
    local_stamp_.resize(m.points.size(), 0);
  }
  link_.reset(corners_);
  for (Index w = 0; w < kNumBounding; ++w) {
    local_of_[w] = w;
    local_stamp_[w] = removal_stamp_;
  }
  struct HoleFacet {
    std::uint64_t key;
    std::array<Index, 3> local;  // oriented: v on the positive side
    Index outside;
    int outside_face;
  };
  std::vector<HoleFacet> facets;
  facets.reserve(star_.size());
  for (const Index t : star_) {
    const Cell& c = m.cells[t];
    int i = 0;
    while (c.v[i] != v) ++i;
    HoleFacet f;
    for (int k = 0; k < 3; ++k) {
      const Index w = c.v[kFaceVertices[i][k]];
      if (local_stamp_[w] != removal_stamp_) {
        local_stamp_[w] = removal_stamp_;
        local_of_[w] = link_.add_vertex(m.points[w].z, w);
      }
      f.local[k] = local_of_[w];
    }
    f.key = triangle_key(f.local[0], f.local[1], f.local[2]);
    f.outside = c.n[i];
    f.outside_face = 0;
    if (f.outside != kInvalidIndex) {
      while (m.cells[f.outside].n[f.outside_face] != t) ++f.outside_face;
    }
    facets.push_back(f);
  }
  const Index nlocal = static_cast<Index>(link_.points.size());
  SKINMESH_ASSERT_MSG(nlocal < kMaxLinkVertices, "link too large");
  stats_.link_vertices += nlocal;

  // 3. The Delaunay triangulation of the link and the bounding points.
  std::uint64_t link_rng = walk_seed(v);
  for (Index w = kNumBounding; w < nlocal; ++w) {
    const Index t = link_.walk(link_.points[w].z, link_.last_cell, link_rng, nullptr, nullptr);
    SKINMESH_ASSERT(t != kInvalidIndex);
    link_.insert_vertex(w, t, nullptr);
  }
  stats_.local_tets += link_.live_cells;

  // 4. Find every hole facet in the link triangulation, on v's side.
  std::sort(facets.begin(), facets.end(), [](const HoleFacet& a, const HoleFacet& b) { return a.key < b.key; });
  const Index ncells = static_cast<Index>(link_.cells.size());
  boundary_mask_.assign(ncells, 0);
  boundary_outside_.resize(4 * std::size_t(ncells));
  std::size_t found = 0;
  hole_.clear();
  const std::uint32_t g = link_.next_generation();
  for (Index t = 0; t < ncells; ++t) {
    const Cell& c = link_.cells[t];
    if (c.v[0] == kInvalidIndex) continue;
    for (int i = 0; i < 4; ++i) {
      const auto& fv = kFaceVertices[i];
      const std::uint64_t key = triangle_key(c.v[fv[0]], c.v[fv[1]], c.v[fv[2]]);
      const auto it = std::lower_bound(facets.begin(), facets.end(), key,
                                       [](const HoleFacet& f, std::uint64_t k) { return f.key < k; });
      if (it == facets.end() || it->key != key) continue;
      if (!same_orientation(it->local, {c.v[fv[0]], c.v[fv[1]], c.v[fv[2]]})) continue;
      boundary_mask_[t] |= std::uint8_t(1u << i);
      boundary_outside_[4 * std::size_t(t) + i] = static_cast<Index>(it - facets.begin());
      ++found;
      if (link_.cell_mark[t] != 2 * g) {
        link_.cell_mark[t] = 2 * g;
        hole_.push_back(t);
      }
    }
  }
  SKINMESH_ASSERT_MSG(found == facets.size(), "a facet of the hole is missing from the link triangulation");

  // 5. Flood from the seeds across the faces that are not hole facets.
  for (std::size_t k = 0; k < hole_.size(); ++k) {
    const Index t = hole_[k];
    for (int i = 0; i < 4; ++i) {
      if (boundary_mask_[t] & (1u << i)) continue;
      const Index u = link_.cells[t].n[i];
      SKINMESH_ASSERT_MSG(u != kInvalidIndex, "the hole is not closed in the link triangulation");
      if (link_.cell_mark[u] != 2 * g) {
        link_.cell_mark[u] = 2 * g;
        hole_.push_back(u);
      }
    }
  }

  // 6. Replace the star by the hole tetrahedra, in global vertex ids.
  for (const Index t : star_) m.kill_cell(t);
  m.vertex_tet[v] = kInvalidIndex;
  global_of_local_.resize(ncells);
  for (const Index t : hole_) global_of_local_[t] = m.new_cell();
  for (const Index t : hole_) {
    const Index gt = global_of_local_[t];
    const Cell& lc = link_.cells[t];
    Cell& c = m.cells[gt];
    for (int i = 0; i < 4; ++i) {
      c.v[i] = link_.sos[lc.v[i]];
      m.vertex_tet[c.v[i]] = gt;
      if (boundary_mask_[t] & (1u << i)) {
        const HoleFacet& f = facets[boundary_outside_[4 * std::size_t(t) + i]];
        c.n[i] = f.outside;
        if (f.outside != kInvalidIndex) m.cells[f.outside].n[f.outside_face] = gt;
      } else {
        c.n[i] = global_of_local_[lc.n[i]];
      }
    }
  }
  m.last_cell = global_of_local_[hole_.front()];
  ++stats_.removals;
}

// Queries -------------------------------------------------------------------------

Index DelaunayTriangulation::locate(const Vec3& p, Index hint) const {
  const Index start = mesh_.live(hint) ? hint : mesh_.last_cell;
  std::uint64_t rng = walk_seed(start);
  return mesh_.walk(p, start, rng, nullptr, nullptr);
}

Sign DelaunayTriangulation::conflict(Index t, Index v) const {
  SKINMESH_DEBUG_ASSERT(is_live(t) && is_vertex(v) && local_index(t, v) < 0);
  return mesh_.conflict_with(t, v);
}

bool DelaunayTriangulation::is_vertex(Index v) const {
  return v < mesh_.vertex_tet.size() && mesh_.vertex_tet[v] != kInvalidIndex;
}

const Vec3& DelaunayTriangulation::point(Index v) const {
  SKINMESH_DEBUG_ASSERT(v < mesh_.points.size());
  return mesh_.points[v].z;
}

Index DelaunayTriangulation::vertex_tet(Index v) const {
  return v < mesh_.vertex_tet.size() ? mesh_.vertex_tet[v] : kInvalidIndex;
}

void DelaunayTriangulation::incident_tets(Index v, std::vector<Index>& out) const {
  out.clear();
  const Index t0 = vertex_tet(v);
  if (t0 == kInvalidIndex) return;
  constexpr std::size_t kLinearLimit = 64;
  std::unordered_set<Index> seen;  // used only for large stars
  auto visited = [&](Index u) {
    if (out.size() <= kLinearLimit) return std::find(out.begin(), out.end(), u) != out.end();
    if (seen.empty()) seen.insert(out.begin(), out.end());
    return seen.count(u) != 0;
  };
  out.push_back(t0);
  for (std::size_t k = 0; k < out.size(); ++k) {
    const Cell& c = mesh_.cells[out[k]];
    for (int i = 0; i < 4; ++i) {
      if (c.v[i] == v) continue;
      const Index u = c.n[i];
      if (u != kInvalidIndex && !visited(u)) {  // outer faces: bounding v only
        out.push_back(u);
        if (!seen.empty()) seen.insert(u);
      }
    }
  }
}

bool DelaunayTriangulation::is_live(Index t) const { return mesh_.live(t); }

const std::array<Index, 4>& DelaunayTriangulation::tet(Index t) const {
  SKINMESH_DEBUG_ASSERT(t < mesh_.cells.size());
  return mesh_.cells[t].v;
}

Index DelaunayTriangulation::neighbor(Index t, int i) const {
  SKINMESH_DEBUG_ASSERT(t < mesh_.cells.size() && i >= 0 && i < 4);
  return mesh_.cells[t].n[i];
}

int DelaunayTriangulation::local_index(Index t, Index v) const {
  const std::array<Index, 4>& tv = tet(t);
  for (int i = 0; i < 4; ++i) {
    if (tv[i] == v) return i;
  }
  return -1;
}

Vec3 DelaunayTriangulation::circumcentre(Index t) const {
  const std::array<Index, 4>& tv = tet(t);
  const Vec3& a = point(tv[0]);
  const Vec3 u = point(tv[1]) - a, w = point(tv[2]) - a, x = point(tv[3]) - a;
  // c - a = (|u|² (w × x) + |w|² (x × u) + |x|² (u × w)) / (2 u · (w × x)).
  const Vec3 wx = w.cross(x), xu = x.cross(u), uw = u.cross(w);
  const double det = 2.0 * u.dot(wx);
  return a + (u.squaredNorm() * wx + w.squaredNorm() * xu + x.squaredNorm() * uw) / det;
}

bool DelaunayTriangulation::is_valid(std::string* why) const {
  auto fail = [&](const std::string& problem) {
    if (why) *why = problem;
    return false;
  };
  const Mesh& m = mesh_;
  const Index np = static_cast<Index>(m.points.size());
  const Index nc = static_cast<Index>(m.cells.size());
  if (m.cell_mark.size() != nc) return fail("mark array out of step");
  Index live = 0, live_vertices = 0, outer_faces = 0;
  std::vector<char> used(np, 0);
  for (Index v = 0; v < np; ++v) {
    if (m.sos[v] != v) return fail("SoS index of vertex " + std::to_string(v) + " is not its id");
    const Index t = m.vertex_tet[v];
    if (t == kInvalidIndex) {
      if (v < kNumBounding) return fail("bounding point " + std::to_string(v) + " is not live");
      continue;
    }
    ++live_vertices;
    if (!m.live(t)) return fail("vertex " + std::to_string(v) + " has a dead vertex_tet");
    if (local_index(t, v) < 0) return fail("vertex_tet of vertex " + std::to_string(v) + " does not contain it");
  }
  if (live_vertices != num_live_vertices_ + kNumBounding) return fail("live vertex count");
  for (Index t = 0; t < nc; ++t) {
    if (!m.live(t)) continue;
    ++live;
    const std::string name = "tet " + std::to_string(t);
    const std::array<Index, 4>& q = m.cells[t].v;
    for (int a = 0; a < 4; ++a) {
      if (q[a] >= np || m.vertex_tet[q[a]] == kInvalidIndex) return fail(name + " has a dead vertex");
      used[q[a]] = 1;
      for (int b = a + 1; b < 4; ++b)
        if (q[a] == q[b]) return fail(name + " has a repeated vertex");
    }
    if (orient3d(m.points[q[0]].z, m.points[q[1]].z, m.points[q[2]].z, m.points[q[3]].z) != Sign::Positive)
      return fail(name + " is not positively oriented");
    for (int i = 0; i < 4; ++i) {
      const Index u = m.cells[t].n[i];
      if (u == kInvalidIndex) {
        ++outer_faces;
        for (int k = 0; k < 4; ++k)
          if (k != i && !is_bounding(q[k])) return fail(name + ": outer face with an input vertex");
        continue;
      }
      if (!m.live(u)) return fail(name + " has a dead neighbour");
      int j = -1;
      for (int k = 0; k < 4; ++k)
        if (m.cells[u].n[k] == t) j = k;
      if (j < 0) return fail(name + ": neighbour relation not symmetric");
      const Index opposite = m.cells[u].v[j];
      if (local_index(t, opposite) >= 0) return fail(name + ": neighbour shares 4 vertices");
      for (int k = 0; k < 4; ++k)
        if (k != i && local_index(u, q[k]) < 0) return fail(name + ": neighbour misses the facet");
      if (m.conflict_with(t, opposite) != Sign::Negative)
        return fail(name + ": not locally Delaunay (vertex " + std::to_string(opposite) + ")");
    }
  }
  if (live != m.live_cells) return fail("live tetrahedron count");
  if (live + m.free_cells.size() != nc) return fail("free list out of step");
  if (outer_faces != 4) return fail("not exactly 4 outer faces");
  for (Index v = 0; v < np; ++v)
    if (bool(used[v]) != (m.vertex_tet[v] != kInvalidIndex))
      return fail("vertex " + std::to_string(v) + ": live flag and use disagree");
  return true;
}

}  // namespace skinmesh::geometry
