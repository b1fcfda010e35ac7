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

struct Scratch {
  fs::path dir;
  Scratch() {
    dir = fs::temp_directory_path() / ("skinmesh_formats_test_" + std::to_string(std::random_device{}()));
    fs::create_directories(dir);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::string path(const std::string& name) const { return (dir / name).string(); }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(path(name), std::ios::binary) << bytes;
    return path(name);
  }
};

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

/// A closed mesh (a subdivided, jittered octahedron: 66 vertices, 128
/// triangles) with every per-vertex attribute set.
IndexedMesh sphere_mesh() {
  IndexedMesh m;
  std::map<std::pair<Index, Index>, Index> mid;
  m.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int round = 0; round < 2; ++round) {
    std::vector<std::array<Index, 3>> next;
    auto middle = [&](Index a, Index b) {
      const auto key = std::minmax(a, b);
      auto [it, inserted] = mid.try_emplace(key, Index(m.positions.size()));
      if (inserted) m.positions.push_back((m.positions[a] + m.positions[b]).normalized());
      return it->second;
    };
    for (const auto& t : m.triangles) {
      const Index ab = middle(t[0], t[1]), bc = middle(t[1], t[2]), ca = middle(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({ab, t[1], bc});
      next.push_back({ca, bc, t[2]});
      next.push_back({ab, bc, ca});
    }
    m.triangles = next;
  }
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jitter(-1e-4, 1e-4);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    Vec3& p = m.positions[v];
    p = 12.3456789 * p + Vec3(31.25 + jitter(rng), -7.5 + jitter(rng), 1.0 / 3.0);
    m.normals.push_back((p - Vec3(31.25, -7.5, 1.0 / 3.0)).normalized());
    m.atom.push_back(static_cast<std::int32_t>(v % 17));
    m.rho.push_back(0.5 + 0.01 * double(v));
    m.patch.push_back(static_cast<std::uint8_t>(v % 4));
  }
  return m;
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

}  // namespace

