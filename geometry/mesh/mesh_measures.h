// geometry/mesh/mesh_measures.h: what a closed triangle mesh measures — per
// connected component its area and the volume it encloses (divergence
// theorem), for the reports of `skinmesh mesh --stats`.
// Notes: papers/geometry/io/mesh_io.md ("Measures").
#pragma once

#include <cstddef>
#include <vector>

#include "geometry/mesh/indexed_mesh.h"

namespace skinmesh::geometry {

/// One connected component of a mesh (triangles sharing vertices).
struct ComponentMeasure {
  std::size_t vertices = 0, triangles = 0;
  /// Sum of the triangles' areas (Å²).
  double area = 0;
  /// Signed volume enclosed by the component (Å³): (1/6) Σ (a - o)·((b - o) × (c - o))
  /// over its triangles, o the component's first vertex. For a closed,
  /// outward-oriented surface it is the volume inside; for the surface of a
  /// cavity (oriented into the cavity, away from the body) it is minus the
  /// cavity's volume. Meaningless for an open component.
  double volume = 0;
};

/// The connected component of every vertex (through the triangles' vertices):
/// 1, 2, ... in the order of the components' smallest vertex index; 0 for a
/// vertex in no triangle. Pre: every triangle index < mesh.positions.size().
std::vector<int> vertex_components(const IndexedMesh& mesh);

/// The connected components of `mesh`, in the order of their smallest vertex
/// index, with their measures. Vertices in no triangle are not counted.
/// Pre: every triangle index < mesh.positions.size().
std::vector<ComponentMeasure> component_measures(const IndexedMesh& mesh);

/// component_measures(mesh) for a caller that has `label` =
/// vertex_components(mesh) already. Pre: as vertex_components(), and `label`
/// is that function's result for `mesh`.
std::vector<ComponentMeasure> component_measures(const IndexedMesh& mesh, const std::vector<int>& label);

}  // namespace skinmesh::geometry
