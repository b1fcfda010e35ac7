// geometry/io/mesh_io_vtk_xml.cpp: the XML VTK formats of mesh_io.h (Kitware,
// "VTK File Formats", the XML formats that ParaView, VTK and meshio read) —
// PolyData (.vtp) and UnstructuredGrid (.vtu) of triangles with ASCII data
// arrays: every per-vertex attribute a named array, which XML readers load by
// default (the legacy reader loads only the active scalars), and per-triangle
// smallest angle. The reader takes the ASCII files these writers and VTK
// (data mode ascii) and meshio (binary=False) write, and refuses binary or
// appended (and so compressed) arrays with a message that says how to save them. Declared in mesh_io_internal.h.
#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/errors.h"
#include "core/text_split.h"
#include "geometry/io/mesh_io_internal.h"
#include "geometry/kernel/angles.h"

namespace skinmesh::geometry::mesh_io_detail {

namespace {

constexpr int kVtkTriangle = 5;  ///< VTK_TRIANGLE, the cell type of .vtu triangles

/// `<DataArray ...>` of one component per value, values as append_number()
/// writes them, one line per tuple.
template <class Value>
void write_array(ChunkedWriter& w, const std::string& attributes, std::size_t tuples, int components,
                 const Value& value) {
  std::string& out = w.buffer();
  out += "        <DataArray " + attributes + " format=\"ascii\">\n";
  for (std::size_t i = 0; i < tuples; ++i) {
    out += "          ";
    for (int k = 0; k < components; ++k) {
      if (k > 0) out += ' ';
      value(out, i, k);
    }
    out += '\n';
    w.spill();
  }
  out += "        </DataArray>\n";
}

/// One XML tag of the file: its name, attributes, kind and where it ends.
struct Tag {
  std::string name;
  std::map<std::string, std::string> attributes;
  bool closing = false, self_closing = false;
  std::size_t end = 0;  ///< the position after '>'
  int line = 0;
};

/// The tags of an XML text, one after the other (declarations and comments
/// skipped), with their line numbers. Throws InputError for a tag that does
/// not end or an attribute without a quoted value.
class TagScanner {
 public:
  TagScanner(const std::string& path, std::string_view text) : path_(path), text_(text) {}

  /// The next tag from position `pos_` on; false at the end of the text.
  bool next(Tag& tag) {
    for (;;) {
      const std::size_t open = text_.find('<', pos_);
      if (open == std::string_view::npos) return false;
      advance_to(open);
      if (text_.substr(open, 4) == "<!--") {
        pos_ = end_of(open, "-->");
        continue;
      }
      if (text_.substr(open, 2) == "<?" || text_.substr(open, 2) == "<!") {
        pos_ = end_of(open, ">");
        continue;
      }
      tag = Tag{};
      tag.line = line_;
      std::size_t i = open + 1;
      if (i < text_.size() && text_[i] == '/') tag.closing = true, ++i;
      const std::size_t name_end = text_.find_first_of(" \t\r\n/>", i);
      if (name_end == std::string_view::npos) throw InputError(path_, line_, "an XML tag does not end");
      tag.name = std::string(text_.substr(i, name_end - i));
      i = name_end;
      for (;;) {
        i = text_.find_first_not_of(" \t\r\n", i);
        if (i == std::string_view::npos) throw InputError(path_, line_, "the XML tag <" + tag.name + "> does not end");
        if (text_[i] == '>') break;
        if (text_.compare(i, 2, "/>") == 0) {
          tag.self_closing = true;
          ++i;
          break;
        }
        const std::size_t eq = text_.find('=', i);
        if (eq == std::string_view::npos)
          throw InputError(path_, line_, "an attribute of <" + tag.name + "> has no value");
        const std::string key(trim(text_.substr(i, eq - i)));
        const std::size_t quote = text_.find_first_not_of(" \t\r\n", eq + 1);
        if (quote == std::string_view::npos || (text_[quote] != '"' && text_[quote] != '\''))
          throw InputError(path_, line_, "attribute " + key + " of <" + tag.name + "> has no quoted value");
        const std::size_t close = text_.find(text_[quote], quote + 1);
        if (close == std::string_view::npos)
          throw InputError(path_, line_, "attribute " + key + " of <" + tag.name + "> does not end");
        tag.attributes[key] = std::string(text_.substr(quote + 1, close - quote - 1));
        i = close + 1;
      }
      tag.end = i + 1;
      pos_ = tag.end;
      return true;
    }
  }