TEST_SUITE("geometry") {

TEST_CASE("formats: the extension chooses the format; MSMS is a pair of files") {
  CHECK(skinmesh::geometry::mesh_format_from_extension("a.STL") == MeshFormat::Stl);
  CHECK(skinmesh::geometry::mesh_format_from_extension("a.vtk") == MeshFormat::Vtk);
  CHECK(skinmesh::geometry::mesh_format_from_extension("a.vert") == MeshFormat::Msms);
  CHECK(skinmesh::geometry::mesh_format_from_extension("a.face") == MeshFormat::Msms);
  CHECK_THROWS_AS(skinmesh::geometry::mesh_format_from_extension("a.stp"), InputError);
  const auto [vert, face] = skinmesh::geometry::msms_paths("dir/x.y.face");
  CHECK(vert == "dir/x.y.vert");
  CHECK(face == "dir/x.y.face");
}

TEST_CASE("formats: binary STL round trip — float32 corners, shared vertices merged, facet normals outward") {
  Scratch s;
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
  Scratch s;
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
  Scratch s;
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

TEST_CASE("formats: VTK round trip is exact, with normals, atom, rho and the min angle per triangle") {
  Scratch s;
  const IndexedMesh m = sphere_mesh();
  write_mesh(s.path("m.vtk"), m);
  const IndexedMesh r = read_mesh(s.path("m.vtk"));
  CHECK(r.positions == m.positions);
  CHECK(r.triangles == m.triangles);
  CHECK(r.normals == m.normals);
  CHECK(r.atom == m.atom);
  CHECK(r.rho == m.rho);
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
  Scratch s;
  const std::string text =
      "# vtk DataFile Version 2.0\nhand written\nascii\nDATASET POLYDATA\n"
      "POINTS 4 float\n0 0 0  1 0 0\n0 1 0  0 0 1\n"
      "VERTICES 1 2\n1 0\n"
      "POLYGONS 4 16\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"
      "POINT_DATA 4\nSCALARS temperature float\nLOOKUP_TABLE default\n1 2 3 4\n"
      "SCALARS atom int 1\nLOOKUP_TABLE default\n5 6 7 8\n"
      "CELL_DATA 4\nSCALARS quality float 1\nLOOKUP_TABLE default\n1 1 1 1\n";
  const IndexedMesh r = read_mesh(s.write("hand.vtk", text));
  CHECK(r.positions.size() == 4);
  CHECK(r.triangles.size() == 4);
  CHECK(r.atom == std::vector<std::int32_t>{5, 6, 7, 8});
  CHECK(r.normals.empty());
}

TEST_CASE("formats: broken VTK files name the file, the line and the problem") {
  Scratch s;
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

TEST_CASE("formats: MSMS round trip — positions and normals to 1e-3, the 1-based atom, types and components") {
  Scratch s;
  IndexedMesh m = sphere_mesh();
  // A second component, shifted: its vertices get component 2.
  const std::size_t n = m.positions.size(), nt = m.triangles.size();
  for (std::size_t v = 0; v < n; ++v) {
    m.positions.push_back(m.positions[v] + Vec3(100, 0, 0));
    m.normals.push_back(m.normals[v]);
    m.atom.push_back(m.atom[v] + 17);
    m.rho.push_back(m.rho[v]);
    m.patch.push_back(0);
  }
  for (std::size_t t = 0; t < nt; ++t)
    m.triangles.push_back({Index(m.triangles[t][0] + n), Index(m.triangles[t][1] + n), Index(m.triangles[t][2] + n)});
  write_mesh(s.path("m.vert"), m);
  REQUIRE(fs::exists(s.path("m.face")));
  for (const char* name : {"m.vert", "m.face"}) {
    CAPTURE(name);
    const IndexedMesh r = read_mesh(s.path(name));
    REQUIRE(r.positions.size() == m.positions.size());
    CHECK(r.triangles == m.triangles);
    CHECK(r.atom == m.atom);
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
      CHECK((r.positions[v] - m.positions[v]).cwiseAbs().maxCoeff() <= 5.0001e-4);
      CHECK((r.normals[v] - m.normals[v]).cwiseAbs().maxCoeff() <= 5.0001e-4);
    }
  }
  // The layout MSMS writes: three header lines, fixed-width records.
  std::istringstream vert(slurp(s.path("m.vert")));
  std::string l1, l2, l3, first;
  std::getline(vert, l1), std::getline(vert, l2), std::getline(vert, l3), std::getline(vert, first);
  CHECK(l1.rfind("# MSMS", 0) == 0);
  CHECK(l2 == "#vertex #sphere density probe_r");
  CHECK(std::stoul(l3) == m.positions.size());
  CHECK(first.size() == 6 * 9 + 5 + (1 + 7) + (1 + 7) + (1 + 2));  // "%9.3f" ×6, two " %7d", " %2d"
  std::istringstream fields(first);
  double x[6];
  int component = 0, atom = 0, type = 0;
  for (double& v : x) fields >> v;
  fields >> component >> atom >> type;
  CHECK(component == 1);
  CHECK(atom == m.atom[0] + 1);
  CHECK(type == 3);  // patch 0: an atom's sphere patch is MSMS "contact"
  const std::string face = slurp(s.path("m.face"));
  CHECK(face.find("\n#faces  #sphere density probe_r\n") != std::string::npos);
  const std::size_t last_line = face.rfind('\n', face.size() - 2);
  std::istringstream last(face.substr(last_line + 1));
  int a = 0, b = 0, c = 0;
  last >> a >> b >> c >> type >> component;
  CHECK(component == 2);
  CHECK(type == 3);
  CHECK(Index(a - 1) == m.triangles.back()[0]);
}

TEST_CASE("formats: MSMS files written by another program, and broken ones") {
  Scratch s;
  s.write("x.vert",
          "# MSMS solvent excluded surface vertices for x\n#vertex #sphere density probe_r\n    3      2  1.00  1.50\n"
          "    0.000     0.000     0.000     0.000     0.000     1.000       0      1  2\n"
          "    1.000     0.000     0.000     0.000     0.000     1.000       0      2  2\n"
          "    0.000     1.000     0.000     0.000     0.000     1.000      -3      2  1\n");
  s.write("x.face",
          "# MSMS solvent excluded surface triangles for x\n#faces  #sphere density probe_r\n    1      2  1.00  1.50\n"
          "     1      2      3  2     17\n");
  const IndexedMesh r = read_mesh(s.path("x.face"));
  CHECK(r.triangles.size() == 1);
  CHECK(r.atom == std::vector<std::int32_t>{0, 1, 1});
  s.write("y.vert", "# v\n#vertex\n 1 1 1 1\n 0 0 0 0 0 1 0 1 2\n");
  s.write("y.face", "# f\n#faces\n 1 1 1 1\n 1 2 3 2 1\n");
  const std::string e = error_of(s.path("y.vert"));
  CHECK(e.find("y.face:4") != std::string::npos);
  CHECK(e.find("out of range") != std::string::npos);
  CHECK(error_of(s.path("missing.vert")).find("missing.vert") != std::string::npos);
  // In memory: the .vert content followed by the .face content.
  const IndexedMesh mem =
      read_mesh_from_bytes(slurp(s.path("x.vert")) + slurp(s.path("x.face")), MeshFormat::Msms, "x");
  CHECK(mem.triangles == r.triangles);
}

TEST_CASE("formats: MSMS writes both files or neither") {
  Scratch s;
  fs::create_directories(s.path("blocked.vert"));  // the .vert cannot be written over a folder
  CHECK_THROWS_AS(write_mesh(s.path("blocked.vert"), sphere_mesh()), InputError);
  CHECK_FALSE(fs::exists(s.path("blocked.face")));
  // An earlier pair stays whole when a new one cannot be written.
  write_mesh(s.path("pair.vert"), sphere_mesh());
  const std::string vert = slurp(s.path("pair.vert")), face = slurp(s.path("pair.face"));
  fs::remove(s.path("pair.face"));
  fs::create_directories(s.path("pair.face"));
  CHECK_THROWS_AS(write_mesh(s.path("pair.vert"), IndexedMesh{}), InputError);
  CHECK(slurp(s.path("pair.vert")) == vert);
  // No temporary file is left behind.
  for (const auto& entry : fs::directory_iterator(s.dir))
    CHECK(entry.path().filename().string().find(".tmp.") == std::string::npos);
}

}  // TEST_SUITE
