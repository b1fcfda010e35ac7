// tests/front/sweep_test.cpp: the whole pipeline on the test configurations of
// papers/front/open_questions.md §11 (one atom, two atoms, a neck with live saddles, the
// three-ball torus, the tetrahedral void, the paper's Figure 4 cube corners):
// the result must be closed, manifold, outward-oriented, free of
// self-intersections, on the skin, and of the expected topology; with the
// local refinement (the default) also free of [L], [U] and restricted-Delaunay
// violations, with every angle above 21.5°, for several height directions.
#include <doctest/doctest.h>

#include <cmath>

#include "front/pipeline.h"
#include "tests/refine/check_expectations.h"
#include "tests/skin/skin_test_util.h"

using namespace skinmesh;

namespace {

MeshResult sweep_and_check(const std::vector<geometry::WeightedPoint>& pts, bool refine = true,
                           Vec3 direction = morse::default_height_direction()) {
  MeshOptions options;
  options.height_direction = direction.normalized();
  options.refine = refine;
  options.checks.check_restricted_delaunay = refine;
  return mesh_skin(pts, options);
}

double w_of(double r, double probe) { return 2 * (r + probe) * (r + probe); }

struct Case {
    const char* name;
  std::vector<geometry::WeightedPoint> pts;
  int expected_chi;
  bool expect_bridges;
};

std::vector<Case> cases() {
  std::vector<Case> cases = {
      {"one atom", {{Vec3(0, 0, 0), w_of(1.6, 1.4)}}, 2, false},
      {"two overlapping atoms", {{Vec3(0, 0, 0), w_of(1.6, 1.4)}, {Vec3(2.4, 0.3, 0.2), w_of(1.7, 1.4)}}, 2, false},
      {"two atoms with a neck", {{Vec3(0, 0, 0), w_of(1.6, 1.4)}, {Vec3(4.5, 0.8, 0.3), w_of(1.6, 1.4)}}, 2, true},
      {"three-ball ring (torus)", test::three_ball_ring(), 0, true},
      {"tetrahedral void (sphere + cavity)", test::tetrahedron_void(), 4, true},
      {"cube corners (Figure 4, genus 5)", test::cube_corners(1.4), -8, true},
  };
  return cases;
}

}  // namespace

TEST_SUITE("front") {

TEST_CASE("sweep without refinement: closed, oriented, embedded meshes of the expected topology") {
  for (const Case& c : cases()) {
    INFO(c.name);
    const MeshResult res = sweep_and_check(c.pts, /*refine=*/false);
    const refine::SkinCheckReport& rep = res.check;
    const front::SweepStats& st = res.sweep;
    test::check_embedded_skin_mesh(rep);
    std::int64_t chi = 0;
    for (auto e : rep.component_euler) chi += e;
    CHECK(chi == c.expected_chi);
    if (c.expect_bridges) CHECK(st.bridges > 0);
    CHECK(st.creations > 0);
    CHECK(st.seals > 0);
    CHECK(res.refinement.flips == 0);
  }
}

TEST_CASE("sweep + refinement: every check passes, for several height directions") {
  const Vec3 directions[] = {morse::default_height_direction(), Vec3(1, 0, 0), Vec3(0.3, 0.5, 0.8),
                             Vec3(-0.7, 0.1, 0.7)};
  for (const Case& c : cases())
    for (const Vec3& d : directions) {
      INFO(c.name);
      INFO("direction " << d.transpose());
      const MeshResult res = sweep_and_check(c.pts, /*refine=*/true, d);
      test::check_every_property(res.check);
      CHECK(res.refinement.L_left == 0);
      CHECK(res.refinement.U_left == 0);
    }
}

}  // TEST_SUITE
