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

#include "geometry/kernel/triangle_intersection.h"
#include "geometry/mesh/indexed_mesh.h"

namespace skinmesh::test {

using geometry::IndexedMesh;

// Regular icosahedron with edge length 2, faces counter-clockwise seen from outside.
inline IndexedMesh icosahedron() {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  IndexedMesh m;
  m.positions = {Vec3(-1, t, 0),  Vec3(1, t, 0),  Vec3(-1, -t, 0), Vec3(1, -t, 0), Vec3(0, -1, t),  Vec3(0, 1, t),
                 Vec3(0, -1, -t), Vec3(0, 1, -t), Vec3(t, 0, -1),  Vec3(t, 0, 1),  Vec3(-t, 0, -1), Vec3(-t, 0, 1)};
  m.triangles = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  return m;
}

// `m` (vertices on the unit sphere) subdivided `levels` times (1 -> 4
// triangles), new vertices projected on the unit sphere, numbered in order of
// creation.
inline IndexedMesh subdivided_on_sphere(IndexedMesh m, int levels) {
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

// Icosahedron subdivided `levels` times (1 -> 4 triangles), projected on the unit sphere.
inline IndexedMesh sphere(int levels) {
  IndexedMesh m = icosahedron();
  for (Vec3& p : m.positions) p.normalize();
  return subdivided_on_sphere(std::move(m), levels);
}

// Torus with radii R = 2, r = 0.7 from an n x m grid; outward orientation
// (d/du x d/dv points away from the core circle).
inline IndexedMesh torus(int n, int m) {
  IndexedMesh t;
  const double pi = std::numbers::pi;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * pi * i / n, v = 2 * pi * j / m;
      t.positions.emplace_back((2 + 0.7 * std::cos(v)) * std::cos(u), (2 + 0.7 * std::cos(v)) * std::sin(u),
                               0.7 * std::sin(v));
    }
  auto id = [&](int i, int j) { return Index(((i + n) % n) * m + (j + m) % m); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      t.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return t;
}

// b's vertices and triangles appended to a (b's indices shifted).
inline IndexedMesh join(IndexedMesh a, const IndexedMesh& b) {
  const Index off = Index(a.positions.size());
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  for (auto t : b.triangles) a.triangles.push_back({t[0] + off, t[1] + off, t[2] + off});
  return a;
}

// Brute-force list of intersecting pairs (i < j) of the usable triangles of m
// (no repeated index, not degenerate), with the checker's exact narrow phase
// on all pairs; exact duplicates (3 shared vertices) are skipped.
inline std::vector<std::array<Index, 2>> brute_force_intersections(const IndexedMesh& m) {
  std::vector<std::array<Index, 2>> out;
  const auto& T = m.triangles;
  auto usable = [&](const std::array<Index, 3>& t) {
    return t[0] != t[1] && t[1] != t[2] && t[2] != t[0] &&
           !geometry::is_degenerate_triangle(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
  };
  for (std::size_t i = 0; i < T.size(); ++i) {
    if (!usable(T[i])) continue;
    for (std::size_t j = i + 1; j < T.size(); ++j) {
      if (!usable(T[j])) continue;
      int shared = 0;
      for (Index a : T[i])
        for (Index b : T[j]) shared += a == b;
      if (shared == 3) continue;
      if (geometry::mesh_triangles_intersect(T[i], T[j], m.positions)) out.push_back({Index(i), Index(j)});
    }
  }
  return out;
}

// Integer points on the sphere x^2 + y^2 + z^2 = r2 (exactly cospherical).
inline std::vector<Vec3> integer_sphere(int r2) {
  std::vector<Vec3> out;
  const int r = static_cast<int>(std::sqrt(double(r2)));
  for (int x = -r; x <= r; ++x)
    for (int y = -r; y <= r; ++y)
      for (int z = -r; z <= r; ++z)
        if (x * x + y * y + z * z == r2) out.emplace_back(x, y, z);
  return out;
}

}  // namespace skinmesh::test
