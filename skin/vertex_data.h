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
#include "skin/mixed_complex.h"

namespace skinmesh::skin {

/// The mixed cell that holds the vertex (an index into skin::MixedComplex).
/// With the vertex's position it fixes the skin's normal and rho there
/// (VertexNormals, VertexRhos), which are therefore not stored.
inline constexpr geometry::VertexPropertyKey<Index> kVertexCell{"v:cell"};
/// 1 on the vertices the local refinement inserted (refine/local_refinement.h).
inline constexpr geometry::VertexPropertyKey<std::uint8_t> kVertexInserted{"v:inserted"};

/// A value of the skin at the vertices of a mesh of the skin, derived on each
/// read from the vertex's position and its mixed cell (kVertexCell) by
/// MixedComplex member `Of`. Every stage places a vertex with a sample of the
/// skin there (SkinSurface::sample) and stores that sample's cell, so the
/// value read is bit for bit the sample's; keeping it would cost its bytes
/// for every vertex through every stage (papers/decompose/history.md,
/// "Normals and rho from the cell").
/// Preconditions: `mc` and `mesh` outlive the view, `mesh` has the kVertexCell
/// property, and every vertex read has a valid cell.
template <class T, T (MixedComplex::*Of)(Index, const Vec3&) const>
class VertexSkinValues {
 public:
  VertexSkinValues() = default;
  VertexSkinValues(const MixedComplex& mc, const geometry::SurfaceMesh& mesh)
      : mc_(&mc), mesh_(&mesh), cell_(mesh.get_vertex_property(kVertexCell)) {}
  T operator[](geometry::Vertex v) const { return (mc_->*Of)(cell_[v], mesh_->position(v)); }

 private:
  const MixedComplex* mc_ = nullptr;
  const geometry::SurfaceMesh* mesh_ = nullptr;
  geometry::VertexProperty<Index> cell_;
};

/// The unit outward normal of the skin (the gradient direction of f, Cheng &
/// Shi §2.1) at the vertices: MixedComplex::unit_normal.
using VertexNormals = VertexSkinValues<Vec3, &MixedComplex::unit_normal>;
/// The local length scale rho (Å, Cheng & Shi §2.2) at the vertices:
/// MixedComplex::rho.
using VertexRhos = VertexSkinValues<double, &MixedComplex::rho>;

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
