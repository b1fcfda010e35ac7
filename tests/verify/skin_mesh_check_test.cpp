// tests/verify/skin_mesh_check_test.cpp: the skin-aware verifier on meshes
// whose properties are known: icospheres on a one-atom skin (the restricted
// Delaunay triangulation of points on a sphere is their convex hull).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "skin/restricted_delaunay.h"
#include "skin/size_conditions.h"
#include "tests/geometry/test_meshes.h"
#include "verify/skin_mesh_check.h"

using namespace skinmesh;

namespace {

/// Icosphere of radius R about c with `levels` 1:4 subdivisions, CCW outward.
geometry::IndexedMesh icosphere(const Vec3& c, double R, int levels) {
  geometry::IndexedMesh m = test::sphere(levels);
  for (Vec3& p : m.positions) p = c + R * p;
  return m;
}

}  // namespace

TEST_SUITE("verify") {

TEST_CASE("size constants: the numbers of papers/skin/skin_math.md §8") {
  skin::SizeConstants k;
  CHECK(k.min_angle_bound_deg() == doctest::Approx(21.5498).epsilon(1e-4));
  CHECK(k.disc_factor_lower() == doctest::Approx(0.107383).epsilon(1e-5));
  CHECK(k.disc_factor_upper() == doctest::Approx(0.207719).epsilon(1e-5));
  CHECK(skin::circumradius(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)) == doctest::Approx(std::sqrt(0.5)));
}

TEST_CASE("surface Delaunay centre of a triangle on a sphere is on the sphere") {
  skin::SkinSurface skin({{Vec3(1, 2, 3), 2 * 4.0}});  // sphere of radius 2 about (1,2,3)
  const Vec3 c(1, 2, 3);
  const Vec3 a = c + 2 * Vec3(1, 0.1, 0).normalized(), b = c + 2 * Vec3(1, 0, 0.1).normalized(),
             d = c + 2 * Vec3(1, -0.1, -0.05).normalized();
  Vec3 m;
  Index cell = kInvalidIndex;
  REQUIRE(skin::surface_delaunay_centre(skin, a, b, d, m, cell));
  CHECK(std::abs((m - c).norm() - 2.0) < 1e-12);
  CHECK(std::abs((m - a).norm() - (m - b).norm()) < 1e-12);
  CHECK(std::abs((m - a).norm() - (m - d).norm()) < 1e-12);
}

TEST_CASE("icosphere on a one-atom skin passes every check at the right density") {
  const Vec3 c(0.3, -0.2, 0.1);
  const double R = 2.0;
  skin::SkinSurface skin({{c, 2 * R * R}});  // skin: sphere of radius R
  const auto rep = verify::check_skin_mesh(skin, icosphere(c, R, 3));
  INFO(rep.to_json());
  CHECK(rep.ok());
  CHECK(rep.mesh.closed);
  CHECK(rep.topology_matches);
  CHECK(rep.max_vertex_distance < 1e-12);
  CHECK(rep.num_L_violations == 0);
  CHECK(rep.num_U_violations == 0);
  CHECK(rep.num_rdt_violations == 0);
  CHECK(rep.num_inward_triangles == 0);
}

