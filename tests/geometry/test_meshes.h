// tests/geometry/test_meshes.h: closed reference meshes shared by the tests
// (icosahedron, subdivided sphere, torus), with known topology and geometry.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

#include "geometry/indexed_mesh.h"

namespace skinmesh::test {

using geometry::IndexedMesh;

// Regular icosahedron with edge length 2, faces counter-clockwise seen from outside.
inline IndexedMesh icosahedron() {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  IndexedMesh m;
  m.positions = {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0),
                 Vec3(0, -1, t), Vec3(0, 1, t), Vec3(0, -1, -t), Vec3(0, 1, -t),
                 Vec3(t, 0, -1), Vec3(t, 0, 1), Vec3(-t, 0, -1), Vec3(-t, 0, 1)};
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  return m;
}

// Icosahedron subdivided `levels` times (1 -> 4 triangles), projected on the unit sphere.
inline IndexedMesh sphere(int levels) {
  IndexedMesh m = icosahedron();
  for (Vec3& p : m.positions) p.normalize();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<Index, Index>, Index> mid;
    auto midpoint = [&](Index a, Index b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      const Index i = Index(m.positions.size());
      m.positions.push_back((m.positions[a] + m.positions[b]).normalized());
      mid.emplace(key, i);
      return i;
    };
    std::vector<std::array<Index, 3>> next;
    for (const auto& t : m.triangles) {
      const Index ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({ab, t[1], bc});
      next.push_back({ca, bc, t[2]});
      next.push_back({ab, bc, ca});
    }
    m.triangles = next;
  }
  return m;
}

// Torus with radii R = 2, r = 0.7 from an n x m grid; outward orientation
// (d/du x d/dv points away from the core circle).
inline IndexedMesh torus(int n, int m) {
  IndexedMesh t;
  const double pi = std::numbers::pi;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * pi * i / n, v = 2 * pi * j / m;
      t.positions.emplace_back((2 + 0.7 * std::cos(v)) * std::cos(u),
                               (2 + 0.7 * std::cos(v)) * std::sin(u), 0.7 * std::sin(v));
    }
  auto id = [&](int i, int j) { return Index(((i + n) % n) * m + (j + m) % m); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      t.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return t;
}

}  // namespace skinmesh::test
