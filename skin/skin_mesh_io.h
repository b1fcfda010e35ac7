// skin/skin_mesh_io.h: the files of a mesh of the skin — the geometric formats
// of geometry/io/mesh_io.h (PLY, OFF, OBJ, STL, VTK) with the skin's vertex data
// (SkinVertexData) as their per-vertex attributes, and the molecular format
// MSMS .vert/.face (M. F. Sanner, "Reduced surface: an efficient way to compute
// molecular surfaces", Biopolymers 38, 1996), whose records hold atoms and
// patch types. Which vertex data each format stores is decided here, where
// its meaning is known; the geometry layer only passes named scalars through.
// Implemented in skin/skin_mesh_io.cpp.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "geometry/io/mesh_io.h"
#include "geometry/mesh/indexed_mesh.h"
#include "skin/molecule.h"
#include "skin/vertex_data.h"

namespace skinmesh::skin {

/// True if `path` ends in .vert or .face (case-insensitive): an MSMS mesh.
bool is_msms_path(const std::string& path);

/// The two files of the MSMS mesh `path` (NAME.vert or NAME.face): NAME.vert
/// and NAME.face. Throws InputError(path, 0, ...) if `path` ends in neither.
std::pair<std::string, std::string> msms_paths(const std::string& path);

/// Checks that `path` names a mesh format write_skin_mesh() writes: .ply,
/// .off, .obj, .stl, .vtk, or .vert/.face (case-insensitive). Throws
/// InputError(path, 0, "unknown mesh format (expected ...)").
void require_mesh_format(const std::string& path);

/// The attributes the file format `format` stores of `data`: PLY the atom
/// index (`int atom`); VTK the atom index and rho (`SCALARS atom int`,
/// `SCALARS rho double|float`); OFF, OBJ and STL none. Arrays of `data` that
/// are empty are left out.
std::vector<geometry::VertexAttribute> file_attributes(const SkinVertexData& data, geometry::MeshFormat format);

/// Fewest and most decimals of MSMS positions: MSMS's own three, up to the
/// digits that still change a double of a molecule's size (|x| < 10^4 Å).
constexpr int kMinMsmsDecimals = 3, kMaxMsmsDecimals = 12;

/// How write_skin_mesh() writes.
struct SkinMeshWriteOptions {
  /// For PLY, OFF, OBJ, STL and VTK (geometry::write_mesh()).
  geometry::MeshWriteOptions geometry;
  /// Digits after the point of MSMS positions, in [kMinMsmsDecimals,
  /// kMaxMsmsDecimals]: 3 as MSMS writes them; more for meshes whose small
  /// features three decimals break (the mesher checks them as written).
  int msms_decimals = 3;
  /// The probe radius (Å) the skin was built with, for the MSMS header.
  double probe_radius = 0;
  /// If not empty, one name per atom (msms_atom_name()): each MSMS vertex
  /// record gets its atom's name as a 10th field, as MSMS writes when its
  /// .xyzrn input names the atoms (MaSIF's read_msms.py reads it; readers
  /// that keep only 9-field records, as Biopython's, do not, hence opt-in).
  std::vector<std::string> msms_atom_names;
  /// false: MSMS files without their three header lines (MSMS's -no_header),
  /// for readers that take the records alone; read_skin_mesh() reads both.
  bool msms_header = true;
  /// One NAME.vert/.face pair per surface component, as MSMS's
  /// -all_components writes them: the first component NAME.vert/.face, the
  /// k-th (k >= 2) NAME_{k-1}.vert/.face, each with its own vertex numbers
  /// (components numbered as the single file numbers them).
  bool msms_split_components = false;
};

/// The name MSMS writes for `atom` in its 10th vertex field, in the form
/// surface-learning pipelines split at '_': chain_resnum_icode_resname_name
/// ("A_12_x_ALA_CA"); a blank chain or insertion code is written "x", a
/// blank residue "UNK", a blank atom name "X", and blanks inside a part "-".
/// An atom read from .xyzrn with a name gets that name as the file has it
/// (Atom::msms_name), as MSMS copies it.
std::string msms_atom_name(const Atom& atom);

/// How the file `path` written with `opt` stores positions:
/// PositionStorage::Kind::Decimals with opt.msms_decimals for MSMS, else
/// geometry::position_storage() of its format. Throws InputError(path, 0,
/// "unknown mesh format ...") for another extension.
geometry::PositionStorage position_storage(const std::string& path, const SkinMeshWriteOptions& opt = {});

/// Writes `mesh` with its vertex data `data` to `path` in the format of its
/// extension: geometry::write_mesh() with file_attributes(data, format) for
/// PLY, OFF, OBJ, STL and VTK (see there), or for .vert/.face (MSMS) both
/// NAME.vert and NAME.face, in the layout MSMS writes (three header lines; per
/// vertex position, normal, component, 1-based atom, patch type; per face
/// 1-based vertices, type, component; positions with opt.msms_decimals
/// decimals; the atom's name if opt.msms_atom_names is set; without header
/// lines if !opt.msms_header; one pair per component if opt.msms_split_components; the header's density in vertices per
/// Å² of mesh area and probe opt.probe_radius; skin/skin_mesh_io.cpp), written as one
/// (geometry::write_files_atomically). Pre (checked, std::logic_error): mesh and data as geometry::write_mesh()
/// requires (every array of `data` empty or one entry per vertex). Throws InputError(path, 0, "unknown mesh format
/// ...") or InputError(path, 0, "cannot write ..."), and std::invalid_argument for opt.msms_decimals out of range when
/// writing MSMS.
void write_skin_mesh(const std::string& path, const geometry::IndexedMesh& mesh, const SkinVertexData& data,
                     const SkinMeshWriteOptions& opt = {});

/// Reads a mesh of the skin from `path` (any format write_skin_mesh() writes;
/// for MSMS either name, with or without its header lines) and, if `data` is given, the vertex data the file
/// holds: `atom` from a PLY vertex property or VTK SCALARS array `atom` (an
/// integer type, values >= -1) or from the MSMS atom field (1-based in the
/// file); `rho` from a PLY property or VTK array `rho`; `patch` is not read.
/// Throws InputError(path, line, problem) as geometry::read_mesh() does, and
/// for an MSMS record or an `atom` attribute that breaks the rules above.
geometry::IndexedMesh read_skin_mesh(const std::string& path, SkinVertexData* data = nullptr);

/// Reads an MSMS mesh from `bytes`, the .vert file's content followed by the
/// .face file's (`name` stands for the paths in messages), as read_skin_mesh()
/// reads the pair, with or without header lines: the in-memory entry point
/// the fuzzers use. Without headers the .face part begins at the first line
/// of fewer than 6 fields (a vertex record has at least 6).
geometry::IndexedMesh read_msms_from_bytes(const std::string& bytes, const std::string& name,
                                           SkinVertexData* data = nullptr);

/// How far (Å) the format of `path` may have moved the positions of `mesh`
/// read from it: 1e-3 for MSMS (three decimals, at most 0.87e-3 off); for
/// another format whose every coordinate of `mesh` is a float32 value (a PLY
/// `float`, an OBJ another tool wrote from floats) the float32 rounding, as
/// for STL; else geometry::position_rounding(). The verifier's
/// vertex-distance tolerance must not be below it.
double position_rounding(const std::string& path, const geometry::IndexedMesh& mesh);

}  // namespace skinmesh::skin
