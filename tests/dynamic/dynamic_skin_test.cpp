// tests/dynamic/dynamic_skin_test.cpp: tests of the dynamic-skin baseline
// (dynamic/): the level sets are the skins of the shifted weights (against the
// brute-force skin function), the restricted facets read off the Delaunay
// triangulation agree with a dense search along every Voronoi edge, and both
// variants (growth, static) produce meshes that pass the whole skin check
// (closed, manifold, outward, no self-intersections, topology, on-skin, [L],
// [U], restricted Delaunay, angles). The baseline in the pipeline (local
// frame, singular skins): tests/mesher/dynamic_test.cpp.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/stage_clock.h"
#include "dynamic/dynamic_skin.h"
#include "dynamic/level_set.h"
#include "dynamic/sample_triangulation.h"
#include "geometry/triangulation/delaunay_triangulation.h"
#include "skin/molecule_io.h"
#include "skin/singular_skin.h"
#include "skin/skin_surface.h"
#include "tests/skin/skin_test_util.h"
#include "verify/skin_mesh_check.h"

namespace sd = skinmesh::dynamic;
using skinmesh::Index;
using skinmesh::kInvalidIndex;
using skinmesh::Vec3;
using skinmesh::geometry::WeightedPoint;

namespace {

std::vector<WeightedPoint> test_points(const std::string& name, double probe = 0.0) {
  return skinmesh::skin::weighted_points(skinmesh::skin::read_molecule(std::string(SKINMESH_TEST_DATA) + "/" + name),
                                         probe);
}

/// The baseline's mesh of `points` (the static variant unless `growth`), as
/// the pipeline runs it: in the points' local frame, after the singular-skin
/// refusal; `stats` gets its counts.
skinmesh::geometry::IndexedMesh mesh_of(const std::vector<WeightedPoint>& points, bool growth, sd::DynamicStats& stats,
                                        skinmesh::verify::SkinCheckReport& check) {
  const Vec3 centre = skinmesh::skin::local_frame_centre(points);
  const skinmesh::skin::SkinSurface skin(skinmesh::skin::translated(points, centre));
  skinmesh::skin::require_non_singular(skin);
  sd::DynamicOptions opt;
  opt.growth = growth;
  skinmesh::StageClock clock;
  skinmesh::skin::SkinVertexData data;
  skinmesh::geometry::IndexedMesh mesh = sd::mesh_dynamic(skin, {}, opt, clock, stats, data);
  check = skinmesh::verify::check_skin_mesh(skin, mesh);
  // The vertex data: one entry per vertex, an atom of the input, rho > 0, a cell dimension.
  REQUIRE(data.atom.size() == mesh.positions.size());
  REQUIRE(data.rho.size() == mesh.positions.size());
  REQUIRE(data.patch.size() == mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    CHECK(data.atom[v] >= 0);
    CHECK(static_cast<std::size_t>(data.atom[v]) < points.size());
    CHECK(data.rho[v] > 0);
    CHECK(data.patch[v] <= 3);
  }
  return mesh;
}

void require_clean(const skinmesh::geometry::IndexedMesh& mesh, const sd::DynamicStats& stats,
                   const skinmesh::verify::SkinCheckReport& check, const std::string& what) {
  INFO(what);
  for (const std::string& p : check.problems) INFO(p);
  CHECK(check.ok());
  CHECK(check.topology_matches);
  CHECK(check.num_L_violations == 0);
  CHECK(check.num_U_violations == 0);
  CHECK(check.num_rdt_violations == 0);
  CHECK(check.mesh.min_angle_deg > 21.5);
  CHECK(stats.converged);
  CHECK(mesh.triangles.size() > 100);
}

}  // namespace

