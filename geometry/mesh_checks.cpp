// geometry/mesh_checks.cpp: check_mesh() and the JSON report (see mesh_checks.h).
#include "geometry/mesh_checks.h"

#include <Eigen/Geometry>  // cross()
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <sstream>
#include <utility>

#include "geometry/triangle_intersection.h"

namespace skinmesh::geometry {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegPerRad = 180.0 / kPi;
constexpr int kHistogramBins = 18;  // 10° each
constexpr double kHistogramBinDeg = 10.0;

// Union-find with path halving and union by size.
class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n), size_(n, 1) {
    std::iota(parent_.begin(), parent_.end(), Index(0));
  }
  Index find(Index x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  void unite(Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
  }

 private:
  std::vector<Index> parent_;
  std::vector<Index> size_;
};

bool finite(const Vec3& p) { return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()); }

// Sort (key, value) pairs by key with an LSD radix sort on the low `bits` bits
// of the keys (stable; 11-bit digits). O(n bits / 11).
void radix_sort(std::vector<std::pair<std::uint64_t, Index>>& a, int bits) {
  constexpr int kDigit = 11;
  constexpr std::size_t kBuckets = std::size_t(1) << kDigit;
  std::vector<std::pair<std::uint64_t, Index>> tmp(a.size());
  std::vector<std::size_t> count(kBuckets);
  for (int shift = 0; shift < bits; shift += kDigit) {
    std::fill(count.begin(), count.end(), 0);
    for (const auto& x : a) ++count[(x.first >> shift) & (kBuckets - 1)];
    std::size_t sum = 0;
    for (std::size_t& c : count) {
      const std::size_t n = c;
      c = sum;
      sum += n;
    }
    for (const auto& x : a) tmp[count[(x.first >> shift) & (kBuckets - 1)]++] = x;
    a.swap(tmp);
  }
}

