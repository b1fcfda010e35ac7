// geometry/check/mesh_checks_topology.cpp: the combinatorial half of check_mesh() —
// duplicate triangles, boundary / non-manifold / misoriented edges, edge-connected
// components with their Euler characteristic and genus, vertex links
// (vertex-manifoldness) and vertex-connected components. Index comparisons only,
// so every answer is exact. Declared in mesh_checks_internal.h.
#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

#include "geometry/check/mesh_checks_internal.h"

namespace skinmesh::geometry::mesh_checks_detail {

namespace {

// Union-find with path halving and union by rank. A rank is at most
// log2(n), so a byte holds it: 5 bytes per triangle instead of 8 with sizes
// (the components are numbered by their lowest triangle, so which element
// becomes a root changes nothing that is reported).
class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n), rank_(n, 0) { std::iota(parent_.begin(), parent_.end(), Index(0)); }
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
    if (rank_[a] < rank_[b]) std::swap(a, b);
    parent_[b] = a;
    if (rank_[a] == rank_[b]) ++rank_[a];
  }

 private:
  std::vector<Index> parent_;
  std::vector<std::uint8_t> rank_;
};

/// The number of triangles in the topology whose vertex set (in any order) is
/// that of an earlier one: MeshCheckReport::num_duplicate_triangles. Equal
/// vertex sets have the same lowest vertex, so the triangles are grouped by
/// their lowest vertex (through `in`) and only each group's (middle, highest)
/// vertex pairs are sorted and compared: O(n) for bounded vertex degrees.
std::size_t count_duplicate_triangles(const IndexedMesh& mesh, const VertexIncidence& in) {
  const auto& T = mesh.triangles;
  const std::size_t nv = mesh.positions.size();
  std::size_t duplicates = 0;
  std::vector<std::uint64_t> rest;  // (middle << 32) | highest, of the triangles whose lowest vertex is v
  for (std::size_t v = 0; v < nv; ++v) {
    rest.clear();
    for (Index k = in.start[v]; k < in.start[v + 1]; ++k) {
      std::array<Index, 3> s = T[in.incident[k]];
      std::sort(s.begin(), s.end());
      if (s[0] == v) rest.push_back((std::uint64_t(s[1]) << 32) | s[2]);
    }
    std::sort(rest.begin(), rest.end());
    for (std::size_t i = 1; i < rest.size(); ++i)
      if (rest[i] == rest[i - 1]) ++duplicates;
  }
  return duplicates;
}

/// What is wrong with an edge (bit flags of EdgeRecord::flags).
enum EdgeFlag : std::uint8_t { kBoundary = 1, kNonManifold = 2, kMisoriented = 4 };

/// A distinct undirected edge of the topology with something wrong.
struct EdgeRecord {
  Index triangle;  // one triangle of the edge (all are in one component)
  std::uint8_t flags;
};

/// The distinct edges as the component counts need them: per triangle, how
/// many edges it stands for (each edge is counted at one of its triangles,
/// all of which lie in one component; at most 3), and the edges with a flag.
/// One byte per triangle where a record per edge took 12 (the check runs at
/// the peak of the whole run's memory).
struct EdgeCounts {
  std::vector<std::uint8_t> per_triangle;
  std::vector<EdgeRecord> flagged;
};

/// Every distinct edge, listed at its lower vertex, vertex by vertex. Counts the
/// boundary (one triangle), non-manifold (more than two) and misoriented (two
/// triangles using it in the same direction) edges in `r` with their examples
/// (at most `max_examples`), sets num_edges, closed, edge_manifold and oriented,
/// and joins the triangles of each edge in `faces_uf` (one entry per triangle).
EdgeCounts scan_edges(const IndexedMesh& mesh, const VertexIncidence& in, UnionFind& faces_uf, std::size_t max_examples,
                      MeshCheckReport& r) {
  const auto& T = mesh.triangles;
  const std::size_t nv = mesh.positions.size(), nt = T.size();
  EdgeCounts edges;
  edges.per_triangle.assign(nt, 0);
  std::size_t num_edges = 0;
  struct Use {
    Index other, triangle;
    int dir;  // +1: the triangle goes lower -> higher vertex
    bool operator<(const Use& o) const { return other != o.other ? other < o.other : triangle < o.triangle; }
  };
  std::vector<Use> uses;
  for (std::size_t v = 0; v < nv; ++v) {
    const Index b = in.start[v], e = in.start[v + 1];
    if (b == e) continue;
    uses.clear();
    for (Index k = b; k < e; ++k) {
      const Index t = in.incident[k];
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
        add_example(r.boundary_edge_examples, ends, max_examples);
      } else if (count > 2) {
        flags |= kNonManifold;
        ++r.num_nonmanifold_edges;
        add_example(r.nonmanifold_edge_examples, ends, max_examples);
      } else if (uses[s].dir == uses[s + 1].dir) {
        flags |= kMisoriented;
        ++r.num_misoriented_edges;
        add_example(r.misoriented_edge_examples, ends, max_examples);
      }
      for (std::size_t u = s + 1; u < q; ++u) faces_uf.unite(uses[s].triangle, uses[u].triangle);
      ++edges.per_triangle[uses[s].triangle];
      if (flags) edges.flagged.push_back({uses[s].triangle, flags});
      ++num_edges;
      s = q;
    }
  }
  r.num_edges = num_edges;
  r.closed = r.num_boundary_edges == 0;
  r.edge_manifold = r.num_nonmanifold_edges == 0;
  r.oriented = r.num_misoriented_edges == 0;
  return edges;
}