  /// The text from the end of the last tag to the next '<', and the line it starts on.
  std::string_view text_until_next_tag(int& line) {
    line = line_;
    const std::size_t open = text_.find('<', pos_);
    return text_.substr(pos_, (open == std::string_view::npos ? text_.size() : open) - pos_);
  }

 private:
  void advance_to(std::size_t p) {
    line_ += static_cast<int>(std::count(text_.begin() + static_cast<std::ptrdiff_t>(counted_),
                                         text_.begin() + static_cast<std::ptrdiff_t>(p), '\n'));
    counted_ = p;
  }
  std::size_t end_of(std::size_t from, std::string_view end) {
    const std::size_t at = text_.find(end, from);
    if (at == std::string_view::npos) throw InputError(path_, line_, "an XML comment or declaration does not end");
    return at + end.size();
  }
  const std::string& path_;
  std::string_view text_;
  std::size_t pos_ = 0, counted_ = 0;
  int line_ = 1;
};

/// The attribute `key` of `tag`, or `fallback`.
std::string attribute(const Tag& tag, const std::string& key, const std::string& fallback = "") {
  const auto it = tag.attributes.find(key);
  return it == tag.attributes.end() ? fallback : it->second;
}

/// A count attribute of `tag` (a non-negative integer), 0 if absent.
std::size_t count_attribute(const std::string& path, const Tag& tag, const std::string& key) {
  const std::string v = attribute(tag, key, "0");
  const std::int64_t n = int_or_throw(path, tag.line, v, key.c_str());
  if (n < 0) throw InputError(path, tag.line, key + " is negative");
  return static_cast<std::size_t>(n);
}

/// The numbers of an ASCII DataArray's text, with the line of each.
std::vector<double> array_numbers(const std::string& path, std::string_view text, int line, const std::string& name) {
  std::vector<double> values;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line, ++i;
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\r') {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < text.size() && text[j] != ' ' && text[j] != '\t' && text[j] != '\r' && text[j] != '\n') ++j;
    values.push_back(number_or_throw(path, line, text.substr(i, j - i), ("a value of DataArray " + name).c_str()));
    i = j;
  }
  return values;
}

bool integer_type(const std::string& type) { return type.find("Int") != std::string::npos; }

}  // namespace

