// skin/atom_areas.h: the area of a mesh of the skin per atom, and the file of
// per-atom areas in the layout of MSMS's .area (one header line, one line per
// atom), which surface-learning pipelines read beside the .vert/.face. The
// exact skin's area per atom is skin/skin_measures.h's atom_areas().
// Notes: papers/skin/atom_areas.md
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/mesh/indexed_mesh.h"

namespace skinmesh::skin {

/// The area (Å²) of `mesh` per atom: each triangle's area, a third to the
/// atom of each of its corners (`atom`, as SkinVertexData::atom: 0-based,
/// the atom nearest in power distance among those of the vertex's mixed
/// cell). Corners of atom -1 or >= num_atoms add to no atom, so the entries
/// sum to the mesh's area exactly when every vertex has an atom (up to
/// rounding); an empty `atom` (no atoms known) gives zeros. Returns num_atoms
/// entries. Throws std::invalid_argument if `atom` is neither empty nor one
/// per vertex, or a triangle's index is out of range.
std::vector<double> mesh_atom_areas(const geometry::IndexedMesh& mesh, const std::vector<std::int32_t>& atom,
                                    std::size_t num_atoms);

/// Writes the per-atom areas to `path` (atomically, as the meshes): a header
/// line "#  atom  skin_area  mesh_area[  name]", then per atom, in input
/// order, its 1-based number (as the MSMS .vert atom field), the exact skin's
/// area and the mesh's (Å², six decimals) and, if `names` is not empty, the
/// atom's name (msms_atom_name()) as a fourth field — the fields MSMS's
/// .area has in these places, so readers that take the second field as the
/// atom's area, and MaSIF's that keys it by the fourth, read it. Throws
/// std::invalid_argument if the lengths differ (names may be empty) and
/// InputError(path, 0, "cannot write ...") if the file cannot be written.
void write_area_file(const std::string& path, const std::vector<double>& skin_area,
                     const std::vector<double>& mesh_area, const std::vector<std::string>& names = {});

}  // namespace skinmesh::skin
