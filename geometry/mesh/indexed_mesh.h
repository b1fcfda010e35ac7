// geometry/mesh/indexed_mesh.h: a plain triangle mesh (shared vertex array plus index
// triples) with optional per-vertex normals, and the named per-vertex scalars
// that mesh files carry beside it. The exchange format between the mesher,
// the writers/readers (geometry/io/mesh_io) and the verifier (geometry/check/mesh_checks):
// unlike the half-edge SurfaceMesh it can hold any triangle soup, including the
// broken ones a verifier must diagnose.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "core/types.h"

namespace skinmesh::geometry {

/// Triangle mesh as arrays. Triangles are counter-clockwise seen from outside
/// (their normal (b-a)x(c-a) points out of the body). `normals` is either
/// empty or holds the unit outward surface normal of every vertex. Data that
/// means something only to a layer above (the skin's atom index, rho and patch
/// of a vertex: skin::SkinVertexData) is not part of the mesh; it reaches the
/// files as VertexAttribute arrays (geometry/io/mesh_io.h).
struct IndexedMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<Index, 3>> triangles;
  std::vector<Vec3> normals;
};

/// One named scalar per vertex, as mesh files carry them (a PLY vertex
/// property, a legacy VTK POINT_DATA SCALARS array) and as the geometry layer
/// passes them through without knowing their meaning. `integer`: the values are
/// integers in the int32 range (written as `int`); otherwise reals (written as
/// double, or float if MeshWriteOptions::double_precision is false). `values`
/// holds one entry per vertex (integers exactly: every int32 is a double).
struct VertexAttribute {
  std::string name;
  bool integer = false;
  std::vector<double> values;
};

/// The attribute of `attributes` named `name`, or nullptr.
inline const VertexAttribute* find_attribute(const std::vector<VertexAttribute>& attributes, std::string_view name) {
  for (const VertexAttribute& a : attributes)
    if (a.name == name) return &a;
  return nullptr;
}

}  // namespace skinmesh::geometry