TEST_CASE("dynamic: a level set is the skin of the shifted weights (brute force)") {
  // F_c of the skin function f equals the skin of the weights w + 2c: f_c = f - c.
  const std::vector<WeightedPoint> pts = test_points("tetra_void.xyzr", 0.3);
  const skinmesh::skin::SkinSurface skin(pts);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-2.5, 2.5);
  for (const double c : {-0.8, -0.2, 0.0}) {
    std::vector<WeightedPoint> shifted = pts;
    for (auto& p : shifted) p.w += 2 * c;
    const sd::LevelSet level(skin, c);
    for (int k = 0; k < 200; ++k) {
      const Vec3 x(u(rng), u(rng), u(rng));
      Index cell = kInvalidIndex;
      const double v = level.value(x, cell);
      const double brute = skinmesh::test::brute_force_skin_function(shifted, x);
      if (level.outside_hull(x)) {
        CHECK(brute > 0);
        CHECK(v > 0);
      } else {
        CHECK(v == doctest::Approx(brute).epsilon(1e-9).scale(10));
      }
    }
  }
}

TEST_CASE("dynamic: projection and segment crossing land on the level set") {
  // One atom: F_c is the sphere of radius sqrt(w/2 + c) about the centre.
  const std::vector<WeightedPoint> pts = {{Vec3(0.5, -0.25, 1.0), 2 * 1.7 * 1.7}};
  const skinmesh::skin::SkinSurface skin(pts);
  for (const double c : {-1.0, -0.3, 0.0}) {
    const sd::LevelSet level(skin, c);
    const double r = std::sqrt(pts[0].w / 2 + c);
    Vec3 out;
    Index cell = kInvalidIndex;
    double rho = 0;
    REQUIRE(level.project(pts[0].z + Vec3(0.3, 0.9, -0.2), out, cell, rho));
    CHECK((out - pts[0].z).norm() == doctest::Approx(r).epsilon(1e-13));
    CHECK(rho == doctest::Approx(r).epsilon(1e-13));
    const Vec3 far = pts[0].z + Vec3(3, 2, 1);
    Index hint = kInvalidIndex;
    const double v0 = level.value(pts[0].z, hint), v1 = level.value(far, hint);
    REQUIRE(v0 < 0);
    REQUIRE(v1 > 0);
    REQUIRE(level.crossing(pts[0].z, far, v0, v1, out, cell, rho));
    CHECK((out - pts[0].z).norm() == doctest::Approx(r).epsilon(1e-13));
    CHECK((out - pts[0].z).normalized().dot(Vec3(3, 2, 1).normalized()) == doctest::Approx(1.0).epsilon(1e-12));
  }
}

TEST_CASE("dynamic: restricted facets agree with a dense search along the Voronoi edges") {
  // A random sample of the two-atom skin: for every Delaunay facet, count the
  // sign changes of f along its dual Voronoi edge at 400 points; a facet with
  // one change must be restricted, one with none must not be.
  const std::vector<WeightedPoint> pts = test_points("two_atoms.xyzr", 0.2);
  const skinmesh::skin::SkinSurface skin(pts);
  sd::SampleTriangulation st(skin, 0.0, {});
  const sd::LevelSet& level = st.level_set();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int added = 0;
  while (added < 150) {
    const Index atom = rng() % 2;
    const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
    Vec3 x;
    Index cell = kInvalidIndex;
    double rho = 0;
    if (!level.project(pts[atom].z + 1.5 * dir, x, cell, rho)) continue;
    if (st.add_sample(x, cell, rho, true) != kInvalidIndex) ++added;
  }
  const auto& dt = st.triangulation();
  const skinmesh::geometry::IndexedMesh mesh = st.extract();
  std::set<std::array<Index, 3>> restricted;
  std::vector<Index> ids;
  st.extract(&ids);
  for (const auto& t : mesh.triangles) {
    std::array<Index, 3> k = {ids[t[0]], ids[t[1]], ids[t[2]]};
    std::sort(k.begin(), k.end());
    restricted.insert(k);
  }
  int checked = 0, crossing_once = 0;
  dt.for_each_tet([&](Index t) {
    for (int f = 0; f < 4; ++f) {
      const Index n = dt.neighbor(t, f);
      if (n == kInvalidIndex || n < t) continue;
      const Vec3 a = dt.circumcentre(t), b = dt.circumcentre(n);
      int changes = 0;
      Index hint = kInvalidIndex;
      double prev = level.value(a, hint);
      for (int s = 1; s <= 400; ++s) {
        const double v = level.value(a + (b - a) * (s / 400.0), hint);
        if ((v < 0) != (prev < 0)) ++changes;
        prev = v;
      }
      if (changes > 1) continue;  // not decided by a sign test; the refinement's concern
      std::array<Index, 3> k;
      for (int i = 0; i < 3; ++i) k[i] = dt.tet(t)[skinmesh::geometry::DelaunayTriangulation::kFaceVertices[f][i]];
      std::sort(k.begin(), k.end());
      CHECK((changes == 1) == (restricted.count(k) == 1));
      ++checked;
      crossing_once += changes;
    }
  });
  CHECK(checked > 500);
  CHECK(crossing_once > 100);
  // Outward orientation: the mesh encloses a positive volume.
  double volume = 0;
  for (const auto& t : mesh.triangles)
    volume += mesh.positions[t[0]].dot(mesh.positions[t[1]].cross(mesh.positions[t[2]])) / 6;
  CHECK(volume > 0);
}