void write_vtk_xml(const IndexedMesh& m, const std::vector<VertexAttribute>& attributes, const MeshWriteOptions& opt,
                   bool unstructured, ChunkedWriter& w) {
  const bool dp = opt.double_precision;
  const std::string real = dp ? "Float64" : "Float32";
  const std::string n_points = std::to_string(m.positions.size()), n_cells = std::to_string(m.triangles.size());
  std::string& out = w.buffer();
  out += "<?xml version=\"1.0\"?>\n<!-- skinmesh: a triangulated skin surface -->\n";
  out += std::string("<VTKFile type=\"") + (unstructured ? "UnstructuredGrid" : "PolyData") +
         "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  out +=
      unstructured
          ? "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"" + n_points + "\" NumberOfCells=\"" + n_cells + "\">\n"
          : "  <PolyData>\n    <Piece NumberOfPoints=\"" + n_points +
                "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"" + n_cells + "\">\n";
  if (!m.normals.empty() || !attributes.empty()) {
    out += m.normals.empty() ? "      <PointData>\n" : "      <PointData Normals=\"normals\">\n";
    if (!m.normals.empty())
      write_array(w, "type=\"" + real + "\" Name=\"normals\" NumberOfComponents=\"3\"", m.normals.size(), 3,
                  [&](std::string& o, std::size_t i, int k) { append_number(o, m.normals[i][k], dp); });
    for (const VertexAttribute& a : attributes)
      write_array(w, "type=\"" + (a.integer ? std::string("Int32") : real) + "\" Name=\"" + a.name + "\"",
                  a.values.size(), 1, [&](std::string& o, std::size_t i, int) {
                    if (a.integer)
                      o += std::to_string(static_cast<std::int32_t>(a.values[i]));
                    else
                      append_number(o, a.values[i], dp);
                  });
    out += "      </PointData>\n";
  }
  if (!m.triangles.empty()) {
    out += "      <CellData>\n";
    write_array(w, "type=\"Float64\" Name=\"min_angle\"", m.triangles.size(), 1,
                [&](std::string& o, std::size_t i, int) {
                  const auto& t = m.triangles[i];
                  append_number(o, min_angle(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]) * 180 / kPi, dp);
                });
    out += "      </CellData>\n";
  }
  out += "      <Points>\n";
  write_array(w, "type=\"" + real + "\" Name=\"Points\" NumberOfComponents=\"3\"", m.positions.size(), 3,
              [&](std::string& o, std::size_t i, int k) { append_number(o, m.positions[i][k], dp); });
  out += unstructured ? "      </Points>\n      <Cells>\n" : "      </Points>\n      <Polys>\n";
  write_array(w, "type=\"Int64\" Name=\"connectivity\"", m.triangles.size(), 3,
              [&](std::string& o, std::size_t i, int k) { append_index(o, m.triangles[i][k]); });
  write_array(w, "type=\"Int64\" Name=\"offsets\"", m.triangles.size(), 1,
              [&](std::string& o, std::size_t i, int) { append_index(o, 3 * (i + 1)); });
  if (unstructured)
    write_array(w, "type=\"UInt8\" Name=\"types\"", m.triangles.size(), 1,
                [&](std::string& o, std::size_t, int) { o += std::to_string(kVtkTriangle); });
  out += unstructured ? "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n"
                      : "      </Polys>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
}

