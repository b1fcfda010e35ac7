// tests/skin/skin_mesh_io_test.cpp: the files of a mesh of the skin — the
// skin's vertex data as attributes of PLY and VTK (and absent from OFF, OBJ
// and STL), the molecular MSMS .vert/.face pair written and read back (1e-3 Å),
// MSMS files of another program, broken ones, and the pair written as one.
#include <doctest/doctest.h>

#include <cstdint>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/errors.h"
#include "skin/skin_mesh_io.h"
#include "tests/geometry/mesh_file_fixture.h"

namespace {

using skinmesh::Index;
using skinmesh::InputError;
using skinmesh::Vec3;
using skinmesh::geometry::IndexedMesh;
using skinmesh::skin::read_msms_from_bytes;
using skinmesh::skin::read_skin_mesh;
using skinmesh::skin::SkinVertexData;
using skinmesh::skin::write_skin_mesh;
using skinmesh::test::Scratch;
using skinmesh::test::slurp;
using skinmesh::test::sphere_mesh;

namespace fs = std::filesystem;

/// Vertex data for every vertex of `m`: atoms 0..16 in turn, distinct rho, every patch dimension.
SkinVertexData sphere_data(const IndexedMesh& m) {
  SkinVertexData d;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    d.atom.push_back(static_cast<std::int32_t>(v % 17));
    d.rho.push_back(0.5 + 0.01 * double(v));
    d.patch.push_back(static_cast<std::uint8_t>(v % 4));
  }
  return d;
}

