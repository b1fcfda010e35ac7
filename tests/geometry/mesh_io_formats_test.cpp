// tests/geometry/mesh_io_formats_test.cpp: the formats of the field's pipelines
// — binary and ascii STL, legacy VTK with attributes, MSMS .vert/.face —
// written and read back (exact for VTK, float32 for STL, 1e-3 Å for MSMS),
// hand-written files of each, and the errors of broken ones.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "geometry/io/mesh_io.h"
#include "tests/geometry/mesh_file_fixture.h"

namespace {

using skinmesh::Index;
using skinmesh::InputError;
using skinmesh::Vec3;
using skinmesh::geometry::IndexedMesh;
using skinmesh::geometry::MeshFormat;
using skinmesh::geometry::read_mesh;
using skinmesh::geometry::read_mesh_from_bytes;
using skinmesh::geometry::write_mesh;

namespace fs = std::filesystem;
using skinmesh::geometry::VertexAttribute;
using skinmesh::test::Scratch;
using skinmesh::test::slurp;
using skinmesh::test::sphere_mesh;

/// The attributes of sphere_mesh() the VTK test writes: an integer one and a real one.
std::vector<VertexAttribute> sphere_attributes(const IndexedMesh& m) {
  VertexAttribute atom{"atom", true, {}}, rho{"rho", false, {}};
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    atom.values.push_back(double(v % 17));
    rho.values.push_back(0.5 + 0.01 * double(v));
  }
  return {atom, rho};
}

/// The triangles as sets of corner positions (each rounded by `round`), for
/// formats that renumber vertices.
template <class Round>
std::multiset<std::array<std::array<double, 3>, 3>> corner_sets(const IndexedMesh& m, Round round) {
  std::multiset<std::array<std::array<double, 3>, 3>> out;
  for (const auto& t : m.triangles) {
    std::array<std::array<double, 3>, 3> c;
    for (int k = 0; k < 3; ++k)
      c[k] = {round(m.positions[t[k]].x()), round(m.positions[t[k]].y()), round(m.positions[t[k]].z())};
    // the same rotation for the same triangle: smallest corner first
    int first = 0;
    for (int k = 1; k < 3; ++k)
      if (c[k] < c[first]) first = k;
    out.insert({c[first], c[(first + 1) % 3], c[(first + 2) % 3]});
  }
  return out;
}

double as_float(double x) { return static_cast<double>(static_cast<float>(x)); }