/// The edge-connected components (the groups of `faces_uf`), numbered in the
/// order of their lowest triangle: appends one MeshComponent per component to
/// r.components (closed, manifold and oriented until shown otherwise), counts
/// its faces, and returns the component of every triangle (kInvalidIndex for
/// triangles outside the topology).
std::vector<Index> label_components(const TriangleClasses& classes, UnionFind& faces_uf, MeshCheckReport& r) {
  const std::size_t nt = classes.kind.size();
  // triangle -> component id. A root's own entry holds its group's id from
  // the group's lowest triangle on (the root's component is that id), so no
  // second array of roots is needed at the check's peak.
  std::vector<Index> component(nt, kInvalidIndex);
  for (std::size_t t = 0; t < nt; ++t) {
    if (!classes.in_topology(t)) continue;
    const Index root = faces_uf.find(Index(t));
    if (component[root] == kInvalidIndex) {
      component[root] = Index(r.components.size());
      r.components.emplace_back();
      r.components.back().manifold = r.components.back().oriented = r.components.back().closed = true;
    }
    component[t] = component[root];
    ++r.components[component[t]].faces;
  }
  return component;
}

/// Counts the edges of every component and clears its closed, manifold and
/// oriented flags where one of its edges is a boundary, non-manifold or
/// misoriented edge.
void count_component_edges(const EdgeCounts& edges, const std::vector<Index>& component, MeshCheckReport& r) {
  for (std::size_t t = 0; t < edges.per_triangle.size(); ++t)
    if (edges.per_triangle[t]) r.components[component[t]].edges += edges.per_triangle[t];
  for (const EdgeRecord& e : edges.flagged) {
    MeshComponent& c = r.components[component[e.triangle]];
    if (e.flags & kBoundary) c.closed = false;
    if (e.flags & kNonManifold) c.manifold = false;
    if (e.flags & kMisoriented) c.oriented = false;
  }
}

/// Vertex links, per component. The triangles of one component at v must form a
/// single fan: their link edges (next, prev) form a connected graph with degrees
/// <= 2 (a path or a cycle); otherwise the component is not manifold. v is
/// non-manifold if that fails or if several components meet at v. Counts the
/// vertices of each component, num_nonmanifold_vertices with its examples (at
/// most `max_examples`) and sets vertex_manifold.
void check_vertex_links(const IndexedMesh& mesh, const VertexIncidence& in, const std::vector<Index>& component,
                        std::size_t max_examples, MeshCheckReport& r) {
  constexpr std::size_t kMaxFastFan = 32;
  const auto& T = mesh.triangles;
  const std::size_t nv = mesh.positions.size();
  std::vector<std::pair<Index, Index>> around;  // (component, triangle)
  std::vector<Index> link_vertices, parent;
  std::vector<int> degree;
  auto corner = [&](Index t, std::size_t v) {
    const auto& tri = T[t];
    return tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
  };
  for (std::size_t v = 0; v < nv; ++v) {
    // Fast path, the common case: the triangles at v are in one component and
    // their link edges (next -> prev) form one directed cycle through distinct
    // vertices; then the link graph is a cycle (every degree 2, connected), as
    // the general test below would find.
    const Index kb = in.start[v], ke = in.start[v + 1];
    if (ke - kb >= 2 && ke - kb <= kMaxFastFan) {
      const std::size_t k = ke - kb;
      const Index comp = component[in.incident[kb]];
      Index a[kMaxFastFan], b[kMaxFastFan];
      bool fast = true;
      for (std::size_t j = 0; j < k && fast; ++j) {
        const Index t = in.incident[kb + j];
        const int i = corner(t, v);
        a[j] = T[t][(i + 1) % 3];
        b[j] = T[t][(i + 2) % 3];
        fast = component[t] == comp;
      }
      for (std::size_t j = 0; j < k && fast; ++j)
        for (std::size_t m = j + 1; m < k; ++m) fast = fast && a[j] != a[m];
      std::size_t at = 0;
      for (std::size_t step = 1; step <= k && fast; ++step) {
        std::size_t next = k;
        for (std::size_t m = 0; m < k; ++m)
          if (a[m] == b[at]) next = m;
        fast = next != k && (next == 0) == (step == k);
        at = next;
      }
      if (fast) {
        ++r.components[comp].vertices;
        continue;
      }
    }
    around.clear();
    for (Index k = in.start[v]; k < in.start[v + 1]; ++k)
      around.emplace_back(component[in.incident[k]], in.incident[k]);
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
      link_vertices.erase(std::unique(link_vertices.begin(), link_vertices.end()), link_vertices.end());
      const std::size_t m = link_vertices.size();
      parent.resize(m);
      std::iota(parent.begin(), parent.end(), Index(0));
      degree.assign(m, 0);
      auto root = [&](Index x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
      };
      auto slot = [&](Index w) {
        return Index(std::lower_bound(link_vertices.begin(), link_vertices.end(), w) - link_vertices.begin());
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
      add_example(r.nonmanifold_vertex_examples, Index(v), max_examples);
    }
  }
  r.vertex_manifold = r.num_nonmanifold_vertices == 0;
}

