// tests/skin/skin_test_util.h: an independent brute-force evaluation of the skin
// function from its definition, for tests (papers/skin/skin_math.md §1.2, §10).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/Dense>

#include "geometry/kernel/weighted_point.h"
#include "skin/mixed_complex.h"

namespace skinmesh::test {

using geometry::WeightedPoint;

/// f(x) = min over convex combinations b of the input points of pi_{b^{1/2}}(x),
/// by enumerating every subset S of at most 4 affinely independent points: the
/// minimiser over aff S has centre z* = z_S + 2 P_par y and value
/// |P_perp y|² - |P_par y|² + w_S/2; it counts only if z* lies in conv S.
/// O(n^4) per point: small inputs only. Uses no triangulation.
inline double brute_force_skin_function(const std::vector<WeightedPoint>& pts, const Vec3& x) {
  const int n = static_cast<int>(pts.size());
  double best = std::numeric_limits<double>::infinity();
  std::array<int, 4> idx{};
  auto consider = [&](int k) {  // subset idx[0..k-1]
    std::array<WeightedPoint, 4> sub;
    for (int i = 0; i < k; ++i) sub[i] = pts[idx[i]];
    // Orthonormal basis of the direction space (Gram–Schmidt) and the edge
    // vectors; skip affinely dependent subsets.
    std::array<Vec3, 3> basis, edges;
    for (int i = 1; i < k; ++i) {
      edges[i - 1] = sub[i].z - sub[0].z;
      Vec3 v = edges[i - 1];
      for (int j = 0; j < i - 1; ++j) v -= v.dot(basis[j]) * basis[j];
      if (v.norm() < 1e-9 * std::max(1.0, edges[i - 1].norm())) return;
      basis[i - 1] = v.normalized();
    }
    Vec3 zs;
    double ws;
    skin::focus_of(std::span<const WeightedPoint>(sub.data(), k), zs, ws);
    const Vec3 y = x - zs;
    Vec3 ypar = Vec3::Zero();
    for (int j = 0; j < k - 1; ++j) ypar += y.dot(basis[j]) * basis[j];
    const Vec3 yperp = y - ypar;
    const Vec3 zstar = zs + 2.0 * ypar;
    // Barycentric coordinates of z* (least squares in the edge basis).
    if (k > 1) {
      Mat3 G = Mat3::Identity();
      Vec3 rhs = Vec3::Zero();
      for (int i = 0; i < k - 1; ++i) {
        rhs(i) = edges[i].dot(zstar - sub[0].z);
        for (int j = 0; j < k - 1; ++j) G(i, j) = edges[i].dot(edges[j]);
      }
      const Vec3 lam = G.fullPivLu().solve(rhs);
      double l0 = 1.0;
      for (int i = 0; i < k - 1; ++i) {
        if (lam(i) < -1e-12) return;
        l0 -= lam(i);
      }
      if (l0 < -1e-12) return;
    }
    best = std::min(best, yperp.squaredNorm() - ypar.squaredNorm() + 0.5 * ws);
  };
  for (int a = 0; a < n; ++a) {
    idx[0] = a;
    consider(1);
    for (int b = a + 1; b < n; ++b) {
      idx[1] = b;
      consider(2);
      for (int c = b + 1; c < n; ++c) {
        idx[2] = c;
        consider(3);
        for (int d = c + 1; d < n; ++d) {
          idx[3] = d;
          consider(4);
        }
      }
    }
  }
  return best;
}

/// Random rotation matrix from a seeded generator.
inline Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> g;
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  return q.normalized().toRotationMatrix();
}

/// The configurations of papers/skin/skin_math.md §10; their reference values
/// are in tests/data/skin_vectors.txt (tests/skin/skin_vectors.h).
inline std::vector<WeightedPoint> two_balls() { return {{Vec3(0, 0, 0), 2.0}, {Vec3(2, 0, 0), 2.0}}; }
inline std::vector<WeightedPoint> tetrahedron_void() {
  const double s = 1.0 / std::sqrt(2.0);
  return {
      {Vec3(1, 1, 1) * s, 1.42}, {Vec3(1, -1, -1) * s, 1.42}, {Vec3(-1, 1, -1) * s, 1.42}, {Vec3(-1, -1, 1) * s, 1.42}};
}
inline std::vector<WeightedPoint> three_ball_ring() {
  const double r = 1.9 / std::sqrt(3.0);
  return {{Vec3(1, 0, 0) * r, 1.0},
          {Vec3(-0.5, std::sqrt(3.0) / 2, 0) * r, 1.0},
          {Vec3(-0.5, -std::sqrt(3.0) / 2, 0) * r, 1.0}};
}
/// Eight weighted points at the corners of a cube (the paper's Figure 4).
inline std::vector<WeightedPoint> cube_corners(double w) {
  std::vector<WeightedPoint> p;
  for (int i = 0; i < 8; ++i) p.push_back({Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1), w});
  return p;
}
/// n random weighted points in a cube of side `side`, weights in [wlo, whi].
inline std::vector<WeightedPoint> random_points(int n, double side, double wlo, double whi, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, side), uw(wlo, whi);
  std::vector<WeightedPoint> p(n);
  for (auto& b : p) b = {Vec3(u(rng), u(rng), u(rng)), uw(rng)};
  return p;
}

}  // namespace skinmesh::test
