// tests/skin/dual_complex_exact_test.cpp: the expected topology from K0 on flat
// and cospherical inputs, independent of rotation and translation, and the
// reporting of exact ties (papers/skin/dual_complex.md "Exact filtration signs").
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "skin/dual_complex.h"
#include "skin/skin_surface.h"

using namespace skinmesh;
using geometry::WeightedPoint;

namespace {

/// n balls of radius rho with centres on a circle of radius R in the plane
/// z = 0, then rotated by `rot` and translated by `shift`.
std::vector<WeightedPoint> ring(int n, double R, double rho, const Eigen::Matrix3d& rot, const Vec3& shift) {
  std::vector<WeightedPoint> pts;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    pts.push_back({rot * Vec3(R * std::cos(t), R * std::sin(t), 0) + shift, rho * rho});
  }
  return pts;
}

Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> g(0, 1);
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  return q.normalized().toRotationMatrix();
}

}  // namespace

TEST_SUITE("skin") {

TEST_CASE("K0 of a rotated planar ring: hole open gives a torus, closed a sphere") {
  // Centres on a circle of radius R = 2; neighbours overlap (rho > R sin(pi/n))
  // and opposite balls do not (rho < R), so the union is a solid torus iff the
  // centre of the circle, at distance R from every centre, is uncovered.
  std::mt19937 rng(42);
  for (const int n : {6, 8, 12}) {
    for (int trial = 0; trial < 12; ++trial) {
      const Eigen::Matrix3d rot = trial == 0 ? Eigen::Matrix3d::Identity() : random_rotation(rng);
      const Vec3 shift = (trial % 3 == 1) ? Vec3(1e6, -1e6, 1e6) : (trial % 3 == 2 ? Vec3(0.3, 0.1, 7) : Vec3::Zero());
      for (const double rel : {1e-3, 1e-6}) {
        INFO("n = " << n << ", trial = " << trial << ", margin = " << rel);
        const auto open =
            skin::dual_complex_topology(skin::SkinSurface(ring(n, 2.0, 2.0 * (1 - rel), rot, shift)).mixed_complex());
        CHECK(open.components() == 1);
        CHECK(open.euler_skin() == 0);
        CHECK(open.total_genus() == 1);
        CHECK(open.singular_simplices.empty());
        const auto closed =
            skin::dual_complex_topology(skin::SkinSurface(ring(n, 2.0, 2.0 * (1 + rel), rot, shift)).mixed_complex());
        CHECK(closed.components() == 1);
        CHECK(closed.euler_skin() == 2);
        CHECK(closed.total_genus() == 0);
        CHECK(closed.singular_simplices.empty());
      }
    }
  }
}

TEST_CASE("K0 of an exactly cospherical lattice cell does not depend on the tie breaking") {
  // The 8 corners of a cube of side 2 with radius-1.2 balls: edges overlap,
  // face diagonals (2.83) and body diagonals (3.46) do not, and the face and
  // body centres are uncovered: the union is the cube's edge frame, a surface
  // of genus 5 (chi(K0) = 8 - 12 = -4). Every face is four concyclic points.
  std::vector<WeightedPoint> pts;
  for (int i = 0; i < 8; ++i) pts.push_back({Vec3(2.0 * (i & 1), 2.0 * ((i >> 1) & 1), 2.0 * (i >> 2)), 1.44});
  const auto t = skin::dual_complex_topology(skin::SkinSurface(pts).mixed_complex());
  CHECK(t.k0_simplices[0] == 8);
  CHECK(t.k0_simplices[1] == 12);
  CHECK(t.k0_simplices[2] == 0);
  CHECK(t.euler_k0 == -4);
  CHECK(t.components() == 1);
  CHECK(t.total_genus() == 5);
  CHECK(t.singular_simplices.empty());
  CHECK(t.orthogonal_ties > 0);  // the face diagonals' foci are the face centres
}

TEST_CASE("K0 reports simplices whose balls meet in exactly one point") {
  SUBCASE("two tangent balls: one component (closed balls), the edge reported") {
    const std::vector<WeightedPoint> pts = {{Vec3(0, 0, 0), 4.0}, {Vec3(5, 0, 0), 9.0}};
    const auto t = skin::dual_complex_topology(skin::SkinSurface(pts).mixed_complex());
    CHECK(t.components() == 1);
    REQUIRE(t.singular_simplices.size() == 1);
    CHECK(t.singular_simplices[0][0] == 0);
    CHECK(t.singular_simplices[0][1] == 1);
    CHECK(t.singular_simplices[0][2] == kInvalidIndex);
  }
  SUBCASE("a square ring whose hole closes exactly at its centre") {
    // Radius-2 balls at (+-2, 0, 0), (0, +-2, 0): all four spheres pass through
    // the origin, the focus of every triangle of the four centres.
    const std::vector<WeightedPoint> pts = {
        {Vec3(2, 0, 0), 4.0}, {Vec3(0, 2, 0), 4.0}, {Vec3(-2, 0, 0), 4.0}, {Vec3(0, -2, 0), 4.0}};
    const auto t = skin::dual_complex_topology(skin::SkinSurface(pts).mixed_complex());
    CHECK(t.components() == 1);
    CHECK(t.total_genus() == 0);  // closed balls share the origin
    REQUIRE(!t.singular_simplices.empty());
    // The two triangles of the square and its diagonal edge have their focus
    // at the origin with weight 0; the sides (w = 2 - 4) and the vertices do not.
    CHECK(t.singular_simplices.size() == 3);
    for (const auto& s : t.singular_simplices) {
      CHECK(s[1] != kInvalidIndex);
      CHECK(s[3] == kInvalidIndex);
      for (const Index v : s) CHECK((v < 4 || v == kInvalidIndex));
    }
  }
}

TEST_CASE("K0 on 1, 2 and 3 threads: the same counts, ties and singular simplices in the same order") {
  // A cubic lattice of touching balls (spacing 2, radius 1): every lattice
  // edge is singular and every cell of the lattice cospherical (ties), with
  // enough cells of each dimension (over 4,096) for several blocks per pass.
  std::vector<WeightedPoint> pts;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j)
      for (int k = 0; k < 12; ++k) pts.push_back({Vec3(2.0 * i, 2.0 * j, 2.0 * k), 1.0});
  const skin::SkinSurface skin(pts, 2);
  const skin::SkinTopology one = skin::dual_complex_topology(skin.mixed_complex(), 1);
  REQUIRE(one.singular_simplices.size() > 4096);
  REQUIRE(one.orthogonal_ties > 0);
  for (int threads : {2, 3}) {
    const skin::SkinTopology many = skin::dual_complex_topology(skin.mixed_complex(), threads);
    for (int d = 0; d < 4; ++d) CHECK(many.k0_simplices[d] == one.k0_simplices[d]);
    CHECK(many.betti0 == one.betti0);
    CHECK(many.betti2 == one.betti2);
    CHECK(many.orthogonal_ties == one.orthogonal_ties);
    CHECK(many.singular_simplices == one.singular_simplices);
  }
}

}  // TEST_SUITE
