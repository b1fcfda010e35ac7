// geometry/io/mesh_io.h: writing and reading IndexedMesh as PLY, OFF, OBJ, STL or
// VTK, with named per-vertex scalars (VertexAttribute) where the format has them —
// the geometric formats, which know nothing of molecules. The skin's files (its
// vertex data in these formats, and the molecular MSMS format) are written and
// read by skin/skin_mesh_io.h on top of these. Formats: PLY (G. Turk, "The PLY
// Polygon File Format", 1994), OFF (Geomview), Wavefront OBJ, STL (3D Systems),
// legacy VTK (Kitware, "VTK File Formats"). Implemented in geometry/io/mesh_io.cpp
// (dispatch, file writing and reading) and one file per format,
// geometry/io/mesh_io_{ply,off,obj,stl,vtk}.cpp (see geometry/io/mesh_io_internal.h).
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "geometry/mesh/indexed_mesh.h"

namespace skinmesh::geometry {

// Mesh Format Types

/// The mesh file formats, chosen by file extension.
enum class MeshFormat { Ply, Off, Obj, Stl, Vtk, Vtp, Vtu };

/// How write_mesh() stores numbers.
struct MeshWriteOptions {
  /// true (default): positions and normals as 64-bit doubles (PLY `double`; OFF
  /// and OBJ with the shortest decimal text that reads back to the same double),
  /// so a read-back mesh is bit-identical and vertices keep their distance to the
  /// skin (the verifier checks it to 1e-9 Å, which float32 cannot resolve).
  /// false: 32-bit floats (PLY `float`, the PLY norm; OFF/OBJ text of the value
  /// rounded to float), half the size.
  bool double_precision = true;
  /// OFF: false (default) writes plain OFF, positions only, the one variant
  /// every OFF reader takes (meshio, PyMOL, VMD, TetGen refuse NOFF or read
  /// its normals as coordinates); true writes NOFF, x y z nx ny nz per vertex,
  /// when the mesh has normals.
  bool off_normals = false;
  /// PLY and STL: false (default) writes them binary; true writes `format
  /// ascii 1.0` PLY and `solid` STL text, for readers that take only text
  /// (TetGen 1.5 reads ASCII PLY and STL only). Numbers are the shortest text
  /// that reads back to the double (or to the float with !double_precision), so
  /// ASCII STL keeps exact positions where binary STL rounds them to float32.
  bool ascii = false;
};

// Mesh I/O Public Functions

/// The format of `path` by its extension, case-insensitive: .ply, .off, .obj,
/// .stl, .vtk; nullopt for any other name.
std::optional<MeshFormat> mesh_format_of(const std::string& path);

/// mesh_format_of(path), or throws InputError(path, 0, "unknown mesh format
/// (expected .ply, .off, .obj, .stl or .vtk)").
MeshFormat mesh_format_from_extension(const std::string& path);

/// Checks the preconditions of write_mesh() (std::logic_error through
/// SKINMESH_ASSERT_MSG): at most 2^31 - 1 vertices (PLY int indices), normals
/// empty or one per vertex, attributes one value per vertex (integers in the
/// int32 range) named by one word, every triangle index in range. For writers
/// of other formats built on this layer (skin/skin_mesh_io's MSMS).
void check_writable(const IndexedMesh& m, const std::vector<VertexAttribute>& attributes = {});

/// Writes `mesh` and its per-vertex `attributes` to `path` in the format of its
/// extension:
/// - .ply: binary little-endian PLY (ASCII with opt.ascii); element vertex with x, y, z, then nx, ny, nz
///   if mesh.normals is set (both double or both float, see MeshWriteOptions),
///   then one property per attribute in order (`int NAME` for an integer one,
///   else `double NAME` or `float NAME`); element face with
///   `list uchar int vertex_indices`.
/// - .off: plain OFF; NOFF (x y z nx ny nz per vertex) if normals are set and
///   opt.off_normals;
///   attributes are not stored.
/// - .obj: `v` lines, `vn` lines (one per vertex, faces written `f a//a b//b c//c`)
///   if normals are set; attributes are not stored.
/// - .stl: binary STL, float32 corners and facet normals (the usual format of 3D
///   printing); one record per triangle, no shared vertices, no attributes.
///   With opt.ascii: `solid` text, corners as exact doubles (floats with
///   !double_precision).
/// - .vtk: legacy VTK, ascii POLYDATA (ParaView, VTK): POINTS, POLYGONS, and as
///   POINT_DATA `normals` (if set) and one `SCALARS NAME int|double|float 1` per
///   attribute in order; CELL_DATA `min_angle` (degrees).
/// The file is written to a temporary file next to `path` and renamed onto `path`
/// only once complete, so a failure never leaves a partial file.
/// Pre (checked, std::logic_error): normals empty or one per vertex, every
/// attribute one value per vertex (integers in the int32 range) with a name
/// that is one word of letters, digits and '_', every index < positions.size()
/// <= 2^31 - 1.
/// Throws InputError(path, 0, "unknown mesh format ...") or
/// InputError(path, 0, "cannot write ...") when the file cannot be written.
void write_mesh(const std::string& path, const IndexedMesh& mesh, const MeshWriteOptions& opt = {},
                const std::vector<VertexAttribute>& attributes = {});

/// Reads a triangle mesh from `path` by its extension:
/// - PLY: ascii, binary_little_endian or binary_big_endian; vertex x, y, z of any
///   numeric type; nx, ny, nz if all three are present; every other scalar
///   vertex property as an attribute (integer if its type is); list properties
///   and other elements skipped; faces from a list property `vertex_indices`
///   (or `vertex_index`) of any integer types.
/// - OFF and NOFF (also the C and ST prefixes: colours and texture coordinates
///   are ignored), one vertex or face per line, `#` comments.
/// - OBJ: `v`, `vn` and `f` with the index forms a, a/b, a//c, a/b/c, negative
///   (relative) indices allowed; other statements ignored. Normals are per
///   vertex: kept only if every vertex gets exactly one normal through the faces.
/// - STL: binary (recognised by its size, 84 + 50 · triangles bytes) or ascii;
///   corners with identical coordinates are merged into one vertex; no normals.
/// - VTK: legacy ascii POLYDATA with POINTS and POLYGONS (triangles), POINT_DATA
///   NORMALS, and every one-component POINT_DATA SCALARS as an attribute
///   (integer if its type is); other attributes skipped; binary legacy files and
///   other datasets are refused.
/// If `attributes` is given, it receives the file's per-vertex attributes (OFF,
/// OBJ and STL have none). Only triangles are accepted. Throws InputError(path, line, problem) for an
/// unreadable file, a malformed header or record, a non-numeric or non-finite
/// number, a face that is not a triangle, an index out of range, or a truncated
/// binary file; `line` is the 1-based text line (0 in PLY binary data, where the
/// problem names the element index instead).
IndexedMesh read_mesh(const std::string& path, std::vector<VertexAttribute>* attributes = nullptr);

/// Reads a triangle mesh from `data`, the whole content of a mesh file in
/// `format`, exactly as read_mesh() reads a file; `name` stands for the path in
/// every InputError(name, line, problem) (empty: the problem alone). The
/// in-memory entry point of read_mesh(), which reads the file and calls it.
IndexedMesh read_mesh_from_bytes(const std::string& data, MeshFormat format, const std::string& name = "",
                                 std::vector<VertexAttribute>* attributes = nullptr);

/// How a file stores vertex positions, and so what a reader gets back: the
/// same doubles (Exact), each coordinate rounded to the nearest float32
/// (Float32: STL, and PLY/OFF/OBJ/VTK with double_precision false), or to a
/// fixed number of decimals (Decimals: MSMS text, skin/skin_mesh_io.h). A
/// writer that rounds can break a mesh its checks passed (a cavity of 1e-3 Å²
/// collapses at three decimals), so the mesher checks the positions as the file
/// will hold them (mesher/pipeline.h, MeshOptions::stored_positions).
struct PositionStorage {
  /// Exact: the doubles themselves. Float32: binary float32 (binary PLY
  /// `float`, binary STL). Float32Text: the shortest text of the float32
  /// value (OFF, OBJ, VTK, ASCII PLY and STL without double precision), which
  /// a reader parses as the nearest double, not always the float itself.
  /// Decimals: printf's "%.Nf" text (MSMS).
  enum class Kind { Exact, Float32, Float32Text, Decimals };
  Kind kind = Kind::Exact;
  int decimals = 0;  ///< digits after the point, for Kind::Decimals (0..17)
  /// True unless positions are stored exactly.
  bool lossy() const { return kind != Kind::Exact; }
  /// The coordinate `x` as a reader gets it back from the file: the float32
  /// nearest `x`, or the double nearest the text written for `x` (the
  /// shortest text of that float32, or printf's "%.Nf"; correctly rounded, as
  /// glibc's printf and std::to_chars are). Non-finite values are returned
  /// unchanged.
  double stored(double x) const;
  /// stored() applied to each coordinate.
  Vec3 stored(const Vec3& p) const { return {stored(p.x()), stored(p.y()), stored(p.z())}; }
  /// An upper bound (Å) on |stored(p) - p| over the positions of `mesh`:
  /// 0 for Exact; sqrt(3) half-units in the last place (float32) of the
  /// largest coordinate for Float32, sqrt(3) whole units for Float32Text (the
  /// text's double may lie up to half a float unit from the float);
  /// sqrt(3) (10^-decimals / 2 + half a double unit in the last place of the
  /// largest coordinate) for Decimals.
  double max_error(const IndexedMesh& mesh) const;
  /// How the positions are stored, for messages: "exact doubles",
  /// "float32", "float32 text", "3 decimals".
  std::string describe() const;
};

/// The position storage of write_mesh() for `format` with `opt`: Float32 for
/// binary STL (always) and binary PLY when opt.double_precision is false,
/// Float32Text for the text formats (OFF, OBJ, VTK, ASCII PLY and STL) when it
/// is false; Exact otherwise (ASCII STL included).
PositionStorage position_storage(MeshFormat format, const MeshWriteOptions& opt = {});

/// True if every coordinate of `mesh` is what a float32 writer gives: a
/// float32 value, or the double parsed from the shortest text of one (false
/// for an empty mesh). A mesh of exact doubles on a curved surface all but
/// never is.
bool float32_coordinates(const IndexedMesh& mesh);

/// How far (Å) the format `format` may have moved the positions of `mesh`
/// read from it: for STL whose coordinates are all float32 (binary STL always
/// is; float32_coordinates) twice PositionStorage{Float32Text}.max_error; 0
/// for an ASCII STL of doubles and for PLY, OFF, OBJ and VTK as skinmesh
/// writes them (exact). The verifier's vertex-distance tolerance must not be
/// below it.
double position_rounding(MeshFormat format, const IndexedMesh& mesh);

/// The bytes of one file as a writer makes them, handed to a sink in chunks of
/// about kChunkBytes, so that no writer holds a whole file: the PLY of a
/// 66 M-triangle mesh is 1.8 GB, beside the mesh it comes from. A writer
/// appends to buffer() and calls spill() after each record; whoever made the
/// ChunkedWriter calls flush() at the end. The bytes reach the sink in order,
/// the same bytes as one string would hold.
class ChunkedWriter {
 public:
  static constexpr std::size_t kChunkBytes = std::size_t{1} << 20;  // [chosen] few writes, little memory
  using Sink = std::function<void(std::string_view)>;
  explicit ChunkedWriter(Sink sink) : sink_(std::move(sink)) {}
  /// The bytes made and not yet handed on: append here.
  std::string& buffer() { return buffer_; }
  /// Hands the buffer on once it holds kChunkBytes or more.
  void spill() {
    if (buffer_.size() >= kChunkBytes) flush();
  }
  /// Hands on whatever the buffer holds.
  void flush() {
    if (!buffer_.empty()) sink_(buffer_);
    buffer_.clear();
  }
  /// Hands on the buffer, then `bytes` as they are (not copied).
  void write(std::string_view bytes) {
    flush();
    if (!bytes.empty()) sink_(bytes);
  }

