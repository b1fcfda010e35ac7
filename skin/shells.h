// skin/shells.h: which shells of a skin mesh to keep — the outer surfaces of
// the body's components and the surfaces of its cavities — and the topology a
// mesh of the kept shells must have. `skinmesh mesh --cavities keep|remove|only
// --min-cavity-volume V` and `skinmesh check` with the same options.
// Notes: papers/skin/shells.md
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"
#include "geometry/mesh/indexed_mesh.h"
#include "skin/dual_complex.h"
#include "skin/vertex_data.h"

namespace skinmesh::skin {

/// Which cavity shells a mesh keeps. A shell is a closed component of the
/// skin; a cavity shell encloses a negative volume (it is oriented away from
/// the body, into the cavity), every other shell is the outer surface of a
/// component of the body (a body inside a cavity included).
enum class CavityChoice {
  Keep,    ///< every shell (the default)
  Remove,  ///< the outer surfaces only, as MSMS writes by default
  Only,    ///< the cavities only
};

/// The name of `c` ("keep", "remove", "only").
const char* cavity_choice_name(CavityChoice c);

/// The choice named `name`; throws std::invalid_argument naming the three.
CavityChoice cavity_choice_named(const std::string& name);

/// The shells to keep: by kind, and cavities by the volume they enclose.
struct ShellSelection {
  CavityChoice cavities = CavityChoice::Keep;
  /// Cavities enclosing less than this (Å³) are left out as well (0: none).
  /// Pre: >= 0 and finite.
  double min_cavity_volume = 0;
  /// True unless every shell is kept.
  bool selects() const { return cavities != CavityChoice::Keep || min_cavity_volume > 0; }
  /// True if a shell enclosing the signed volume `volume` (Å³; negative for a
  /// cavity) is kept.
  bool keeps(double volume) const;
  /// True if some but perhaps not all cavities are kept (min_cavity_volume > 0
  /// and cavities not removed): a checker then knows only an upper bound on
  /// their number.
  bool partial_cavities() const { return min_cavity_volume > 0 && cavities != CavityChoice::Remove; }
};

/// What select_shells() kept and left out.
struct ShellCounts {
  std::size_t bodies = 0, cavities = 0;                  ///< shells kept
  std::size_t removed_bodies = 0, removed_cavities = 0;  ///< shells left out
  double removed_cavity_volume = 0;                      ///< Å³ the left-out cavities enclose (positive)
  /// Euler characteristics of the kept shells and of the left-out ones.
  std::vector<std::int64_t> kept_euler, removed_euler;
};

/// Leaves in `mesh` only the connected components `selection` keeps, by the
/// signed volume each encloses (geometry::component_measures): positions,
/// normals and triangles, and with them each per-vertex array of `data` and
/// `vertex_cells` that has one entry per vertex (empty ones stay empty).
/// Kept vertices and triangles stay in their order. Vertices in no triangle
/// are dropped when anything is left out. Pre: `mesh` closed and oriented
/// (the volumes are meaningless otherwise); triangle indices in range.
ShellCounts select_shells(geometry::IndexedMesh& mesh, SkinVertexData* data, std::vector<Index>* vertex_cells,
                          const ShellSelection& selection);

/// The topology of the kept shells of a skin of topology `all`, when the
/// mesh of all of them was checked and `counts` is what select_shells() did to
/// it: betti0 = the kept bodies, betti2 = the kept cavities, chi(K0) = half the
/// kept shells' Euler characteristic.
SkinTopology kept_topology(const SkinTopology& all, const ShellCounts& counts);

}  // namespace skinmesh::skin
