// geometry/mesh/indexed_mesh.h: a plain triangle mesh (shared vertex array plus index
// triples) with optional per-vertex data. The exchange format between the mesher,
// the writers/readers (geometry/io/mesh_io) and the verifier (geometry/check/mesh_checks):
// unlike the half-edge SurfaceMesh it can hold any triangle soup, including the
// broken ones a verifier must diagnose.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/types.h"

namespace skinmesh::geometry {

/// Triangle mesh as arrays. Triangles are counter-clockwise seen from outside
/// (their normal (b-a)x(c-a) points out of the body). `normals`, `atom`,
/// `rho` and `patch` are either empty or have one entry per vertex: the unit
/// outward surface normal; the index (0-based, into the input atom list) of
/// the atom whose skin patch holds the vertex (-1 if none); the local length
/// scale rho of the skin at the vertex (Å, Cheng & Shi §2.2); the dimension
/// (0..3) of the Delaunay simplex of the vertex's mixed cell — 0: an atom's
/// sphere patch, 1 and 2: hyperboloid patches, 3: a concave sphere patch.
struct IndexedMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<Index, 3>> triangles;
  std::vector<Vec3> normals;
  std::vector<std::int32_t> atom;
  std::vector<double> rho;
  std::vector<std::uint8_t> patch;
};

}  // namespace skinmesh::geometry
