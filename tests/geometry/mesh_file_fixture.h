// tests/geometry/mesh_file_fixture.h: what the tests of mesh files share — a
// scratch folder removed at the end, reading a file whole, and a closed mesh
// to write (tests/geometry/mesh_io_formats_test.cpp, tests/skin/skin_mesh_io_test.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "core/types.h"
#include "geometry/mesh/indexed_mesh.h"
#include "tests/geometry/test_meshes.h"

namespace skinmesh::test {

using geometry::IndexedMesh;

/// A fresh folder under the system's temporary folder (its name begins with
/// `prefix`), removed with its content.
struct Scratch {
  std::filesystem::path dir;
  explicit Scratch(const std::string& prefix) {
    dir = std::filesystem::temp_directory_path() / (prefix + std::to_string(std::random_device{}()));
    std::filesystem::create_directories(dir);
  }
  ~Scratch() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  std::string path(const std::string& name) const { return (dir / name).string(); }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(path(name), std::ios::binary) << bytes;
    return path(name);
  }
};

/// The whole content of the file `path` (empty if it cannot be read).
inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

/// A closed mesh (a subdivided, jittered octahedron: 66 vertices, 128
/// triangles, centred at (31.25, -7.5, 1/3)) with unit outward normals.
inline IndexedMesh sphere_mesh() {
  IndexedMesh octahedron;
  octahedron.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  octahedron.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  IndexedMesh m = subdivided_on_sphere(std::move(octahedron), 2);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jitter(-1e-4, 1e-4);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    Vec3& p = m.positions[v];
    p = 12.3456789 * p + Vec3(31.25 + jitter(rng), -7.5 + jitter(rng), 1.0 / 3.0);
    m.normals.push_back((p - Vec3(31.25, -7.5, 1.0 / 3.0)).normalized());
  }
  return m;
}

}  // namespace skinmesh::test