TEST_CASE("dynamic: the static variant passes every check") {
  // Two atoms (one neck), a void (two components), a ring (genus 1), the
  // paper's Figure 4 configuration (8 atoms at the corners of a cube).
  for (const char* name : {"two_atoms.xyzr", "tetra_void.xyzr", "three_ring.xyzr", "cube_corners.xyzr"}) {
    sd::DynamicStats stats;
    skinmesh::verify::SkinCheckReport check;
    const auto mesh = mesh_of(test_points(name), false, stats, check);
    require_clean(mesh, stats, check, name);
    CHECK(stats.samples.seeds > 0);
    CHECK(stats.steps == 0);
  }
}

TEST_CASE("dynamic: growth from small spheres passes every check") {
  for (const char* name : {"two_atoms.xyzr", "three_ring.xyzr"}) {
    sd::DynamicStats stats;
    skinmesh::verify::SkinCheckReport check;
    const auto mesh = mesh_of(test_points(name), true, stats, check);
    require_clean(mesh, stats, check, name);
    CHECK(stats.steps >= 3);
    CHECK(stats.start_level < 0);
    CHECK(stats.births >= 2);
    CHECK(stats.moves > 0);
  }
}

TEST_CASE("dynamic: options out of range are refused") {
  sd::DynamicOptions opt;
  opt.seed_spacing = 0;
  CHECK_THROWS_AS(sd::validate(opt), std::invalid_argument);
  opt = {};
  opt.max_step_motion = 1.5;
  CHECK_THROWS_AS(sd::validate(opt), std::invalid_argument);
  opt = {};
  opt.rho_floor_fraction = -1;
  CHECK_THROWS_AS(sd::validate(opt), std::invalid_argument);
  CHECK_NOTHROW(sd::validate({}));
}

TEST_CASE("dynamic: lowering the rho floor re-refines the facets it makes violate [U]") {
  // A sparse sample of one sphere meets [U] with a floor of twice the radius;
  // with the floor removed, refine() must find and split the facets that now
  // violate [U] although no operation queued them (regression: the growth's
  // final level once ended with [U] violations left).
  const std::vector<WeightedPoint> pts = {{Vec3(0.1, 0.2, -0.3), 2 * 1.7 * 1.7}};
  const skinmesh::skin::SkinSurface skin(pts);
  sd::SampleTriangulation st(skin, 0.0, {});
  const double r = 1.7;
  st.set_rho_floor(2 * r);
  const int n = 60;
  for (int k = 0; k < n; ++k) {
    const double u = 1 - (2 * k + 1) / double(n), s = std::sqrt(1 - u * u), phi = 2.399963229728653 * k;
    Vec3 x;
    Index cell = kInvalidIndex;
    double rho = 0;
    REQUIRE(st.level_set().project(pts[0].z + r * Vec3(s * std::cos(phi), s * std::sin(phi), u), x, cell, rho));
    st.add_sample(x, cell, rho, true);
  }
  REQUIRE(st.refine(20));
  const std::size_t before = st.triangulation().num_vertices();
  st.set_rho_floor(0);
  CHECK(st.refine(20));
  CHECK(st.stats().U_left == 0);
  CHECK(st.triangulation().num_vertices() > before);
  const skinmesh::verify::SkinCheckReport rep = skinmesh::verify::check_skin_mesh(skin, st.extract());
  for (const std::string& p : rep.problems) INFO(p);
  CHECK(rep.ok());
}