 private:
  Sink sink_;
  std::string buffer_;
};

/// Makes the bytes of one file into a ChunkedWriter (through buffer() and
/// spill(); the caller flushes).
using FileProducer = std::function<void(ChunkedWriter& out)>;

/// Writes the bytes `produce` makes to a fresh temporary file beside `path`,
/// chunk by chunk, then renames it onto `path`, so that readers never see a
/// partial file and the whole file is never in memory. On any failure
/// (including an exception from `produce`, passed on) the temporary file is
/// removed; a failed write throws InputError(path, 0, "cannot write <what>
/// (reason)").
void write_file_atomically(const std::string& path, const FileProducer& produce, const std::string& what = "file");

/// write_files_atomically() below with producers: each file written chunk by
/// chunk.
void write_files_atomically(const std::vector<std::pair<std::string, FileProducer>>& files,
                            const std::string& what = "file");

/// Writes `bytes` to a fresh temporary file beside `path`, then renames it onto
/// `path`, so that readers never see a partial file. On any failure the
/// temporary file is removed and InputError(path, 0, "cannot write <what>
/// (reason)") is thrown.
void write_file_atomically(const std::string& path, const std::string& bytes, const std::string& what = "file");

/// Writes several files (path, bytes) as one: each to a temporary file beside
/// it first, then all renamed one right after the other, so that a failure while
/// writing leaves every earlier file as it was (never a new file of a set beside
/// an old one, as the two files of an MSMS mesh must not be). A folder in the
/// place of any of them is refused before anything is written. Throws
/// InputError(path, 0, "cannot write <what> (reason)").
void write_files_atomically(const std::vector<std::pair<std::string, std::string>>& files,
                            const std::string& what = "file");

}  // namespace skinmesh::geometry
