// geometry/mesh_io.h: writing and reading IndexedMesh as PLY, OFF or OBJ, the last
// stage of the pipeline (papers/conventions.md §2) and the verifier's way back in.
// Formats: PLY (G. Turk, "The PLY Polygon File Format", 1994), OFF (Geomview),
// Wavefront OBJ. Implemented in geometry/mesh_io.cpp (dispatch, file writing and
// reading) and one file per format, geometry/mesh_io_{ply,off,obj}.cpp (see
// geometry/mesh_io_internal.h).
#pragma once

#include <string>

#include "geometry/indexed_mesh.h"

namespace skinmesh::geometry {

// Mesh Format Types

/// The mesh file formats, chosen by file extension.
enum class MeshFormat { Ply, Off, Obj };

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

/// The format of `path` by its extension, case-insensitive: .ply, .off, .obj.
/// Throws InputError(path, 0, "unknown mesh format (expected .ply, .off or .obj)").
MeshFormat mesh_format_from_extension(const std::string& path);

/// Writes `mesh` to `path` in the format of its extension:
/// - .ply: binary little-endian PLY; element vertex with x, y, z, then nx, ny, nz
///   if mesh.normals is set (both double or both float, see MeshWriteOptions),
///   then `int atom` if mesh.atom is set; element face with
///   `list uchar int vertex_indices`.
/// - .off: OFF, or NOFF (x y z nx ny nz per vertex) if normals are set; atom ids
///   are not stored.
/// - .obj: `v` lines, `vn` lines (one per vertex, faces written `f a//a b//b c//c`)
///   if normals are set; atom ids are not stored.
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
/// Only triangles are accepted. Throws InputError(path, line, problem) for an
/// unreadable file, a malformed header or record, a non-numeric or non-finite
/// number, a face that is not a triangle, an index out of range, or a truncated
/// binary file; `line` is the 1-based text line (0 in PLY binary data, where the
/// problem names the element index instead).
IndexedMesh read_mesh(const std::string& path);

/// Reads a triangle mesh from `data`, the whole content of a mesh file in
/// `format`, exactly as read_mesh() reads a file; `name` stands for the path in
/// every InputError(name, line, problem) (empty: the problem alone). The
/// in-memory entry point of read_mesh(), which reads the file and calls it.
IndexedMesh read_mesh_from_bytes(const std::string& data, MeshFormat format, const std::string& name = "");

/// Writes `bytes` to a fresh temporary file beside `path`, then renames it onto
/// `path`, so that readers never see a partial file. On any failure the
/// temporary file is removed and InputError(path, 0, "cannot write <what>
/// (reason)") is thrown.
void write_file_atomically(const std::string& path, const std::string& bytes, const std::string& what = "file");

}  // namespace skinmesh::geometry