// Uniform-grid broad phase over triangle boxes. Calls test(i, j) once for every
// pair of listed triangles whose (closed, exact) bounding boxes overlap.
template <class PairTest>
void for_each_box_pair(const std::vector<Index>& tris, const std::vector<std::array<double, 6>>& box,
                       PairTest&& test) {
  const std::size_t n = tris.size();
  if (n < 2) return;
  Vec3 gmin = Vec3::Constant(std::numeric_limits<double>::infinity()), gmax = -gmin;
  double mean_extent = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& b = box[i];
    for (int k = 0; k < 3; ++k) {
      gmin[k] = std::min(gmin[k], b[k]);
      gmax[k] = std::max(gmax[k], b[3 + k]);
    }
    mean_extent += std::max({b[3] - b[0], b[4] - b[1], b[5] - b[2]});
  }
  mean_extent /= double(n);
  const double span = (gmax - gmin).maxCoeff();
  // Cell size: kCellPerExtent times the mean triangle extent (so a triangle
  // covers a few cells), coarsened until the grid has at most 2^21 cells per
  // axis and the (cell, triangle) entries stay below kMaxEntriesPerTriangle per
  // triangle. Both constants only trade speed (measured on spheres of 1e6
  // triangles), never correctness.
  constexpr double kCellPerExtent = 2.0;
  constexpr double kMaxEntriesPerTriangle = 16.0;
  constexpr double kMaxCellsPerAxis = double(1 << 21);
  double cell = mean_extent > 0.0 ? kCellPerExtent * mean_extent : (span > 0.0 ? span : 1.0);
  std::array<std::uint64_t, 3> dims{};
  std::vector<std::array<Index, 6>> range(n);  // cell index ranges [lo, hi] per axis
  for (;;) {
    const double inv = 1.0 / cell;
    bool fits = true;
    for (int k = 0; k < 3; ++k) {
      const double d = std::floor((gmax[k] - gmin[k]) * inv) + 1.0;
      fits = fits && d <= kMaxCellsPerAxis;
      dims[k] = fits ? std::uint64_t(d) : 1;
    }
    if (!fits) {
      cell *= 2.0;
      continue;
    }
    double entries = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      double cells = 1.0;
      for (int k = 0; k < 3; ++k) {
        // Monotone in the coordinate, so overlapping boxes share a cell.
        auto c = [&](double x) {
          const double t = std::floor((x - gmin[k]) * inv);
          return Index(std::clamp(t, 0.0, double(dims[k] - 1)));
        };
        range[i][k] = c(box[i][k]);
        range[i][3 + k] = c(box[i][3 + k]);
        cells *= double(range[i][3 + k] - range[i][k] + 1);
      }
      entries += cells;
    }
    if (entries <= kMaxEntriesPerTriangle * double(n) + 1024.0) break;
    cell *= 2.0;
  }
  auto key = [&](std::uint64_t x, std::uint64_t y, std::uint64_t z) {
    return (z * dims[1] + y) * dims[0] + x;
  };
  std::vector<std::pair<std::uint64_t, Index>> entries;
  entries.reserve(4 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& r = range[i];
    for (Index z = r[2]; z <= r[5]; ++z)
      for (Index y = r[1]; y <= r[4]; ++y)
        for (Index x = r[0]; x <= r[3]; ++x) entries.emplace_back(key(x, y, z), Index(i));
  }
  radix_sort(entries, std::bit_width(dims[0] * dims[1] * dims[2] - 1));
  // In each cell, sweep along x: sort the cell's triangles by their box's lower
  // x and pair each one only with those starting before it ends.
  std::vector<Index> cell_tris;
  for (std::size_t s = 0; s < entries.size();) {
    std::size_t e = s + 1;
    while (e < entries.size() && entries[e].first == entries[s].first) ++e;
    cell_tris.clear();
    for (std::size_t a = s; a < e; ++a) cell_tris.push_back(entries[a].second);
    std::sort(cell_tris.begin(), cell_tris.end(),
              [&](Index i, Index j) { return box[i][0] < box[j][0] || (box[i][0] == box[j][0] && i < j); });
    for (std::size_t a = 0; a < cell_tris.size(); ++a) {
      const Index i = cell_tris[a];
      const auto& bi = box[i];
      const auto& ri = range[i];
      for (std::size_t b = a + 1; b < cell_tris.size(); ++b) {
        const Index j = cell_tris[b];
        const auto& bj = box[j];
        if (bj[0] > bi[3]) break;  // this and all later ones start after i ends
        if (bi[1] > bj[4] || bj[1] > bi[4] || bi[2] > bj[5] || bj[2] > bi[5]) continue;
        // Test the pair only in the first cell the two ranges share.
        const auto& rj = range[j];
        if (key(std::max(ri[0], rj[0]), std::max(ri[1], rj[1]), std::max(ri[2], rj[2])) !=
            entries[s].first)
          continue;
        test(tris[std::min(i, j)], tris[std::max(i, j)]);
      }
    }
    s = e;
  }
}

// Minimal JSON writer: objects, arrays, numbers, booleans, strings.
class JsonWriter {
 public:
  std::string str() const { return os_.str(); }
  void begin_object() {
    separator();
    os_ << '{';
    first_ = true;
  }
  void end_object() {
    os_ << '}';
    first_ = false;
  }
  void begin_array() {
    separator();
    os_ << '[';
    first_ = true;
  }
  void end_array() {
    os_ << ']';
    first_ = false;
  }
  void key(const std::string& k) {
    separator();
    string_literal(k);
    os_ << ':';
    first_ = true;  // the value follows without a comma
  }
  void value(bool b) {
    separator();
    os_ << (b ? "true" : "false");
  }
  void value(double x) {
    separator();
    if (!std::isfinite(x)) {
      os_ << "null";
      return;
    }
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    os_ << buf;
  }
  void value(std::uint64_t x) {
    separator();
    os_ << x;
  }
  void value(std::int64_t x) {
    separator();
    os_ << x;
  }
  void null() {
    separator();
    os_ << "null";
  }
  void value(const std::string& s) {
    separator();
    string_literal(s);
  }

