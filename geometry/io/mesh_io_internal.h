// geometry/io/mesh_io_internal.h: the private header of the mesh readers and
// writers — the number and index helpers the formats share, and one writer and
// one reader per format, each format in its own file:
//   mesh_io.cpp      dispatch by extension (mesh_io.h), atomic file writing,
//                    file reading, and the shared helpers below
//   mesh_io_ply.cpp  PLY: binary little-endian or ascii writer; ascii / binary reader
//   mesh_io_off.cpp  OFF (NOFF on request) writer and OFF/NOFF reader
//   mesh_io_obj.cpp  Wavefront OBJ writer and reader
//   mesh_io_stl.cpp  STL: binary or ascii writer; binary / ascii reader
//   mesh_io_vtk.cpp  legacy VTK POLYDATA: ascii writer (with attributes) and reader
//   mesh_io_vtk_xml.cpp  XML VTK PolyData (.vtp) and UnstructuredGrid (.vtu):
//                    ascii writer (every attribute a named array) and reader
// Numbers go through std::to_chars / std::from_chars: shortest text that reads
// back to the same double, and correctly rounded parsing, so text round trips are
// bit-exact. Only geometry/io/mesh_io*.cpp include this header.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/text_numbers.h"  // to_int, number_or_throw, int_or_throw
#include "geometry/io/mesh_io.h"
#include "geometry/mesh/indexed_mesh.h"

namespace skinmesh::geometry::mesh_io_detail {

// Shared Helpers (mesh_io.cpp)

/// Appends the shortest decimal text that reads back to `v` (or, if
/// !double_precision, to float(v)).
void append_number(std::string& out, double v, bool double_precision);

/// Appends the decimal text of `i`.
void append_index(std::string& out, std::uint64_t i);

/// Appends one line "3 a b c" per triangle (0-based indices), spilling after
/// each: the polygon list of OFF and of legacy VTK.
void append_triangle_lines(ChunkedWriter& out, const std::vector<std::array<Index, 3>>& triangles);

/// Checks that every triangle index is < positions.size(); `lines[i]` (if given)
/// is the source line of triangle i. Throws InputError(path, line, "face i: vertex
/// index v out of range (n vertices)").
void check_indices(const std::string& path, const IndexedMesh& m, const std::vector<int>& lines);

// Formats: writers make the whole file into a ChunkedWriter (mesh_io.h),
// spilling it record by record, and leave the last chunk for the caller to
// flush; readers take the whole file `data` read from `path` (for messages) and
// throw InputError as read_mesh() says.

/// The PLY file of `m`, binary little-endian or, with opt.ascii, ASCII
/// (layout: write_mesh() in mesh_io.h).
/// Pre: `m` passed the checks of write_mesh() (check_writable in mesh_io.cpp).
void write_ply(const IndexedMesh& m, const std::vector<VertexAttribute>& attributes, const MeshWriteOptions& opt,
               ChunkedWriter& out);

/// Reads a PLY file (ascii, binary_little_endian or binary_big_endian); the
/// scalar vertex properties besides the position and normal into `attributes`.
IndexedMesh read_ply(const std::string& path, const std::string& data, std::vector<VertexAttribute>& attributes);

/// The OFF file of `m`: plain OFF, or NOFF if opt.off_normals and m.normals is set.
void write_off(const IndexedMesh& m, const MeshWriteOptions& opt, ChunkedWriter& out);

/// Reads an OFF file ([ST][C][N]OFF, ascii).
IndexedMesh read_off(const std::string& path, const std::string& data);

/// The Wavefront OBJ file of `m` (`v`, then `vn` and `f a//a b//b c//c` if
/// m.normals is set, else `f a b c`; 1-based indices).
void write_obj(const IndexedMesh& m, const MeshWriteOptions& opt, ChunkedWriter& out);

/// Reads a Wavefront OBJ file (`v`, `vn`, `f`; other statements ignored).
IndexedMesh read_obj(const std::string& path, const std::string& data);

/// The binary STL file of `m` (80-byte header, triangle count, per triangle
/// the unit facet normal and the three corners as float32, 2 zero bytes), or
/// with opt.ascii the `solid skinmesh` text with the same records, numbers as
/// append_number() writes them.
void write_stl(const IndexedMesh& m, const MeshWriteOptions& opt, ChunkedWriter& out);

/// Reads a binary or ascii STL file; corners with identical coordinates
/// become one vertex (in order of first appearance). No normals.
IndexedMesh read_stl(const std::string& path, const std::string& data);

/// The legacy VTK file of `m` (ascii POLYDATA; POINT_DATA normals when set and
/// one SCALARS array per attribute; CELL_DATA min_angle in degrees).
void write_vtk(const IndexedMesh& m, const std::vector<VertexAttribute>& attributes, const MeshWriteOptions& opt,
               ChunkedWriter& out);

/// Reads an ascii legacy VTK POLYDATA file (POINTS, POLYGONS of triangles;
/// VERTICES and LINES skipped; POINT_DATA NORMALS kept, one-component SCALARS
/// into `attributes`, other attributes skipped).
IndexedMesh read_vtk(const std::string& path, const std::string& data, std::vector<VertexAttribute>& attributes);

/// The XML VTK file of `m`: PolyData (.vtp), or with `unstructured`
/// UnstructuredGrid (.vtu) of triangle cells; positions, normals ("normals",
/// the active normals) and every attribute as ASCII DataArrays, numbers as
/// append_number() writes them, per triangle `min_angle` (degrees).
void write_vtk_xml(const IndexedMesh& m, const std::vector<VertexAttribute>& attributes, const MeshWriteOptions& opt,
                   bool unstructured, ChunkedWriter& out);

/// Reads an XML VTK PolyData or UnstructuredGrid file of one piece of
/// triangles with ASCII data arrays: the points, the active normals (or the
/// 3-component point array "normals"), every 1-component point array into
/// `attributes`. Refuses binary and appended arrays, other cells,
/// triangle strips and several pieces.
IndexedMesh read_vtk_xml(const std::string& path, const std::string& data, std::vector<VertexAttribute>& attributes);

}  // namespace skinmesh::geometry::mesh_io_detail