std::string error_of(const std::string& path) {
  try {
    read_mesh(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

/// Writes `m` with `attributes` to `path` and checks that reading it back gives
/// the same positions, triangles, normals and attributes, bit for bit.
void check_exact_round_trip(const std::string& path, const IndexedMesh& m,
                            const std::vector<VertexAttribute>& attributes) {
  write_mesh(path, m, {}, attributes);
  std::vector<VertexAttribute> read;
  const IndexedMesh r = read_mesh(path, &read);
  CHECK(r.positions == m.positions);
  CHECK(r.triangles == m.triangles);
  CHECK(r.normals == m.normals);
  REQUIRE(read.size() == attributes.size());
  for (std::size_t k = 0; k < attributes.size(); ++k) {
    CHECK(read[k].name == attributes[k].name);
    CHECK(read[k].integer == attributes[k].integer);
    CHECK(read[k].values == attributes[k].values);
  }
}

}  // namespace

TEST_SUITE("geometry") {

TEST_CASE("formats: the extension chooses the format; the molecular MSMS is not a geometric format") {
  CHECK(skinmesh::geometry::mesh_format_from_extension("a.STL") == MeshFormat::Stl);
  CHECK(skinmesh::geometry::mesh_format_from_extension("a.vtk") == MeshFormat::Vtk);
  CHECK_FALSE(skinmesh::geometry::mesh_format_of("a.vert"));
  CHECK_THROWS_AS(skinmesh::geometry::mesh_format_from_extension("a.stp"), InputError);
}

TEST_CASE("formats: binary STL round trip — float32 corners, shared vertices merged, facet normals outward") {
  Scratch s("skinmesh_formats_test_");
  const IndexedMesh m = sphere_mesh();
  write_mesh(s.path("m.stl"), m);
  const std::string bytes = slurp(s.path("m.stl"));
  REQUIRE(bytes.size() == 84 + 50 * m.triangles.size());
  const IndexedMesh r = read_mesh(s.path("m.stl"));
  CHECK(r.positions.size() == m.positions.size());  // every shared corner merged back
  CHECK(r.triangles.size() == m.triangles.size());
  CHECK(r.normals.empty());
  CHECK(corner_sets(r, as_float) == corner_sets(m, as_float));
  // The facet normal of the first record points away from the centre.
  float n[3], a[3];
  std::memcpy(n, bytes.data() + 84, 12);
  std::memcpy(a, bytes.data() + 96, 12);
  const Vec3 centre(31.25, -7.5, 1.0 / 3.0);
  CHECK(Vec3(n[0], n[1], n[2]).dot(Vec3(a[0], a[1], a[2]) - centre) > 0);
  CHECK(Vec3(n[0], n[1], n[2]).norm() == doctest::Approx(1).epsilon(1e-6));
}

TEST_CASE("formats: ascii STL, and a binary STL whose header begins with 'solid'") {
  Scratch s("skinmesh_formats_test_");
  const std::string ascii =
      "solid tetra\n"
      " facet normal 0 0 -1\n  outer loop\n   vertex 0 0 0\n   vertex 0 1 0\n   vertex 1 0 0\n  endloop\n endfacet\n"
      " facet normal 0 -1 0\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 0 1\n  endloop\n endfacet\n"
      " facet normal -1 0 0\n  outer loop\n   vertex 0 0 0\n   vertex 0 0 1\n   vertex 0 1 0\n  endloop\n endfacet\n"
      " facet normal 1 1 1\n  outer loop\n   vertex 1 0 0\n   vertex 0 1 0\n   vertex 0 0 1\n  endloop\n endfacet\n"
      "endsolid tetra\n";
  const IndexedMesh r = read_mesh(s.write("t.stl", ascii));
  CHECK(r.positions.size() == 4);
  CHECK(r.triangles.size() == 4);
  // A binary file whose 80-byte header starts with "solid": told apart by its size.
  IndexedMesh one;
  one.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  one.triangles = {{0, 1, 2}};
  write_mesh(s.path("one.stl"), one);
  std::string bytes = slurp(s.path("one.stl"));
  bytes.replace(0, 5, "solid");
  const IndexedMesh b = read_mesh(s.write("solid_binary.stl", bytes));
  CHECK(b.triangles.size() == 1);
  CHECK(b.positions.size() == 3);
}

TEST_CASE("formats: broken STL files name the file and the problem") {
  Scratch s("skinmesh_formats_test_");
  CHECK(error_of(s.write("short.stl", "abc")).find("not an STL file") != std::string::npos);
  std::string bytes(84, '\0');
  bytes[80] = 2;  // claims 2 triangles, holds none
  CHECK(error_of(s.write("trunc.stl", bytes)).find("announces 2 triangles") != std::string::npos);
  const std::string quad =
      "solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\n"
      "vertex 0 1 0\nendloop\nendfacet\nendsolid q\n";
  const std::string e = error_of(s.write("quad.stl", quad));
  CHECK(e.find("quad.stl:7") != std::string::npos);
  CHECK(e.find("only triangles") != std::string::npos);
  CHECK(error_of(s.write("open.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n")).find("end of file") !=
        std::string::npos);
  CHECK(error_of(s.write("nan.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 nan 0\n"))
            .find("non-numeric or non-finite") != std::string::npos);
}

TEST_CASE("formats: VTK round trip is exact, with normals, attributes and the min angle per triangle") {
  Scratch s("skinmesh_formats_test_");
  const IndexedMesh m = sphere_mesh();
  const std::vector<VertexAttribute> attributes = sphere_attributes(m);
  check_exact_round_trip(s.path("m.vtk"), m, attributes);
  const std::string text = slurp(s.path("m.vtk"));
  CHECK(text.rfind("# vtk DataFile Version 3.0\n", 0) == 0);
  CHECK(text.find("DATASET POLYDATA\nPOINTS 66 double\n") != std::string::npos);
  CHECK(text.find("POLYGONS 128 512\n") != std::string::npos);
  CHECK(text.find("POINT_DATA 66\nNORMALS normals double\n") != std::string::npos);
  CHECK(text.find("SCALARS atom int 1\nLOOKUP_TABLE default\n") != std::string::npos);
  CHECK(text.find("SCALARS rho double 1\nLOOKUP_TABLE default\n") != std::string::npos);
  // The min angle of the first triangle, recomputed here.
  const std::size_t at = text.find("SCALARS min_angle double 1\nLOOKUP_TABLE default\n");
  REQUIRE(at != std::string::npos);
  const double written = std::stod(text.substr(at + 48));
  const auto& t = m.triangles[0];
  double smallest = 180;
  for (int k = 0; k < 3; ++k) {
    const Vec3 u = m.positions[t[(k + 1) % 3]] - m.positions[t[k]], v = m.positions[t[(k + 2) % 3]] - m.positions[t[k]];
    smallest = std::min(smallest, std::acos(u.normalized().dot(v.normalized())) * 180 / M_PI);
  }
  CHECK(written == doctest::Approx(smallest).epsilon(1e-12));
}

TEST_CASE("formats: a hand-written VTK file with cells and attributes this reader skips") {
  Scratch s("skinmesh_formats_test_");
  const std::string text =
      "# vtk DataFile Version 2.0\nhand written\nascii\nDATASET POLYDATA\n"
      "POINTS 4 float\n0 0 0  1 0 0\n0 1 0  0 0 1\n"
      "VERTICES 1 2\n1 0\n"
      "POLYGONS 4 16\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"
      "POINT_DATA 4\nSCALARS temperature float\nLOOKUP_TABLE default\n1 2 3 4\n"
      "SCALARS atom int 1\nLOOKUP_TABLE default\n5 6 7 8\n"
      "CELL_DATA 4\nSCALARS quality float 1\nLOOKUP_TABLE default\n1 1 1 1\n";
  std::vector<VertexAttribute> read;
  const IndexedMesh r = read_mesh(s.write("hand.vtk", text), &read);
  CHECK(r.positions.size() == 4);
  CHECK(r.triangles.size() == 4);
  REQUIRE(read.size() == 2);  // the point data's scalars, not the cells'
  CHECK(read[0].name == "temperature");
  CHECK_FALSE(read[0].integer);
  CHECK(read[0].values == std::vector<double>{1, 2, 3, 4});
  CHECK(read[1].name == "atom");
  CHECK(read[1].integer);
  CHECK(read[1].values == std::vector<double>{5, 6, 7, 8});
  CHECK(r.normals.empty());
}

TEST_CASE("formats: broken VTK files name the file, the line and the problem") {
  Scratch s("skinmesh_formats_test_");
  CHECK(error_of(s.write("a.vtk", "hello\n")).find("not a legacy VTK file") != std::string::npos);
  CHECK(error_of(s.write("b.vtk", "# vtk DataFile Version 3.0\nx\nBINARY\n")).find("b.vtk:3") != std::string::npos);
  CHECK(error_of(s.write("c.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\n"))
            .find("not supported") != std::string::npos);
  const std::string quad =
      "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 4 double\n0 0 0 1 0 0 1 1 0 0 1 0\n"
      "POLYGONS 1 5\n4 0 1 2 3\n";
  const std::string e = error_of(s.write("d.vtk", quad));
  CHECK(e.find("d.vtk:8") != std::string::npos);
  CHECK(e.find("only triangles") != std::string::npos);
  CHECK(error_of(s.write("e.vtk",
                         "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 4000000000 double\n0 0 0\n"))
            .find("exceeds what the file holds") != std::string::npos);
  CHECK(
      error_of(s.write("c4.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 1 double\n"))
          .find("c4.vtk:4:") != std::string::npos);  // the line of the dataset type, not the next one
  // A second POINTS section would leave triangles and attributes of the first.
  const std::string twice =
      "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 4 double\n0 0 0 1 0 0 0 1 0 0 0 1\n"
      "POLYGONS 1 4\n3 1 2 3\nPOINTS 1 double\n0 0 0\n";
  CHECK(error_of(s.write("twice.vtk", twice)).find("twice.vtk:9: a second POINTS section") != std::string::npos);
  CHECK(error_of(s.write("f.vtk",
                         "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 1 double\n0 0 0\n"
                         "POLYGONS 1 4\n3 0 0 7\n"))
            .find("out of range") != std::string::npos);
}

TEST_CASE("formats: XML VTK (.vtp, .vtu) round trips are exact, float32 ones float; every array named") {
  Scratch s("skinmesh_formats_test_");
  const IndexedMesh m = sphere_mesh();
  const std::vector<VertexAttribute> attributes = sphere_attributes(m);
  for (const char* name : {"m.vtp", "m.vtu"}) {
    CAPTURE(name);
    check_exact_round_trip(s.path(name), m, attributes);
    const std::string text = slurp(s.path(name));
    const bool vtu = std::string(name) == "m.vtu";
    CHECK(text.find(vtu ? "<Piece NumberOfPoints=\"66\" NumberOfCells=\"128\">" : "NumberOfPolys=\"128\"") !=
          std::string::npos);
    CHECK(text.find("<PointData Normals=\"normals\">") != std::string::npos);
    CHECK(text.find("Name=\"atom\" format=\"ascii\"") != std::string::npos);
    CHECK(text.find("type=\"Float64\" Name=\"min_angle\"") != std::string::npos);
    CHECK((text.find("Name=\"types\"") != std::string::npos) == vtu);
    // float32: the positions are floats, read back as the doubles of their text.
    skinmesh::geometry::MeshWriteOptions f;
    f.double_precision = false;
    write_mesh(s.path(std::string("f") + name), m, f);
    const IndexedMesh rf = read_mesh(s.path(std::string("f") + name));
    REQUIRE(rf.positions.size() == m.positions.size());
    for (std::size_t v = 0; v < m.positions.size(); ++v)
      for (int k = 0; k < 3; ++k)
        CHECK(static_cast<float>(rf.positions[v][k]) == static_cast<float>(m.positions[v][k]));
    CHECK(slurp(s.path(std::string("f") + name)).find("type=\"Float32\" Name=\"Points\"") != std::string::npos);
  }
}

TEST_CASE("formats: XML VTK as VTK writes it in ASCII (ranges, information keys, a compressor named) reads") {
  Scratch s("skinmesh_formats_test_");
  std::vector<VertexAttribute> read;
  const IndexedMesh r = read_mesh(std::string(SKINMESH_TEST_DATA) + "/readers/tetra_vtk_style.vtu", &read);
  CHECK(r.positions.size() == 4);
  CHECK(r.positions[3] == Vec3(0, 0, 1));
  CHECK(r.triangles.size() == 4);
  CHECK(r.triangles[1] == std::array<skinmesh::Index, 3>{0, 1, 3});
  REQUIRE(read.size() == 1);
  CHECK(read[0].name == "atom");
  CHECK(read[0].integer);
  CHECK(read[0].values == std::vector<double>{0, 1, 2, 3});
  CHECK(r.normals.empty());
}

TEST_CASE("formats: XML VTK arrays outside the Piece are field data, never sized against its counts") {
  // Found by fuzz_mesh_invariants: PointData before the Piece was read against
  // 0 points, an attribute of no values beside 4 points; Points before it gave
  // triangles indexing positions that were never read.
  Scratch s("skinmesh_formats_test_");
  const std::string head = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\">\n<PolyData>\n";
  const std::string field =
      "<FieldData><DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">2.5"
      "</DataArray></FieldData>\n";
  const std::string early_data = "<PointData><DataArray Name=\"rho\" format=\"ascii\"></DataArray></PointData>\n";
  const std::string points =
      "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 1 1 0 0 1 0"
      "</DataArray></Points>\n";
  const std::string piece = "<Piece NumberOfPoints=\"4\" NumberOfPolys=\"1\">\n";
  const std::string polys =
      "<Polys><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 2</DataArray>"
      "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">3</DataArray></Polys>\n";
  const std::string tail = "</Piece>\n</PolyData>\n</VTKFile>\n";
  std::vector<VertexAttribute> read;
  const IndexedMesh r =
      read_mesh(s.write("field.vtp", head + field + early_data + piece + points + polys + tail), &read);
  CHECK(r.positions.size() == 4);
  CHECK(r.triangles.size() == 1);
  CHECK(read.empty());
  CHECK(error_of(s.write("early.vtp", head + points + piece + polys + tail)).find("no Points data array") !=
        std::string::npos);
}

TEST_CASE("formats: XML VTK that is not ASCII triangles is refused, naming the file, the line and the fix") {
  Scratch s("skinmesh_formats_test_");
  const std::string head =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\">\n<PolyData>\n"
      "<Piece NumberOfPoints=\"4\" NumberOfPolys=\"1\">\n";
  const std::string points =
      "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 1 1 0 0 1 0"
      "</DataArray></Points>\n";
  const std::string tail = "</Piece>\n</PolyData>\n</VTKFile>\n";
  const auto polys = [](const std::string& connectivity, const std::string& offsets) {
    return "<Polys><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">" + connectivity +
           "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">" + offsets +
           "</DataArray></Polys>\n";
  };
  CHECK(read_mesh(s.write("ok.vtp", head + points + polys("0 1 2", "3") + tail)).triangles.size() == 1);
  CHECK(error_of(s.write("quad.vtp", head + points + polys("0 1 2 3", "4") + tail)).find("only triangles") !=
        std::string::npos);
  CHECK(error_of(s.write("range.vtp", head + points + polys("0 1 9", "3") + tail)).find("out of range") !=
        std::string::npos);
  std::string binary = head + points + polys("0 1 2", "3") + tail;
  binary.replace(binary.find("format=\"ascii\""), 14, "format=\"binary\"");
  const std::string e = error_of(s.write("binary.vtp", binary));
  CHECK(e.find("binary.vtp:5:") != std::string::npos);
  CHECK(e.find("only ASCII data arrays are read") != std::string::npos);
  CHECK(e.find("SetDataModeToAscii") != std::string::npos);
  CHECK(error_of(s.write("image.vti", "x")).find("unknown mesh format") != std::string::npos);
  CHECK(error_of(s.write("image.vtp", "<VTKFile type=\"ImageData\">")).find("not supported") != std::string::npos);
  CHECK(error_of(s.write("text.vtp", "hello")).find("not an XML VTK file") != std::string::npos);
  CHECK(error_of(s.write("two.vtp", head + points + polys("0 1 2", "3") + "</Piece><Piece>" + tail))
            .find("several pieces") != std::string::npos);
  std::string vtu = head + points +
                    "<Cells><DataArray Name=\"connectivity\" format=\"ascii\">0 1 2</DataArray>"
                    "<DataArray Name=\"offsets\" format=\"ascii\">3</DataArray>"
                    "<DataArray Name=\"types\" format=\"ascii\">9</DataArray></Cells>\n" +
                    tail;
  vtu.replace(vtu.find("PolyData"), 8, "UnstructuredGrid");
  vtu.replace(vtu.find("<PolyData>"), 10, "<UnstructuredGrid>");
  vtu.replace(vtu.find("NumberOfPolys"), 13, "NumberOfCells");
  CHECK(error_of(s.write("quad.vtu", vtu)).find("not a triangle") != std::string::npos);
}

}  // TEST_SUITE