IndexedMesh read_vtk_xml(const std::string& path, const std::string& data, std::vector<VertexAttribute>& attributes) {
  TagScanner scan(path, data);
  Tag tag;
  if (!scan.next(tag) || tag.name != "VTKFile")
    throw InputError(path, tag.line,
                     "not an XML VTK file (expected <VTKFile type=\"PolyData\"> or \"UnstructuredGrid\")");
  const std::string type = attribute(tag, "type");
  if (type != "PolyData" && type != "UnstructuredGrid")
    throw InputError(path, tag.line,
                     "VTK XML type '" + type + "' is not supported (only PolyData and UnstructuredGrid)");
  const bool unstructured = type == "UnstructuredGrid";
  // A compressor applies to binary arrays only: VTK names one in ASCII files too.

  IndexedMesh mesh;
  std::size_t n_points = 0, n_cells = 0, pieces = 0;
  bool have_points = false, in_piece = false;
  std::vector<double> connectivity, offsets, types;
  std::string section, normals_name = "normals";  // the innermost section of the piece
  while (scan.next(tag)) {
    if (tag.name == "Piece") {
      in_piece = !tag.closing && !tag.self_closing;
      if (tag.closing) continue;
      if (++pieces > 1) throw InputError(path, tag.line, "several pieces are not supported (merge them first)");
      n_points = count_attribute(path, tag, "NumberOfPoints");
      n_cells = count_attribute(path, tag, unstructured ? "NumberOfCells" : "NumberOfPolys");
      if (!unstructured && (count_attribute(path, tag, "NumberOfStrips") > 0))
        throw InputError(path, tag.line, "triangle strips are not supported");
      continue;
    }
    if (tag.name == "Points" || tag.name == "PointData" || tag.name == "CellData" || tag.name == "Polys" ||
        tag.name == "Cells" || tag.name == "Verts" || tag.name == "Lines" || tag.name == "Strips") {
      section = tag.closing || tag.self_closing ? std::string() : tag.name;
      if (tag.name == "PointData" && !tag.closing) normals_name = attribute(tag, "Normals", "normals");
      continue;
    }
    if (tag.name != "DataArray" || tag.closing) continue;
    const std::string name = attribute(tag, "Name");
    const std::string format = attribute(tag, "format", "ascii");
    if (format != "ascii")
      throw InputError(path, tag.line,
                       "DataArray '" + name + "' is " + format +
                           ": only ASCII data arrays are read (VTK writers: SetDataModeToAscii(); meshio: "
                           "binary=False; ParaView: Data Mode Ascii)");
    // An array outside a Piece is the dataset's FieldData (VTK writes TimeValue
    // there), never per point or per cell: the counts it would be checked against
    // are the Piece's.
    if (tag.self_closing || !in_piece) continue;
    int line = 0;
    const std::vector<double> values = array_numbers(path, scan.text_until_next_tag(line), line, name);
    const std::int64_t components =
        int_or_throw(path, tag.line, attribute(tag, "NumberOfComponents", "1"), "NumberOfComponents");
    if (section == "Points") {
      if (components != 3 || values.size() != 3 * n_points)
        throw InputError(path, tag.line,
                         "Points: " + std::to_string(values.size()) + " values for " + std::to_string(n_points) +
                             " points of 3 components");
      mesh.positions.resize(n_points);
      for (std::size_t i = 0; i < n_points; ++i)
        mesh.positions[i] = Vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
      have_points = true;
    } else if (section == (unstructured ? "Cells" : "Polys")) {
      if (name == "connectivity")
        connectivity = values;
      else if (name == "offsets")
        offsets = values;
      else if (name == "types")
        types = values;
    } else if (section == "PointData") {
      if (values.size() != n_points * static_cast<std::size_t>(std::max<std::int64_t>(components, 1)))
        throw InputError(path, tag.line,
                         "DataArray '" + name + "': " + std::to_string(values.size()) + " values for " +
                             std::to_string(n_points) + " points");
      if (components == 3 && name == normals_name) {
        mesh.normals.resize(n_points);
        for (std::size_t i = 0; i < n_points; ++i)
          mesh.normals[i] = Vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
      } else if (components == 1) {
        const bool integer = integer_type(attribute(tag, "type"));
        for (std::size_t i = 0; i < values.size(); ++i)
          if (integer && (values[i] != std::floor(values[i]) || std::fabs(values[i]) > 2147483647.0))
            throw InputError(path, tag.line, "non-integer or out-of-range value in DataArray " + name);
        std::erase_if(attributes, [&](const VertexAttribute& a) { return a.name == name; });
        attributes.push_back({name, integer, values});
      }
    } else if (section == "Verts" || section == "Lines") {
      // Points and segments: not part of a triangle mesh, skipped.
    }
  }
  if (!have_points) throw InputError(path, 0, "no Points data array");
  // Triangles: every cell three corners (offsets 3, 6, 9, ...), of type triangle in a .vtu.
  if (offsets.size() != n_cells || connectivity.size() != 3 * n_cells)
    throw InputError(path, 0,
                     std::to_string(n_cells) + " cells, but " + std::to_string(offsets.size()) + " offsets and " +
                         std::to_string(connectivity.size()) + " corner indices (only triangles are accepted)");
  if (unstructured && types.size() != n_cells)
    throw InputError(path, 0, std::to_string(types.size()) + " cell types for " + std::to_string(n_cells) + " cells");
  mesh.triangles.resize(n_cells);
  for (std::size_t i = 0; i < n_cells; ++i) {
    if (offsets[i] != 3.0 * static_cast<double>(i + 1) || (unstructured && types[i] != kVtkTriangle))
      throw InputError(path, 0, "cell " + std::to_string(i) + " is not a triangle; only triangles are accepted");
    for (int k = 0; k < 3; ++k) {
      const double v = connectivity[3 * i + static_cast<std::size_t>(k)];
      if (!(v >= 0 && v < static_cast<double>(n_points)) || v != std::floor(v))
        throw InputError(path, 0,
                         "cell " + std::to_string(i) + ": vertex index " + std::to_string(v) + " out of range (" +
                             std::to_string(n_points) + " points)");
      mesh.triangles[i][static_cast<std::size_t>(k)] = static_cast<Index>(v);
    }
  }
  return mesh;
}

}  // namespace skinmesh::geometry::mesh_io_detail