 private:
  void separator() {
    if (!first_) os_ << ',';
    first_ = false;
  }
  void string_literal(const std::string& s) {
    os_ << '"';
    for (unsigned char ch : s) {
      switch (ch) {
        case '"':
          os_ << "\\\"";
          break;
        case '\\':
          os_ << "\\\\";
          break;
        case '\n':
          os_ << "\\n";
          break;
        case '\r':
          os_ << "\\r";
          break;
        case '\t':
          os_ << "\\t";
          break;
        case '\b':
          os_ << "\\b";
          break;
        case '\f':
          os_ << "\\f";
          break;
        default:
          if (ch < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", ch);
            os_ << buf;
          } else {
            os_ << ch;
          }
      }
    }
    os_ << '"';
  }
  std::ostringstream os_;
  bool first_ = true;
};

}  // namespace

// ---------------------------------------------------------------------------
// check_mesh
// ---------------------------------------------------------------------------

MeshCheckReport check_mesh(const IndexedMesh& mesh, const MeshCheckOptions& options) {
  MeshCheckReport r;
  const auto& P = mesh.positions;
  const auto& T = mesh.triangles;
  const std::size_t nv = P.size(), nt = T.size();
  r.num_vertices = nv;
  r.num_triangles = nt;
  r.small_angle_threshold_deg = options.small_angle_threshold_deg;
  const std::size_t max_ex = options.max_examples;
  auto example = [max_ex](auto& list, auto item) {
    if (list.size() < max_ex) list.push_back(item);
  };

  // Vertices and triangle classes --------------------------------------------
  std::vector<bool> vertex_finite(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    vertex_finite[v] = finite(P[v]);
    if (!vertex_finite[v]) ++r.num_nonfinite_vertices;
  }
  enum class Kind : std::uint8_t { kOutOfRange, kRepeated, kZeroArea, kNonFinite, kGood };
  std::vector<Kind> kind(nt, Kind::kGood);
  std::vector<bool> referenced(nv, false);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = T[t];
    if (tri[0] >= nv || tri[1] >= nv || tri[2] >= nv) {
      kind[t] = Kind::kOutOfRange;
      ++r.num_out_of_range_triangles;
      continue;
    }
    for (Index v : tri) referenced[v] = true;
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
      kind[t] = Kind::kRepeated;
      ++r.num_repeated_index_triangles;
      example(r.degenerate_triangle_examples, Index(t));
    } else if (!vertex_finite[tri[0]] || !vertex_finite[tri[1]] || !vertex_finite[tri[2]]) {
      kind[t] = Kind::kNonFinite;
    } else if (is_degenerate_triangle(P[tri[0]], P[tri[1]], P[tri[2]])) {
      kind[t] = Kind::kZeroArea;
      ++r.num_zero_area_triangles;
      example(r.degenerate_triangle_examples, Index(t));
    }
  }
  r.num_degenerate_triangles = r.num_repeated_index_triangles + r.num_zero_area_triangles;
  r.num_unreferenced_vertices = std::size_t(std::count(referenced.begin(), referenced.end(), false));
  auto in_topology = [&](std::size_t t) {
    return kind[t] != Kind::kOutOfRange && kind[t] != Kind::kRepeated;
  };

  // Duplicate triangles (same vertex set) ---------------------------------------
  {
    std::vector<std::pair<std::array<Index, 3>, Index>> sorted;
    sorted.reserve(nt);
    for (std::size_t t = 0; t < nt; ++t) {
      if (!in_topology(t)) continue;
      std::array<Index, 3> s = T[t];
      std::sort(s.begin(), s.end());
      sorted.emplace_back(s, Index(t));
    }
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 1; i < sorted.size(); ++i)
      if (sorted[i].first == sorted[i - 1].first) ++r.num_duplicate_triangles;
  }

  // Vertex -> triangle incidence (CSR) ------------------------------------------
  std::vector<Index> start(nv + 1, 0);
  for (std::size_t t = 0; t < nt; ++t)
    if (in_topology(t))
      for (Index v : T[t]) ++start[v + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<Index> incident(start[nv]);
  {
    std::vector<Index> fill(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < nt; ++t)
      if (in_topology(t))
        for (Index v : T[t]) incident[fill[v]++] = Index(t);
  }

  // Edges, vertex by vertex --------------------------------------------------------
  // An edge is listed at its lower vertex; its triangles are joined in `faces_uf`.
  enum EdgeFlag : std::uint8_t { kBoundary = 1, kNonManifold = 2, kMisoriented = 4 };
  struct EdgeRecord {
    Index triangle;  // one triangle of the edge (all are in one component)
    std::uint8_t flags;
  };
  std::vector<EdgeRecord> edges;
  edges.reserve(nt * 3 / 2 + 16);
  UnionFind faces_uf(nt);
  {
    struct Use {
      Index other, triangle;
      int dir;  // +1: the triangle goes lower -> higher vertex
      bool operator<(const Use& o) const {
        return other != o.other ? other < o.other : triangle < o.triangle;
      }
    };
    std::vector<Use> uses;
    for (std::size_t v = 0; v < nv; ++v) {
      const Index b = start[v], e = start[v + 1];
      if (b == e) continue;
      uses.clear();
      for (Index k = b; k < e; ++k) {
        const Index t = incident[k];
        const auto& tri = T[t];
        const int i = tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
        const Index nx = tri[(i + 1) % 3], pv = tri[(i + 2) % 3];
        if (nx > v) uses.push_back({nx, t, +1});
        if (pv > v) uses.push_back({pv, t, -1});
      }
      // Edges (v, w), w > v.
      std::sort(uses.begin(), uses.end());
      for (std::size_t s = 0; s < uses.size();) {
        std::size_t q = s + 1;
        while (q < uses.size() && uses[q].other == uses[s].other) ++q;
        const std::size_t count = q - s;
        std::uint8_t flags = 0;
        const std::array<Index, 2> ends{Index(v), uses[s].other};
        if (count == 1) {
          flags |= kBoundary;
          ++r.num_boundary_edges;
          example(r.boundary_edge_examples, ends);
        } else if (count > 2) {
          flags |= kNonManifold;
          ++r.num_nonmanifold_edges;
          example(r.nonmanifold_edge_examples, ends);
        } else if (uses[s].dir == uses[s + 1].dir) {
          flags |= kMisoriented;
          ++r.num_misoriented_edges;
          example(r.misoriented_edge_examples, ends);
        }
        for (std::size_t u = s + 1; u < q; ++u) faces_uf.unite(uses[s].triangle, uses[u].triangle);
        edges.push_back({uses[s].triangle, flags});
        s = q;
      }
    }
  }
  r.num_edges = edges.size();
  r.closed = r.num_boundary_edges == 0;
  r.edge_manifold = r.num_nonmanifold_edges == 0;
  r.oriented = r.num_misoriented_edges == 0;

  // Components ----------------------------------------------------------------
  std::vector<Index> component(nt, kInvalidIndex);  // triangle -> component id
  {
    std::vector<Index> root_component(nt, kInvalidIndex);
    for (std::size_t t = 0; t < nt; ++t) {
      if (!in_topology(t)) continue;
      const Index root = faces_uf.find(Index(t));
      if (root_component[root] == kInvalidIndex) {
        root_component[root] = Index(r.components.size());
        r.components.emplace_back();
        r.components.back().manifold = r.components.back().oriented = r.components.back().closed =
            true;
      }
      component[t] = root_component[root];
    }
  }
  // Volumes relative to the centre of the bounding box, to limit cancellation.
  Vec3 centre = Vec3::Zero();
  {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (std::size_t v = 0; v < nv; ++v)
      if (vertex_finite[v] && referenced[v]) {
        lo = lo.cwiseMin(P[v]);
        hi = hi.cwiseMax(P[v]);
      }
    if (lo.x() <= hi.x()) centre = 0.5 * (lo + hi);
  }
  for (std::size_t t = 0; t < nt; ++t) {
    if (component[t] == kInvalidIndex) continue;
    MeshComponent& c = r.components[component[t]];
    ++c.faces;
    if (kind[t] == Kind::kNonFinite) continue;
    const Vec3 a = P[T[t][0]] - centre, b = P[T[t][1]] - centre, d = P[T[t][2]] - centre;
    c.volume += a.dot(b.cross(d)) / 6.0;
    c.area += 0.5 * (b - a).cross(d - a).norm();
  }
  for (const EdgeRecord& e : edges) {
    MeshComponent& c = r.components[component[e.triangle]];
    ++c.edges;
    if (e.flags & kBoundary) c.closed = false;
    if (e.flags & kNonManifold) c.manifold = false;
    if (e.flags & kMisoriented) c.oriented = false;
  }
  // Vertex links, per component ---------------------------------------------------
  // The triangles of one component at v must form a single fan: their link
  // edges (next, prev) form a connected graph with degrees <= 2 (a path or a
  // cycle). v is non-manifold if that fails or if several components meet at v.
  {
    std::vector<std::pair<Index, Index>> around;  // (component, triangle)
    std::vector<Index> link_vertices, parent;
    std::vector<int> degree;
    auto corner = [&](Index t, std::size_t v) {
      const auto& tri = T[t];
      return tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
    };
    for (std::size_t v = 0; v < nv; ++v) {
      around.clear();
      for (Index k = start[v]; k < start[v + 1]; ++k)
        around.emplace_back(component[incident[k]], incident[k]);
      if (around.empty()) continue;
      std::sort(around.begin(), around.end());
      bool bad = false;
      for (std::size_t s = 0; s < around.size();) {
        std::size_t q = s + 1;
        while (q < around.size() && around[q].first == around[s].first) ++q;
        link_vertices.clear();
        for (std::size_t k = s; k < q; ++k) {
          const auto& tri = T[around[k].second];
          const int i = corner(around[k].second, v);
          link_vertices.push_back(tri[(i + 1) % 3]);
          link_vertices.push_back(tri[(i + 2) % 3]);
        }
        std::sort(link_vertices.begin(), link_vertices.end());
        link_vertices.erase(std::unique(link_vertices.begin(), link_vertices.end()),
                            link_vertices.end());
        const std::size_t m = link_vertices.size();
        parent.resize(m);
        std::iota(parent.begin(), parent.end(), Index(0));
        degree.assign(m, 0);
        auto root = [&](Index x) {
          while (parent[x] != x) x = parent[x] = parent[parent[x]];
          return x;
        };
        auto slot = [&](Index w) {
          return Index(std::lower_bound(link_vertices.begin(), link_vertices.end(), w) -
                       link_vertices.begin());
        };
        bool fan = true;
        std::size_t groups = m;
        for (std::size_t k = s; k < q; ++k) {
          const auto& tri = T[around[k].second];
          const int i = corner(around[k].second, v);
          const Index x = slot(tri[(i + 1) % 3]), y = slot(tri[(i + 2) % 3]);
          if (++degree[x] > 2 || ++degree[y] > 2) fan = false;
          const Index rx = root(x), ry = root(y);
          if (rx != ry) {
            parent[rx] = ry;
            --groups;
          }
        }
        MeshComponent& c = r.components[around[s].first];
        ++c.vertices;
        if (!fan || groups != 1) {
          c.manifold = false;
          bad = true;
        }
        if (s != 0) bad = true;  // a second component at v
        s = q;
      }
      if (bad) {
        ++r.num_nonmanifold_vertices;
        example(r.nonmanifold_vertex_examples, Index(v));
      }
    }
  }
  r.vertex_manifold = r.num_nonmanifold_vertices == 0;
  for (MeshComponent& c : r.components) {
    c.euler = std::int64_t(c.vertices) - std::int64_t(c.edges) + std::int64_t(c.faces);
    if (c.closed && c.manifold && c.oriented && c.euler % 2 == 0) c.genus = (2 - c.euler) / 2;
  }
  {
    UnionFind vertex_uf(nv);
    for (std::size_t t = 0; t < nt; ++t)
      if (kind[t] != Kind::kOutOfRange) {
        vertex_uf.unite(T[t][0], T[t][1]);
        vertex_uf.unite(T[t][0], T[t][2]);
      }
    for (std::size_t v = 0; v < nv; ++v)
      if (referenced[v] && vertex_uf.find(Index(v)) == v) ++r.num_vertex_components;
  }

  // Angles -------------------------------------------------------------------
  {
    double min_angle = std::numeric_limits<double>::infinity(), max_angle = -min_angle;
    const double threshold = options.small_angle_threshold_deg;
    for (std::size_t t = 0; t < nt; ++t) {
      if (kind[t] != Kind::kGood && kind[t] != Kind::kZeroArea) continue;
      const Vec3& a = P[T[t][0]];
      const Vec3& b = P[T[t][1]];
      const Vec3& c = P[T[t][2]];
      const double angles[3] = {corner_angle(a, b, c) * kDegPerRad,
                                corner_angle(b, c, a) * kDegPerRad,
                                corner_angle(c, a, b) * kDegPerRad};
      double tri_min = angles[0];
      for (double x : angles) {
        tri_min = std::min(tri_min, x);
        max_angle = std::max(max_angle, x);
        const int bin = std::clamp(int(x / kHistogramBinDeg), 0, kHistogramBins - 1);
        ++r.angle_histogram[std::size_t(bin)];
      }
      if (tri_min < min_angle) {
        min_angle = tri_min;
        r.worst_triangle = Index(t);
      }
      if (tri_min < threshold) ++r.num_small_angle_triangles;
    }
    if (r.worst_triangle != kInvalidIndex) {
      r.min_angle_deg = min_angle;
      r.max_angle_deg = max_angle;
    }
  }

  // Self-intersections ------------------------------------------------------------
  if (options.check_self_intersections) {
    r.self_intersections_checked = true;
    std::vector<Index> tris;
    std::vector<std::array<double, 6>> boxes;
    for (std::size_t t = 0; t < nt; ++t) {
      if (kind[t] != Kind::kGood) continue;
      std::array<double, 6> b;
      for (int k = 0; k < 3; ++k) {
        b[k] = std::min({P[T[t][0]][k], P[T[t][1]][k], P[T[t][2]][k]});
        b[3 + k] = std::max({P[T[t][0]][k], P[T[t][1]][k], P[T[t][2]][k]});
      }
      tris.push_back(Index(t));
      boxes.push_back(b);
    }
    std::vector<std::array<Index, 2>> found;
    for_each_box_pair(tris, boxes, [&](Index i, Index j) {
      const auto& ti = T[i];
      const auto& tj = T[j];
      int shared = 0;
      for (Index a : ti)
        for (Index b : tj) shared += a == b ? 1 : 0;
      if (shared == 3) return;  // a duplicate, counted separately
      ++r.num_pairs_tested;
      if (mesh_triangles_intersect(ti, tj, P)) {
        ++r.num_self_intersections;
        found.push_back({i, j});
      }
    });
    std::sort(found.begin(), found.end());
    if (found.size() > max_ex) found.resize(max_ex);
    r.self_intersection_examples = std::move(found);
  }

  // Summary --------------------------------------------------------------------
  auto add = [&](std::size_t n, const std::string& what) {
    if (n > 0) r.problems.push_back(std::to_string(n) + " " + what);
  };
  add(r.num_out_of_range_triangles, "triangles with a vertex index out of range");
  add(r.num_nonfinite_vertices, "vertices with a non-finite coordinate");
  add(r.num_repeated_index_triangles, "triangles with a repeated vertex index");
  add(r.num_zero_area_triangles, "zero-area (collinear) triangles");
  add(r.num_duplicate_triangles, "duplicate triangles");
  add(r.num_boundary_edges, "boundary edges (the mesh is not closed)");
  add(r.num_nonmanifold_edges, "non-manifold edges (more than two triangles)");
  add(r.num_nonmanifold_vertices, "non-manifold vertices (triangles not a single fan)");
  add(r.num_misoriented_edges, "edges used twice in the same direction (inconsistent orientation)");
  add(r.num_self_intersections, "pairs of self-intersecting triangles");
  return r;
}

