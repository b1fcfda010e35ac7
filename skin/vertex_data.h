// skin/vertex_data.h: the per-vertex data of a mesh of the skin. While the
// mesh is built, the stages share it through the half-edge mesh's properties —
// written by the sweep (front/), read and updated by the refinement and the
// angle improvement (refine/), read by the pipeline's output (mesher/) and the
// recorder (trace/); each is named once here, with its type, so that a
// mismatch of name or type is a compile error, not a missing property. The
// output mesh (a geometry::IndexedMesh) carries it beside it as SkinVertexData,
// which the skin's mesh files store (skin/skin_mesh_io.h).
#pragma once

#include <cstdint>
#include <vector>

#include "core/types.h"
#include "geometry/mesh/surface_mesh.h"

namespace skinmesh::skin {

/// Unit outward normal of the skin at the vertex (the gradient direction of f).
inline constexpr geometry::VertexPropertyKey<Vec3> kVertexNormal{"v:normal"};
/// Local length scale rho at the vertex (Å; Cheng & Shi §2.2).
inline constexpr geometry::VertexPropertyKey<double> kVertexRho{"v:rho"};
/// The mixed cell that holds the vertex (an index into skin::MixedComplex).
inline constexpr geometry::VertexPropertyKey<Index> kVertexCell{"v:cell"};
/// 1 on the vertices the local refinement inserted (refine/local_refinement.h).
inline constexpr geometry::VertexPropertyKey<std::uint8_t> kVertexInserted{"v:inserted"};

/// The skin's data at the vertices of an output mesh, each array empty or one
/// entry per vertex of its geometry::IndexedMesh:
/// - `atom`: the index (0-based, into the input atom list) of the atom whose
///   skin patch holds the vertex (SkinSurface::atom_of), -1 if none;
/// - `rho`: the local length scale rho of the skin at the vertex (Å, Cheng &
///   Shi §2.2);
/// - `patch`: the dimension (0..3) of the Delaunay simplex of the vertex's
///   mixed cell — 0: an atom's sphere patch, 1 and 2: hyperboloid patches, 3:
///   a concave sphere patch.
struct SkinVertexData {
  std::vector<std::int32_t> atom;
  std::vector<double> rho;
  std::vector<std::uint8_t> patch;
};

}  // namespace skinmesh::skin
