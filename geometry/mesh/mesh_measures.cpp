// geometry/mesh/mesh_measures.cpp: vertex_components() by union-find over the
// triangles' vertices; component_measures() then sums, in one pass, areas and signed
// volumes relative to each component's first vertex (small coordinates, so
// that the volume of a molecule far from the origin loses no digits).
#include "geometry/mesh/mesh_measures.h"

#include <numeric>

namespace skinmesh::geometry {

std::vector<int> vertex_components(const IndexedMesh& mesh) {
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
  std::vector<char> used(n, 0);
  for (const auto& t : mesh.triangles)
    for (Index v : t) used[v] = 1;
  std::vector<int> label(n, 0);
  int next = 0;
  for (Index v = 0; v < n; ++v) {
    if (!used[v]) continue;
    const Index r = find(v);
    label[v] = r == v ? ++next : label[r];  // the root comes first: it is the smallest
  }
  return label;
}

std::vector<ComponentMeasure> component_measures(const IndexedMesh& mesh) {
  return component_measures(mesh, vertex_components(mesh));
}

std::vector<ComponentMeasure> component_measures(const IndexedMesh& mesh, const std::vector<int>& label) {
  std::vector<ComponentMeasure> out;
  std::vector<Index> origin;  // component -> its first vertex
  for (Index v = 0; v < label.size(); ++v) {
    if (label[v] == 0) continue;
    if (static_cast<std::size_t>(label[v]) > out.size()) out.emplace_back(), origin.push_back(v);
    ++out[label[v] - 1].vertices;
  }
  for (const auto& t : mesh.triangles) {
    const int c = label[t[0]] - 1;
    const Vec3& o = mesh.positions[origin[c]];
    const Vec3 a = mesh.positions[t[0]] - o, b = mesh.positions[t[1]] - o, cc = mesh.positions[t[2]] - o;
    ++out[c].triangles;
    out[c].area += (b - a).cross(cc - a).norm() / 2;
    out[c].volume += a.dot(b.cross(cc)) / 6;
  }
  return out;
}

}  // namespace skinmesh::geometry