/// Euler characteristic V - E + F of every component, and its genus
/// (2 - euler) / 2 when it is closed, manifold and oriented (and euler is even).
void set_euler_and_genus(MeshCheckReport& r) {
  for (MeshComponent& c : r.components) {
    c.euler = std::int64_t(c.vertices) - std::int64_t(c.edges) + std::int64_t(c.faces);
    if (c.closed && c.manifold && c.oriented && c.euler % 2 == 0) c.genus = (2 - c.euler) / 2;
  }
}

/// MeshCheckReport::num_vertex_components: the referenced vertices grouped by the
/// edges of every in-range triangle (sharing a vertex suffices to connect).
std::size_t count_vertex_components(const IndexedMesh& mesh, const TriangleClasses& classes) {
  const auto& T = mesh.triangles;
  const std::size_t nv = mesh.positions.size(), nt = T.size();
  UnionFind vertex_uf(nv);
  for (std::size_t t = 0; t < nt; ++t)
    if (classes.kind[t] != TriangleKind::kOutOfRange) {
      vertex_uf.unite(T[t][0], T[t][1]);
      vertex_uf.unite(T[t][0], T[t][2]);
    }
  std::size_t count = 0;
  for (std::size_t v = 0; v < nv; ++v)
    if (classes.referenced[v] && vertex_uf.find(Index(v)) == v) ++count;
  return count;
}

}  // namespace

VertexIncidence build_incidence(const IndexedMesh& mesh, const TriangleClasses& classes) {
  const auto& T = mesh.triangles;
  const std::size_t nv = mesh.positions.size(), nt = T.size();
  VertexIncidence in;
  std::vector<Index>& start = in.start;
  start.assign(nv + 1, 0);
  for (std::size_t t = 0; t < nt; ++t)
    if (classes.in_topology(t))
      for (Index v : T[t]) ++start[v + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  in.incident.resize(start[nv]);
  // Filled through the offsets themselves (start[v] runs to v's end, then
  // every offset moves one up): no copy of the offsets at the check's peak.
  for (std::size_t t = 0; t < nt; ++t)
    if (classes.in_topology(t))
      for (Index v : T[t]) in.incident[start[v]++] = Index(t);
  for (std::size_t v = nv; v > 0; --v) start[v] = start[v - 1];
  start[0] = 0;
  return in;
}

std::vector<Index> check_topology(const IndexedMesh& mesh, const TriangleClasses& classes,
                                  const VertexIncidence& incidence, std::size_t max_examples, MeshCheckReport& r) {
  r.num_duplicate_triangles = count_duplicate_triangles(mesh, incidence);
  std::vector<Index> component;
  {
    // The union-find (5 bytes a triangle) goes back once the components are
    // labelled, before the vertex links: the check runs at the whole run's
    // peak of memory.
    UnionFind faces_uf(mesh.triangles.size());  // triangles joined through shared edges
    const EdgeCounts edges = scan_edges(mesh, incidence, faces_uf, max_examples, r);
    component = label_components(classes, faces_uf, r);
    count_component_edges(edges, component, r);
  }
  check_vertex_links(mesh, incidence, component, max_examples, r);
  set_euler_and_genus(r);
  r.num_vertex_components = count_vertex_components(mesh, classes);
  return component;
}

}  // namespace skinmesh::geometry::mesh_checks_detail
