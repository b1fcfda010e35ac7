// tests/skin/mixed_complex_degenerate_test.cpp: the mixed complex on nearly
// degenerate inputs (needle triangles from nearly coincident centres, coplanar
// rings whose tetrahedra are flat up to rounding), papers/skin/mixed_complex.md
// "Degenerate inputs".
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "skin/molecule_io.h"
#include "skin/skin_surface.h"
#include "tests/skin/skin_test_util.h"

using namespace skinmesh;

namespace {

/// Checks that the cells of the mixed complex of `pts` tile space near the
/// atoms and carry the skin function: `samples` points (half of them on the
/// skin, found by bisection of the brute-force f along rays from the centres)
/// are located in a cell they lie in, no point is strictly inside two cells,
/// and f of the located cell equals the brute-force definition.
void check_tiling(const std::vector<geometry::WeightedPoint>& pts, int samples, unsigned seed) {
  INFO("seed = " << seed);
  const skin::SkinSurface skin(pts);
  const skin::MixedComplex& mc = skin.mixed_complex();
  const double L = mc.length_scale();
  Vec3 lo = pts[0].z, hi = pts[0].z;
  double r = 0;
  for (const auto& p : pts) {
    lo = lo.cwiseMin(p.z), hi = hi.cwiseMax(p.z);
    r = std::max(r, std::sqrt(p.w / 2));
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < samples; ++i) {
    Vec3 x = lo - Vec3::Constant(r) + (hi - lo + Vec3::Constant(2 * r)).cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
    if (i % 2 == 1) {  // a point on the skin
      const Vec3 c = pts[static_cast<std::size_t>(i) % pts.size()].z;
      const Vec3 d = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
      double a = 0, b = 2 * r;
      for (int it = 0; it < 60; ++it) {
        const double m = 0.5 * (a + b);
        (test::brute_force_skin_function(pts, c + m * d) < 0 ? a : b) = m;
      }
      x = c + a * d;
    }
    const Index cell = mc.locate(x);
    CHECK(mc.violation(cell, x) <= 1e-9 * L);
    CHECK(std::abs(mc.f(cell, x) - test::brute_force_skin_function(pts, x)) <= 1e-10 * L * L);
    int inside = 0;
    for (Index c = 0; c < mc.num_cells(); ++c) inside += mc.violation(c, x) <= -1e-9 * L ? 1 : 0;
    CHECK(inside <= 1);
  }
}

}  // namespace

TEST_SUITE("skin") {

TEST_CASE("focus of a needle triangle (two centres 1e-9 Å apart) has equal power to its vertices") {
  // Cramer's rule on the Gram matrix cancels to det = 0 here (NaN focus).
  const std::vector<geometry::WeightedPoint> tri = {
      {Vec3(7.7143016194581202, 1.8410153037016823, 0.02784446253773256), 9.0},
      {Vec3(7.7143016187703894, 1.8410153030873522, 0.027844462150918927), 9.0},
      {Vec3(1.5063499737438326, 5.2935089837319094, 10.805394779724196), 12.5}};
  Vec3 z;
  double w = 0;
  skin::focus_of(tri, z, w);
  REQUIRE(z.allFinite());
  REQUIRE(std::isfinite(w));
  for (const auto& p : tri) CHECK(std::abs(geometry::power_distance(p, z) - w) <= 1e-9 * std::max(1.0, std::abs(w)));
  // z lies in the plane of the triangle.
  const Vec3 n = (tri[1].z - tri[0].z).cross(tri[2].z - tri[0].z).normalized();
  CHECK(std::abs(n.dot(z - tri[0].z)) <= 1e-9);
}

TEST_CASE("mixed complex of a ring coplanar up to rounding: cells tile space and carry f") {
  // Before the fix the constructor stopped on a facet/coface pair with
  // P_perp (z_k - z_X) = 0 (tests/data/regression/ring8_probe3_coplanar_facets.xyzr).
  const skin::Molecule mol =
      skin::read_molecule(std::string(SKINMESH_TEST_DATA) + "/regression/ring8_probe3_coplanar_facets.xyzr");
  const auto pts = skin::weighted_points(mol, 3.0);
  check_tiling(pts, 200, 20040101u);
}

TEST_CASE("mixed complex of near-copies (atoms duplicated 1e-9 Å away) and a rotated flat ring") {
  std::mt19937 rng(7);
  // Six atoms on a circle (a closed hexagonal ring), rotated: every four of them
  // are coplanar and cocircular up to rounding.
  std::vector<geometry::WeightedPoint> ring;
  const Mat3 R = test::random_rotation(rng);
  for (int i = 0; i < 6; ++i) {
    const double t = i * M_PI / 3;
    ring.push_back({R * Vec3(3.2 * std::cos(t), 3.2 * std::sin(t), 0.0) + Vec3(2, 1, 1), 2 * 3.3 * 3.3});
  }
  check_tiling(ring, 100, 11u);
  std::vector<geometry::WeightedPoint> copies = test::random_points(6, 4.0, 0.8, 2.0, rng);
  for (int i = 0; i < 6; i += 2) copies.push_back({copies[i].z + Vec3(6e-10, -5e-10, 4e-10), copies[i].w});
  // Every focus and plane is finite (the needle triangles used to give NaN).
  skin::SkinSurface skin(copies);
  const skin::MixedComplex& mc = skin.mixed_complex();
  for (Index c = 0; c < mc.num_cells(); ++c) {
    CHECK(mc.cell(c).focus.allFinite());
    for (const auto& p : mc.planes(c)) CHECK((p.normal.allFinite() && std::isfinite(p.offset)));
  }
}

}  // TEST_SUITE
