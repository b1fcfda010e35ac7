// geometry/io/mesh_io.h: writing and reading IndexedMesh as PLY, OFF, OBJ, STL, VTK
// or MSMS, the last stage of the pipeline (papers/conventions.md §2) and the
// verifier's way back in. Formats: PLY (G. Turk, "The PLY Polygon File Format",
// 1994), OFF (Geomview), Wavefront OBJ, STL (3D Systems), legacy VTK (Kitware,
// "VTK File Formats"), MSMS .vert/.face (M. F. Sanner, Biopolymers 38, 1996).
// Implemented in geometry/io/mesh_io.cpp (dispatch, file writing and reading) and
// one file per format, geometry/mesh_io_{ply,off,obj,stl,vtk,msms}.cpp (see
// geometry/io/mesh_io_internal.h).
#pragma once

#include <string>
#include <utility>

#include "geometry/mesh/indexed_mesh.h"

namespace skinmesh::geometry {

// Mesh Format Types

/// The mesh file formats, chosen by file extension.
enum class MeshFormat { Ply, Off, Obj, Stl, Vtk, Msms };

/// How write_mesh() stores numbers.
struct MeshWriteOptions {
  /// true (default): positions and normals as 64-bit doubles (PLY `double`; OFF
  /// and OBJ with the shortest decimal text that reads back to the same double),
  /// so a read-back mesh is bit-identical and vertices keep their distance to the
  /// skin (the verifier checks it to 1e-9 Å, which float32 cannot resolve).
  /// false: 32-bit floats (PLY `float`, the PLY norm; OFF/OBJ text of the value
  /// rounded to float), half the size.
  bool double_precision = true;
};

// Mesh I/O Public Functions

/// The format of `path` by its extension, case-insensitive: .ply, .off, .obj,
/// .stl, .vtk, and .vert or .face (MSMS). Throws InputError(path, 0, "unknown
/// mesh format (expected ...)").
MeshFormat mesh_format_from_extension(const std::string& path);

/// The two files of the MSMS mesh `path` (NAME.vert or NAME.face): NAME.vert
/// and NAME.face. Throws InputError if `path` ends in neither.
std::pair<std::string, std::string> msms_paths(const std::string& path);

/// Writes `mesh` to `path` in the format of its extension:
/// - .ply: binary little-endian PLY; element vertex with x, y, z, then nx, ny, nz
///   if mesh.normals is set (both double or both float, see MeshWriteOptions),
///   then `int atom` if mesh.atom is set; element face with
///   `list uchar int vertex_indices`.
/// - .off: OFF, or NOFF (x y z nx ny nz per vertex) if normals are set; atom ids
///   are not stored.
/// - .obj: `v` lines, `vn` lines (one per vertex, faces written `f a//a b//b c//c`)
///   if normals are set; atom ids are not stored.
/// - .stl: binary STL, float32 corners and facet normals (the usual format of 3D
///   printing); one record per triangle, no shared vertices, no attributes.
/// - .vtk: legacy VTK, ascii POLYDATA (ParaView, VTK): POINTS, POLYGONS, and as
///   attributes POINT_DATA `normals`, `atom` and `rho` (those set) and CELL_DATA
///   `min_angle` (degrees).
/// - .vert or .face (MSMS): both NAME.vert and NAME.face, in the layout MSMS
///   writes (three header lines; per vertex position, normal, component, 1-based
///   atom, patch type; per face 1-based vertices, type, component; positions to
///   1e-3 Å; geometry/io/mesh_io_msms.cpp). Both are written to temporary files
///   first and then renamed one right after the other, so that a failed write
///   leaves an earlier pair as it was.
/// The file is written to a temporary file next to `path` and renamed onto `path`
/// only once complete, so a failure never leaves a partial file.
/// Pre (checked, std::logic_error): normals and atom empty or one per vertex,
/// every index < positions.size() <= 2^31 - 1.
/// Throws InputError(path, 0, "unknown mesh format ...") or
/// InputError(path, 0, "cannot write ...") when the file cannot be written.
void write_mesh(const std::string& path, const IndexedMesh& mesh, const MeshWriteOptions& opt = {});

/// Reads a triangle mesh from `path` by its extension:
/// - PLY: ascii, binary_little_endian or binary_big_endian; vertex x, y, z of any
///   numeric type; nx, ny, nz if all three are present; an integer `atom` if
///   present; other vertex properties and other elements skipped; faces from a
///   list property `vertex_indices` (or `vertex_index`) of any integer types.
/// - OFF and NOFF (also the C and ST prefixes: colours and texture coordinates
///   are ignored), one vertex or face per line, `#` comments.
/// - OBJ: `v`, `vn` and `f` with the index forms a, a/b, a//c, a/b/c, negative
///   (relative) indices allowed; other statements ignored. Normals are per
///   vertex: kept only if every vertex gets exactly one normal through the faces.
/// - STL: binary (recognised by its size, 84 + 50 · triangles bytes) or ascii;
///   corners with identical coordinates are merged into one vertex; no normals.
/// - VTK: legacy ascii POLYDATA with POINTS and POLYGONS (triangles), POINT_DATA
///   NORMALS and SCALARS `atom` and `rho` kept, other attributes skipped;
///   binary legacy files and other datasets are refused.
/// - MSMS: NAME.vert and NAME.face (either name given): positions, normals and
///   the 1-based atom (stored 0-based in `atom`).
/// Only triangles are accepted. Throws InputError(path, line, problem) for an
/// unreadable file, a malformed header or record, a non-numeric or non-finite
/// number, a face that is not a triangle, an index out of range, or a truncated
/// binary file; `line` is the 1-based text line (0 in PLY binary data, where the
/// problem names the element index instead).
IndexedMesh read_mesh(const std::string& path);

/// Reads a triangle mesh from `data`, the whole content of a mesh file in
/// `format`, exactly as read_mesh() reads a file; `name` stands for the path in
/// every InputError(name, line, problem) (empty: the problem alone). The
/// in-memory entry point of read_mesh(), which reads the file and calls it. For
/// MSMS, `data` is the .vert file's content followed by the .face file's.
IndexedMesh read_mesh_from_bytes(const std::string& data, MeshFormat format, const std::string& name = "");

/// How far (Å) the format of `path` may have moved the positions of `mesh`
/// read from it: 1e-3 for MSMS (three decimals, at most 0.87e-3 off); for
/// STL (float32 corners) twice sqrt(3) half-units in the last place of its
/// largest coordinate; 0 for PLY, OFF, OBJ and VTK as skinmesh writes them
/// (exact). The verifier's vertex-distance tolerance must not be below it.
double position_rounding(const std::string& path, const IndexedMesh& mesh);

/// Writes `bytes` to a fresh temporary file beside `path`, then renames it onto
/// `path`, so that readers never see a partial file. On any failure the
/// temporary file is removed and InputError(path, 0, "cannot write <what>
/// (reason)") is thrown.
void write_file_atomically(const std::string& path, const std::string& bytes, const std::string& what = "file");

}  // namespace skinmesh::geometry
