// skin/vertex_data.h: the per-vertex data of a mesh of the skin that the
// stages share through the half-edge mesh's properties — written by the
// sweep (front/), read and updated by the refinement and the angle
// improvement (refine/), read by the pipeline's output (mesher/) and the
// recorder (trace/). Each is named once here, with its type, so that a
// mismatch of name or type is a compile error, not a missing property.
#pragma once

#include <cstdint>

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

}  // namespace skinmesh::skin