TEST_CASE("the verifier finds each kind of defect") {
  const Vec3 c(0, 0, 0);
  const double R = 2.0;
  skin::SkinSurface skin({{c, 2 * R * R}});
  SUBCASE("too coarse: [U] violations") {
    const auto rep = verify::check_skin_mesh(skin, icosphere(c, R, 1));
    CHECK(rep.num_U_violations > 0);
    CHECK(!rep.ok());
  }
  SUBCASE("too fine: [L] violations") {
    verify::SkinCheckOptions opt;
    opt.check_self_intersections = false;
    const auto rep = verify::check_skin_mesh(skin, icosphere(c, R, 5), opt);
    CHECK(rep.num_L_violations > 0);
  }
  SUBCASE("a vertex off the surface") {
    auto m = icosphere(c, R, 3);
    m.positions[7] *= 1.001;
    const auto rep = verify::check_skin_mesh(skin, m);
    CHECK(rep.num_far_vertices == 1);
    CHECK(rep.max_vertex_distance > 1e-4);
  }
  SUBCASE("inside-out mesh") {
    auto m = icosphere(c, R, 3);
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
    const auto rep = verify::check_skin_mesh(skin, m);
    CHECK(rep.num_inward_triangles == m.triangles.size());
  }
  SUBCASE("a flipped edge breaks the restricted Delaunay property") {
    auto m = icosphere(c, R, 3);
    // Flip the edge shared by triangles 0 and its neighbour across edge (t0[0], t0[1]).
    const auto t0 = m.triangles[0];
    std::size_t j = 0;
    for (; j < m.triangles.size(); ++j) {
      const auto& t = m.triangles[j];
      bool has0 = false, has1 = false;
      for (Index v : t) has0 |= v == t0[0], has1 |= v == t0[1];
      if (j != 0 && has0 && has1) break;
    }
    REQUIRE(j < m.triangles.size());
    Index d = kInvalidIndex;
    for (Index v : m.triangles[j])
      if (v != t0[0] && v != t0[1]) d = v;
    m.triangles[0] = {t0[2], t0[0], d};
    m.triangles[j] = {t0[2], d, t0[1]};
    const auto rep = verify::check_skin_mesh(skin, m);
    CHECK(rep.mesh.closed);
    CHECK(rep.num_rdt_violations >= 2);
  }
  SUBCASE("a missing sphere: wrong topology") {
    std::vector<geometry::WeightedPoint> two = {{Vec3(0, 0, 0), 2.0}, {Vec3(5, 0, 0), 2.0}};
    skin::SkinSurface skin2(two);
    const auto rep = verify::check_skin_mesh(skin2, icosphere(Vec3(0, 0, 0), 1.0, 3));
    CHECK(!rep.topology_matches);
    CHECK(rep.expected.components() == 2);
  }
}

TEST_CASE("[L] and restricted-Delaunay counts equal brute force on perturbed, flipped, duplicated meshes") {
  // Reference: a std::set of undirected edges for [L]; a scan of every vertex for
  // the surface Delaunay balls (same centre, same radius, same distance test).
  const Vec3 c(0.3, -0.2, 0.1);
  const double R = 2.0;
  skin::SkinSurface skin({{c, 2 * R * R}});
  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int level = 2; level <= 4; ++level)
    for (int variant = 0; variant < 3; ++variant) {
      geometry::IndexedMesh m = icosphere(c, R, level);
      // Move vertices along the sphere by a fraction of the edge length (keeps
      // them on the skin, breaks RDT).
      const double amp = 0.05 * R * double(1 << (4 - level));
      for (Vec3& p : m.positions)
        if (u(rng) > 0.2 * variant) p = c + R * (p - c + amp * Vec3(u(rng), u(rng), u(rng))).normalized();
      if (variant == 2) {  // a duplicate, a reversed triangle and a degenerate one
        m.triangles.push_back(m.triangles[3]);
        m.triangles.push_back({m.triangles[5][0], m.triangles[5][2], m.triangles[5][1]});
        m.triangles.push_back({0, 0, 1});
      }
      skin::RunContext run;
      run.size.C = 0.08 * (0.5 + variant);  // more or fewer [L] violations
      const auto rep = verify::check_skin_mesh(skin, m, {}, run);
      const auto& P = m.positions;
      std::set<std::pair<Index, Index>> edges;
      std::size_t want_L = 0, want_rdt = 0;
      auto rho = [&](Index v) { return skin.sample(P[v]).rho; };
      for (const auto& t : m.triangles) {
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
        for (int i = 0; i < 3; ++i) {
          const Index a = std::min(t[i], t[(i + 1) % 3]), b = std::max(t[i], t[(i + 1) % 3]);
          if (edges.insert({a, b}).second && !skin::satisfies_L(P[a], P[b], rho(a), rho(b), run.size)) ++want_L;
        }
        Vec3 mc;
        Index cell = skin.sample(P[t[0]]).cell;
        bool bad = !skin::surface_delaunay_centre(skin, P[t[0]], P[t[1]], P[t[2]], mc, cell);
        if (!bad) {
          const double r = (mc - P[t[0]]).norm() * (1 - 1e-9);
          for (Index v = 0; v < P.size(); ++v)
            if (v != t[0] && v != t[1] && v != t[2] && (P[v] - mc).squaredNorm() <= r * r) bad = true;
        }
        want_rdt += bad;
      }
      INFO("level " << level << " variant " << variant);
      CHECK(rep.num_L_violations == want_L);
      CHECK(rep.num_rdt_violations == want_rdt);
      CHECK(want_rdt > 0);
    }
}

}  // TEST_SUITE

