// geometry/mesh_measures.cpp: component_measures() — components by union-find
// over the triangles' vertices, then one pass summing areas and signed
// volumes relative to each component's first vertex (small coordinates, so
// that the volume of a molecule far from the origin loses no digits).
#include "geometry/mesh_measures.h"

#include <numeric>

namespace skinmesh::geometry {

std::vector<ComponentMeasure> component_measures(const IndexedMesh& mesh) {
  const std::size_t n = mesh.positions.size();
  std::vector<Index> parent(n);
  std::iota(parent.begin(), parent.end(), Index(0));
  const auto find = [&parent](Index v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& t : mesh.triangles)
    for (int k = 1; k < 3; ++k) {
      const Index a = find(t[0]), b = find(t[k]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the root is the smallest vertex
    }
  std::vector<Index> slot(n, kInvalidIndex);  // root -> component
  std::vector<Index> origin;                  // component -> its first vertex
  std::vector<char> used(n, 0);
  for (const auto& t : mesh.triangles)
    for (Index v : t) used[v] = 1;
  std::vector<ComponentMeasure> out;
  for (Index v = 0; v < n; ++v) {
    if (!used[v]) continue;
    const Index r = find(v);
    if (slot[r] == kInvalidIndex) {
      slot[r] = static_cast<Index>(out.size());
      out.emplace_back();
      origin.push_back(v);
    }
    ++out[slot[r]].vertices;
  }
  for (const auto& t : mesh.triangles) {
    ComponentMeasure& c = out[slot[find(t[0])]];
    const Vec3& o = mesh.positions[origin[slot[find(t[0])]]];
    const Vec3 a = mesh.positions[t[0]] - o, b = mesh.positions[t[1]] - o, cc = mesh.positions[t[2]] - o;
    ++c.triangles;
    c.area += (b - a).cross(cc - a).norm() / 2;
    c.volume += a.dot(b.cross(cc)) / 6;
  }
  return out;
}

}  // namespace skinmesh::geometry