bool MeshCheckReport::ok() const {
  return num_out_of_range_triangles == 0 && num_nonfinite_vertices == 0 &&
         num_degenerate_triangles == 0 && num_duplicate_triangles == 0 && closed &&
         edge_manifold && vertex_manifold && oriented && num_self_intersections == 0;
}

std::string MeshCheckReport::to_json() const {
  JsonWriter w;
  auto u = [&](const char* k, std::size_t x) {
    w.key(k);
    w.value(std::uint64_t(x));
  };
  auto b = [&](const char* k, bool x) {
    w.key(k);
    w.value(x);
  };
  auto d = [&](const char* k, double x) {
    w.key(k);
    w.value(x);
  };
  auto index = [&](Index x) {
    if (x == kInvalidIndex)
      w.null();
    else
      w.value(std::uint64_t(x));
  };
  auto indices = [&](const char* k, const std::vector<Index>& xs) {
    w.key(k);
    w.begin_array();
    for (Index x : xs) index(x);
    w.end_array();
  };
  auto pairs = [&](const char* k, const std::vector<std::array<Index, 2>>& xs) {
    w.key(k);
    w.begin_array();
    for (const auto& p : xs) {
      w.begin_array();
      index(p[0]);
      index(p[1]);
      w.end_array();
    }
    w.end_array();
  };

  w.begin_object();
  b("ok", ok());
  u("num_vertices", num_vertices);
  u("num_triangles", num_triangles);
  u("num_unreferenced_vertices", num_unreferenced_vertices);
  u("num_nonfinite_vertices", num_nonfinite_vertices);
  u("num_edges", num_edges);
  u("num_out_of_range_triangles", num_out_of_range_triangles);
  u("num_repeated_index_triangles", num_repeated_index_triangles);
  u("num_zero_area_triangles", num_zero_area_triangles);
  u("num_degenerate_triangles", num_degenerate_triangles);
  u("num_duplicate_triangles", num_duplicate_triangles);
  indices("degenerate_triangle_examples", degenerate_triangle_examples);
  u("num_boundary_edges", num_boundary_edges);
  u("num_nonmanifold_edges", num_nonmanifold_edges);
  u("num_misoriented_edges", num_misoriented_edges);
  u("num_nonmanifold_vertices", num_nonmanifold_vertices);
  b("closed", closed);
  b("edge_manifold", edge_manifold);
  b("vertex_manifold", vertex_manifold);
  b("oriented", oriented);
  pairs("boundary_edge_examples", boundary_edge_examples);
  pairs("nonmanifold_edge_examples", nonmanifold_edge_examples);
  pairs("misoriented_edge_examples", misoriented_edge_examples);
  indices("nonmanifold_vertex_examples", nonmanifold_vertex_examples);
  w.key("components");
  w.begin_array();
  for (const MeshComponent& c : components) {
    w.begin_object();
    u("vertices", c.vertices);
    u("edges", c.edges);
    u("faces", c.faces);
    w.key("euler");
    w.value(std::int64_t(c.euler));
    b("closed", c.closed);
    b("manifold", c.manifold);
    b("oriented", c.oriented);
    w.key("genus");
    if (c.genus)
      w.value(std::int64_t(*c.genus));
    else
      w.null();
    d("volume", c.volume);
    d("area", c.area);
    w.end_object();
  }
  w.end_array();
  u("num_vertex_components", num_vertex_components);
  b("self_intersections_checked", self_intersections_checked);
  u("num_self_intersections", num_self_intersections);
  pairs("self_intersection_examples", self_intersection_examples);
  u("num_pairs_tested", num_pairs_tested);
  d("min_angle_deg", min_angle_deg);
  d("max_angle_deg", max_angle_deg);
  w.key("worst_triangle");
  index(worst_triangle);
  w.key("angle_histogram");
  w.begin_array();
  for (std::size_t x : angle_histogram) w.value(std::uint64_t(x));
  w.end_array();
  d("angle_histogram_bin_deg", kHistogramBinDeg);
  d("small_angle_threshold_deg", small_angle_threshold_deg);
  u("num_small_angle_triangles", num_small_angle_triangles);
  w.key("problems");
  w.begin_array();
  for (const std::string& p : problems) w.value(p);
  w.end_array();
  w.end_object();
  return w.str();
}

}  // namespace skinmesh::geometry
