// skin/shells.cpp: the shell selection of skin/shells.h.
#include "skin/shells.h"

#include <numeric>
#include <stdexcept>

#include "geometry/mesh/mesh_measures.h"

namespace skinmesh::skin {

const char* cavity_choice_name(CavityChoice c) {
  switch (c) {
    case CavityChoice::Keep:
      return "keep";
    case CavityChoice::Remove:
      return "remove";
    case CavityChoice::Only:
      return "only";
  }
  return "?";
}

CavityChoice cavity_choice_named(const std::string& name) {
  for (CavityChoice c : {CavityChoice::Keep, CavityChoice::Remove, CavityChoice::Only})
    if (name == cavity_choice_name(c)) return c;
  throw std::invalid_argument("unknown cavity choice '" + name + "' (keep, remove or only)");
}

bool ShellSelection::keeps(double volume) const {
  if (volume >= 0) return cavities != CavityChoice::Only;
  return cavities != CavityChoice::Remove && -volume >= min_cavity_volume;
}

namespace {

/// v[i] for the kept entries, in order, if v has one entry per vertex.
template <class T>
void keep_entries(std::vector<T>& v, const std::vector<Index>& new_index) {
  if (v.size() != new_index.size()) return;
  std::size_t n = 0;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (new_index[i] != kInvalidIndex) v[n++] = v[i];
  v.resize(n);
  v.shrink_to_fit();
}

/// Euler characteristic V - E + F of the triangles of one component
/// (closed: E = 3F/2).
std::int64_t euler_of(std::size_t vertices, std::size_t triangles) {
  return static_cast<std::int64_t>(vertices) - static_cast<std::int64_t>(3 * triangles / 2) +
         static_cast<std::int64_t>(triangles);
}

}  // namespace

ShellCounts select_shells(geometry::IndexedMesh& mesh, SkinVertexData* data, std::vector<Index>* vertex_cells,
                          const ShellSelection& selection) {
  ShellCounts counts;
  const std::vector<int> component = geometry::vertex_components(mesh);
  const std::vector<geometry::ComponentMeasure> measures = geometry::component_measures(mesh, component);
  std::vector<char> keep(measures.size() + 1, 0);  // by component number, 1-based
  for (std::size_t c = 0; c < measures.size(); ++c) {
    const geometry::ComponentMeasure& m = measures[c];
    const bool cavity = m.volume < 0, kept = selection.keeps(m.volume);
    keep[c + 1] = kept;
    (kept ? (cavity ? counts.cavities : counts.bodies) : (cavity ? counts.removed_cavities : counts.removed_bodies))++;
    (kept ? counts.kept_euler : counts.removed_euler).push_back(euler_of(m.vertices, m.triangles));
    if (!kept && cavity) counts.removed_cavity_volume -= m.volume;
  }
  if (counts.removed_bodies + counts.removed_cavities == 0) return counts;

  std::vector<Index> new_index(mesh.positions.size(), kInvalidIndex);
  Index n = 0;
  for (std::size_t v = 0; v < new_index.size(); ++v)
    if (keep[component[v]]) new_index[v] = n++;
  std::size_t t = 0;
  for (const auto& tri : mesh.triangles)
    if (keep[component[tri[0]]]) mesh.triangles[t++] = {new_index[tri[0]], new_index[tri[1]], new_index[tri[2]]};
  mesh.triangles.resize(t);
  mesh.triangles.shrink_to_fit();
  keep_entries(mesh.normals, new_index);
  keep_entries(mesh.positions, new_index);
  if (data != nullptr) {
    keep_entries(data->atom, new_index);
    keep_entries(data->rho, new_index);
    keep_entries(data->patch, new_index);
  }
  if (vertex_cells != nullptr) keep_entries(*vertex_cells, new_index);
  return counts;
}

SkinTopology kept_topology(const SkinTopology& all, const ShellCounts& counts) {
  SkinTopology t = all;
  t.betti0 = static_cast<int>(counts.bodies);
  t.betti2 = static_cast<int>(counts.cavities);
  t.euler_k0 =
      static_cast<int>(std::accumulate(counts.kept_euler.begin(), counts.kept_euler.end(), std::int64_t{0}) / 2);
  return t;
}

}  // namespace skinmesh::skin