TEST_SUITE("verify") {

TEST_CASE("the report is the same with one, two and three threads") {
  // skin::RunContext::threads: the mesh-only checks on a second thread must
  // not change a single byte of the report, including the order of the
  // problems, on clean and defective meshes.
  const Vec3 c(0, 0, 0);
  const double R = 2.0;
  skin::SkinSurface skin({{c, 2 * R * R}});
  std::vector<geometry::IndexedMesh> meshes;
  meshes.push_back(icosphere(c, R, 3));  // clean
  meshes.push_back(icosphere(c, R, 1));  // too coarse: [U]
  {
    auto m = icosphere(c, R, 3);  // a vertex off the skin, pushed far enough to fold
    m.positions[7] *= 1.2;
    meshes.push_back(m);
  }
  {
    auto m = icosphere(c, R, 3);  // inside out, plus a duplicated triangle
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
    m.triangles.push_back(m.triangles.front());
    meshes.push_back(m);
  }
  {
    auto m = icosphere(c, R, 2);  // a needle: a vertex moved next to its neighbour
    m.positions[5] = m.positions[6] * 0.999 + m.positions[5] * 0.001;
    meshes.push_back(m);
  }
  {
    // Fine enough that the vertex samples and the restricted Delaunay test
    // run in several blocks on the threads (10,242 vertices, 20,480
    // triangles), with defects in the first and the last: the counts and the
    // examples must be joined in order.
    auto m = icosphere(c, R, 5);
    for (const std::size_t v : {std::size_t{40}, m.positions.size() - 40}) m.positions[v] *= 1.01;
    meshes.push_back(m);
  }
  int defective = 0;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    INFO("mesh " << i);
    skin::RunContext one, two, three;
    one.threads = 1;
    two.threads = 2;
    three.threads = 3;
    const auto a = verify::check_skin_mesh(skin, meshes[i], {}, one);
    const auto b = verify::check_skin_mesh(skin, meshes[i], {}, two);
    CHECK(a.to_json() == b.to_json());
    CHECK(a.problems == b.problems);
    CHECK(a.to_json() == verify::check_skin_mesh(skin, meshes[i], {}, three).to_json());
    defective += !a.ok();
    if (i > 0) CHECK(a.problems.size() >= 1);
  }
  CHECK(defective == int(meshes.size()) - 1);
}

TEST_CASE("the report is the same when the caller passes the skin's topology, and that topology is used") {
  // verify::SkinCheckOptions::expected_topology (the pipeline passes the K0 topology
  // it computed for the Morse count) must give the report the check computes
  // itself; a wrong one must make the topology check fail, so the option is
  // not ignored.
  const Vec3 c(0, 0, 0);
  const double R = 2.0;
  const skin::SkinSurface skin({{c, 2 * R * R}});
  const geometry::IndexedMesh mesh = icosphere(c, R, 3);
  verify::SkinCheckOptions computed, given, wrong;
  given.expected_topology = skin::dual_complex_topology(skin.mixed_complex());
  wrong.expected_topology = *given.expected_topology;
  wrong.expected_topology->betti2 += 1;  // a cavity that is not there
  const auto a = verify::check_skin_mesh(skin, mesh, computed);
  const auto b = verify::check_skin_mesh(skin, mesh, given);
  CHECK(a.ok());
  CHECK(a.to_json() == b.to_json());
  CHECK(a.problems == b.problems);
  const auto w = verify::check_skin_mesh(skin, mesh, wrong);
  CHECK(!w.topology_matches);
  CHECK(!w.ok());
}

}  // TEST_SUITE

TEST_SUITE("verify") {

TEST_CASE("the on-skin tolerance is 1e-9 Å up to L = 100 Å and 1e-11 L beyond") {
  // Scale-free (issue #7, item 4): a molecule 10x larger gets a 10x larger
  // tolerance, so a check does not fail on rounding alone at large L.
  skin::SkinSurface small({{Vec3(0, 0, 0), 8.0}});
  CHECK(verify::check_skin_mesh(small, icosphere(Vec3(0, 0, 0), 2.0, 3)).vertex_distance_tolerance == 1e-9);
  skin::SkinSurface large({{Vec3(0, 0, 0), 8.0}, {Vec3(2000, 0, 0), 8.0}});
  const double L = large.length_scale();
  REQUIRE(L > 2000);
  const geometry::IndexedMesh two = test::join(icosphere(Vec3(0, 0, 0), 2.0, 3), icosphere(Vec3(2000, 0, 0), 2.0, 3));
  const auto rep = verify::check_skin_mesh(large, two);
  CHECK(rep.vertex_distance_tolerance == doctest::Approx(1e-11 * L));
  CHECK(rep.num_far_vertices == 0);
  CHECK(rep.topology_matches);
}

}  // TEST_SUITE