/// The message of the InputError read_skin_mesh(path) throws ("no error" if none).
std::string error_of(const std::string& path) {
  try {
    read_skin_mesh(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_SUITE("skin") {

TEST_CASE("skin mesh files: the extension chooses the format; MSMS is a pair of files") {
  CHECK(skinmesh::skin::is_msms_path("a.VERT"));
  CHECK(skinmesh::skin::is_msms_path("a.face"));
  CHECK_FALSE(skinmesh::skin::is_msms_path("a.ply"));
  CHECK_NOTHROW(skinmesh::skin::require_mesh_format("a.vtk"));
  CHECK_NOTHROW(skinmesh::skin::require_mesh_format("a.face"));
  CHECK_THROWS_AS(skinmesh::skin::require_mesh_format("a.stp"), InputError);
  const auto [vert, face] = skinmesh::skin::msms_paths("dir/x.y.face");
  CHECK(vert == "dir/x.y.vert");
  CHECK(face == "dir/x.y.face");
}

TEST_CASE("skin mesh files: PLY keeps the atom, VTK the atom and rho, OFF, OBJ and STL neither") {
  Scratch s("skinmesh_skin_mesh_io_test_");
  const IndexedMesh m = sphere_mesh();
  const SkinVertexData d = sphere_data(m);
  for (const char* name : {"m.ply", "m.vtk", "m.off", "m.obj", "m.stl"}) {
    CAPTURE(name);
    write_skin_mesh(s.path(name), m, d);
    SkinVertexData r;
    r.patch = {1};  // never read: cleared
    const IndexedMesh back = read_skin_mesh(s.path(name), &r);
    CHECK(back.triangles.size() == m.triangles.size());
    const std::string n = name;
    CHECK(r.atom == (n == "m.ply" || n == "m.vtk" ? d.atom : std::vector<std::int32_t>{}));
    CHECK(r.rho == (n == "m.vtk" ? d.rho : std::vector<double>{}));
    CHECK(r.patch.empty());
  }
  // An atom attribute must be an integer, and -1 (no atom) at least.
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\n";
  const std::string tail = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  CHECK(error_of(s.write("real.ply", head + "property float atom\n" + tail + "0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 2\n"))
            .find("'atom' must have an integer type") != std::string::npos);
  CHECK(error_of(s.write("low.ply", head + "property int atom\n" + tail + "0 0 0 1\n1 0 0 -2\n0 1 0 1\n3 0 1 2\n"))
            .find("atom index -2 (expected >= -1)") != std::string::npos);
}

TEST_CASE("formats: MSMS round trip — positions and normals to 1e-3, the 1-based atom, types and components") {
  Scratch s("skinmesh_skin_mesh_io_test_");
  IndexedMesh m = sphere_mesh();
  SkinVertexData d = sphere_data(m);
  // A second component, shifted: its vertices get component 2.
  const std::size_t n = m.positions.size(), nt = m.triangles.size();
  for (std::size_t v = 0; v < n; ++v) {
    m.positions.push_back(m.positions[v] + Vec3(100, 0, 0));
    m.normals.push_back(m.normals[v]);
    d.atom.push_back(d.atom[v] + 17);
    d.rho.push_back(d.rho[v]);
    d.patch.push_back(0);
  }
  for (std::size_t t = 0; t < nt; ++t)
    m.triangles.push_back({Index(m.triangles[t][0] + n), Index(m.triangles[t][1] + n), Index(m.triangles[t][2] + n)});
  write_skin_mesh(s.path("m.vert"), m, d);
  REQUIRE(fs::exists(s.path("m.face")));
  for (const char* name : {"m.vert", "m.face"}) {
    CAPTURE(name);
    SkinVertexData rd;
    const IndexedMesh r = read_skin_mesh(s.path(name), &rd);
    REQUIRE(r.positions.size() == m.positions.size());
    CHECK(r.triangles == m.triangles);
    CHECK(rd.atom == d.atom);
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
  CHECK(atom == d.atom[0] + 1);
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

TEST_CASE("formats: MSMS without header lines (-no_header) and one pair per component (-all_components)") {
  Scratch s("skinmesh_skin_mesh_io_test_");
  IndexedMesh m = sphere_mesh();
  SkinVertexData d = sphere_data(m);
  // Three components: the sphere and two shifted copies.
  const std::size_t n = m.positions.size(), nt = m.triangles.size();
  for (int copy = 1; copy <= 2; ++copy) {
    for (std::size_t v = 0; v < n; ++v) {
      m.positions.push_back(m.positions[v] + Vec3(100.0 * copy, 0, 0));
      m.normals.push_back(m.normals[v]);
      d.atom.push_back(d.atom[v] + 17 * copy);
      d.rho.push_back(d.rho[v]);
      d.patch.push_back(d.patch[v]);
    }
    for (std::size_t t = 0; t < nt; ++t)
      m.triangles.push_back({Index(m.triangles[t][0] + copy * n), Index(m.triangles[t][1] + copy * n),
                             Index(m.triangles[t][2] + copy * n)});
  }
  write_skin_mesh(s.path("h.vert"), m, d);
  skinmesh::skin::SkinMeshWriteOptions opt;
  opt.msms_header = false;
  write_skin_mesh(s.path("n.vert"), m, d, opt);
  // The records alone: the headered file without its first three lines.
  const std::string headered = slurp(s.path("h.vert")), bare = slurp(s.path("n.vert"));
  std::size_t third = 0;
  for (int k = 0; k < 3; ++k) third = headered.find('\n', third) + 1;
  CHECK(bare == headered.substr(third));
  CHECK(bare.front() != '#');
  SkinVertexData hd, nd;
  const IndexedMesh h = read_skin_mesh(s.path("h.vert"), &hd), r = read_skin_mesh(s.path("n.face"), &nd);
  CHECK(r.positions == h.positions);
  CHECK(r.triangles == h.triangles);
  CHECK(nd.atom == hd.atom);
  // In memory without headers too: the .face part starts at its first record.
  SkinVertexData md;
  const IndexedMesh mem = read_msms_from_bytes(bare + slurp(s.path("n.face")), "n", &md);
  CHECK(mem.positions == h.positions);
  CHECK(mem.triangles == h.triangles);
  CHECK(md.atom == hd.atom);
  CHECK_THROWS_AS(read_msms_from_bytes(bare, "n"), InputError);  // no .face part
  // A pair per component: the first NAME, then NAME_1, NAME_2, each its own numbering.
  opt.msms_header = true;
  opt.msms_split_components = true;
  write_skin_mesh(s.path("c.vert"), m, d, opt);
  CHECK_FALSE(fs::exists(s.path("c_3.vert")));
  for (int k = 0; k < 3; ++k) {
    const std::string name = k == 0 ? std::string("c.vert") : "c_" + std::to_string(k) + ".vert";
    CAPTURE(name);
    SkinVertexData pd;
    const IndexedMesh part = read_skin_mesh(s.path(name), &pd);
    REQUIRE(part.positions.size() == n);
    CHECK(part.triangles.size() == nt);
    for (std::size_t v = 0; v < n; ++v) {
      CHECK((part.positions[v] - h.positions[k * n + v]).cwiseAbs().maxCoeff() == 0);
      CHECK(pd.atom[v] == hd.atom[k * n + v]);
    }
    for (std::size_t t = 0; t < nt; ++t)
      CHECK(part.triangles[t] == std::array<Index, 3>{Index(h.triangles[k * nt + t][0] - k * n),
                                                      Index(h.triangles[k * nt + t][1] - k * n),
                                                      Index(h.triangles[k * nt + t][2] - k * n)});
  }
}

TEST_CASE("formats: MSMS files written by another program, and broken ones") {
  Scratch s("skinmesh_skin_mesh_io_test_");
  s.write("x.vert",
          "# MSMS solvent excluded surface vertices for x\n#vertex #sphere density probe_r\n    3      2  1.00  1.50\n"
          "    0.000     0.000     0.000     0.000     0.000     1.000       0      1  2\n"
          "    1.000     0.000     0.000     0.000     0.000     1.000       0      2  2\n"
          "    0.000     1.000     0.000     0.000     0.000     1.000      -3      2  1\n");
  s.write("x.face",
          "# MSMS solvent excluded surface triangles for x\n#faces  #sphere density probe_r\n    1      2  1.00  1.50\n"
          "     1      2      3  2     17\n");
  SkinVertexData rd;
  const IndexedMesh r = read_skin_mesh(s.path("x.face"), &rd);
  CHECK(r.triangles.size() == 1);
  CHECK(rd.atom == std::vector<std::int32_t>{0, 1, 1});
  s.write("y.vert", "# v\n#vertex\n 1 1 1 1\n 0 0 0 0 0 1 0 1 2\n");
  s.write("y.face", "# f\n#faces\n 1 1 1 1\n 1 2 3 2 1\n");
  const std::string e = error_of(s.path("y.vert"));
  CHECK(e.find("y.face:4") != std::string::npos);
  CHECK(e.find("out of range") != std::string::npos);
  CHECK(error_of(s.path("missing.vert")).find("missing.vert") != std::string::npos);
  // In memory: the .vert content followed by the .face content.
  const IndexedMesh mem = read_msms_from_bytes(slurp(s.path("x.vert")) + slurp(s.path("x.face")), "x");
  CHECK(mem.triangles == r.triangles);
}

TEST_CASE("formats: one MSMS pair per component leaves out a vertex in no triangle") {
  Scratch s("skinmesh_skin_mesh_io_test_");
  IndexedMesh m = sphere_mesh();
  SkinVertexData d = sphere_data(m);
  const std::size_t n = m.positions.size();
  m.positions.push_back(Vec3(50, 0, 0));  // isolated: component 0
  m.normals.push_back(Vec3::UnitZ());
  d.atom.push_back(0);
  d.rho.push_back(1.0);
  d.patch.push_back(d.patch.front());
  skinmesh::skin::SkinMeshWriteOptions opt;
  opt.msms_split_components = true;
  write_skin_mesh(s.path("i.vert"), m, d, opt);
  CHECK_FALSE(fs::exists(s.path("i_1.vert")));
  const IndexedMesh r = read_skin_mesh(s.path("i.vert"));
  CHECK(r.positions.size() == n);
  CHECK(r.triangles == m.triangles);
}

TEST_CASE("position storage: a reader gets back exactly stored(), within max_error(), in every format that rounds") {
  // Coordinates of every size and sign, halfway cases of three decimals
  // among them (1.0005 is not a double, so printf rounds its exact value).
  IndexedMesh m = sphere_mesh();
  std::uint64_t state = 12345;
  auto next = [&state] {  // splitmix64 -> [-1, 1)
    state += 0x9E3779B97F4A7C15ull;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return double((z ^ (z >> 31)) >> 11) * 0x1.0p-52 - 1.0;
  };
  const double scales[] = {1e-3, 0.7, 13.0, 250.0, 4096.0};
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const double scale = scales[v % 5];
    m.positions[v] = Vec3(next(), next(), next()) * scale;
  }
  m.positions[0] = Vec3(1.0005, -2.0015, 0.0625);
  using skinmesh::geometry::PositionStorage;
  Scratch s("skinmesh_position_storage_test_");
  for (int decimals : {3, 4, 6, 9, 12}) {
    CAPTURE(decimals);
    skinmesh::skin::SkinMeshWriteOptions opt;
    opt.msms_decimals = decimals;
    const PositionStorage storage = skinmesh::skin::position_storage(s.path("m.vert"), opt);
    REQUIRE(storage.kind == PositionStorage::Kind::Decimals);
    write_skin_mesh(s.path("m.vert"), m, {}, opt);
    const IndexedMesh back = read_skin_mesh(s.path("m.vert"));
    REQUIRE(back.positions.size() == m.positions.size());
    const double bound = storage.max_error(m);
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
      CHECK(back.positions[v] == storage.stored(m.positions[v]));
      CHECK((back.positions[v] - m.positions[v]).norm() <= bound);
    }
  }
  // Every float32 variant: binary (the float itself) and text (the shortest
  // text of the float, read back as the nearest double).
  for (const char* name : {"m.stl", "m.ply", "a.ply", "a.stl", "m.off", "m.obj", "m.vtk"}) {
    CAPTURE(name);
    skinmesh::skin::SkinMeshWriteOptions opt;
    opt.geometry.double_precision = std::string(name) == "m.stl";  // binary STL rounds either way
    opt.geometry.ascii = name[0] == 'a';
    const PositionStorage storage = skinmesh::skin::position_storage(s.path(name), opt);
    const bool binary = std::string(name) == "m.stl" || std::string(name) == "m.ply";
    REQUIRE(storage.kind == (binary ? PositionStorage::Kind::Float32 : PositionStorage::Kind::Float32Text));
    write_skin_mesh(s.path(name), m, {}, opt);
    const IndexedMesh back = read_skin_mesh(s.path(name));
    const double bound = storage.max_error(m);
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const Vec3 &p = m.positions[m.triangles[t][k]], &q = back.positions[back.triangles[t][k]];
        CHECK(q == storage.stored(p));
        CHECK((q - p).norm() <= bound);
      }
    // The checker recognises float32 coordinates in any format.
    CHECK(skinmesh::skin::position_rounding(s.path(name), back) >= bound);
  }
  // Exact formats: stored() is the identity and a reader gets the doubles back.
  const PositionStorage exact = skinmesh::skin::position_storage(s.path("m.ply"));
  CHECK_FALSE(exact.lossy());
  write_skin_mesh(s.path("m.ply"), m, {});
  CHECK(read_skin_mesh(s.path("m.ply")).positions == m.positions);
  CHECK(skinmesh::skin::position_rounding(s.path("m.ply"), m) == 0);
  // Decimals out of range are refused before anything is written.
  skinmesh::skin::SkinMeshWriteOptions bad;
  bad.msms_decimals = 2;
  CHECK_THROWS_AS(write_skin_mesh(s.path("bad.vert"), m, {}, bad), std::invalid_argument);
  CHECK_FALSE(fs::exists(s.path("bad.vert")));
}

TEST_CASE("msms_atom_name: five parts split at '_', blanks named, inner blanks joined by '-'") {
  using skinmesh::skin::Atom;
  using skinmesh::skin::msms_atom_name;
  Atom a;
  a.chain = "A", a.residue_number = 12, a.residue = "ALA", a.name = "CA";
  CHECK(msms_atom_name(a) == "A_12_x_ALA_CA");
  a.insertion_code = 'B';
  CHECK(msms_atom_name(a) == "A_12_B_ALA_CA");
  // Blank fields (built without string literals: GCC 12 warns falsely on
  // a short literal assigned over a longer string, -Wrestrict).
  a.chain.clear();
  a.residue.assign(1, ' ');
  a.name.clear();
  a.residue_number = -3;
  a.insertion_code = ' ';
  CHECK(msms_atom_name(a) == "x_-3_x_UNK_X");
  a.chain = "AB", a.residue = "LIG", a.name = "C 1 ";
  CHECK(msms_atom_name(a) == "AB_-3_x_LIG_C-1");
}

TEST_CASE("formats: MSMS writes both files or neither") {
  Scratch s("skinmesh_skin_mesh_io_test_");
  fs::create_directories(s.path("blocked.vert"));  // the .vert cannot be written over a folder
  CHECK_THROWS_AS(write_skin_mesh(s.path("blocked.vert"), sphere_mesh(), {}), InputError);
  CHECK_FALSE(fs::exists(s.path("blocked.face")));
  // An earlier pair stays whole when a new one cannot be written.
  write_skin_mesh(s.path("pair.vert"), sphere_mesh(), {});
  const std::string vert = slurp(s.path("pair.vert")), face = slurp(s.path("pair.face"));
  fs::remove(s.path("pair.face"));
  fs::create_directories(s.path("pair.face"));
  CHECK_THROWS_AS(write_skin_mesh(s.path("pair.vert"), IndexedMesh{}, {}), InputError);
  CHECK(slurp(s.path("pair.vert")) == vert);
  // No temporary file is left behind.
  for (const auto& entry : fs::directory_iterator(s.dir))
    CHECK(entry.path().filename().string().find(".tmp.") == std::string::npos);
}

}  // TEST_SUITE
