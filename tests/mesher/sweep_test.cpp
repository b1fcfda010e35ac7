// tests/mesher/sweep_test.cpp: the whole pipeline on the test configurations of
// papers/front/open_questions.md §11 (one atom, two atoms, a neck with live saddles, the
// three-ball torus, the tetrahedral void, the paper's Figure 4 cube corners):
// the result must be closed, manifold, outward-oriented, free of
// self-intersections, on the skin, and of the expected topology; with the
// local refinement (the default) also free of [L], [U] and restricted-Delaunay
// violations, with every angle above 21.5°, for several height directions.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/errors.h"
#include "mesher/pipeline.h"
#include "skin/singular_skin.h"
#include "skin/skin_surface.h"
#include "tests/skin/skin_test_util.h"
#include "tests/verify/check_expectations.h"

using namespace skinmesh;

namespace {

mesher::MeshResult sweep_and_check(const std::vector<geometry::WeightedPoint>& pts, bool refine = true,
                                   Vec3 direction = morse::default_height_direction()) {
  mesher::MeshOptions options;
  options.height_direction = direction.normalized();
  options.refine = refine;
  options.checks.check_restricted_delaunay = refine;
  return mesher::mesh_skin(pts, options);
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

TEST_SUITE("mesher") {

TEST_CASE("sweep without refinement: closed, oriented, embedded meshes of the expected topology") {
  for (const Case& c : cases()) {
    INFO(c.name);
    const mesher::MeshResult res = sweep_and_check(c.pts, /*refine=*/false);
    const verify::SkinCheckReport& rep = res.check;
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

TEST_CASE("the sweep's observer is told of every operation; replaying its faces gives the swept mesh") {
  for (const Case& c : cases()) {
    INFO(c.name);
    mesher::MeshOptions options;
    options.refine = false;
    std::map<front::SweepOperation, std::size_t> count;
    std::set<Index> alive;       // faces replayed from the events
    std::size_t faces_seen = 0;  // faces_size() after the previous event
    bool creations_done = false, creation_after_other = false, closed_at_last = false;
    std::size_t faces_at_last = 0;
    options.sweep.observer = [&](const front::SweepEvent& e) {
      ++count[e.op];
      if (e.op != front::SweepOperation::Creation)
        creations_done = true;
      else if (creations_done)
        creation_after_other = true;
      // No face appears between two events.
      CHECK(e.first_face == faces_seen);
      faces_seen = e.mesh.faces_size();
      for (std::size_t f = e.first_face; f < e.mesh.faces_size(); ++f)
        if (!e.mesh.is_deleted(geometry::Face(static_cast<Index>(f)))) alive.insert(static_cast<Index>(f));
      if (alive.size() != e.mesh.n_faces())  // the operation deleted faces (a re-opened hole)
        std::erase_if(alive, [&](Index f) { return e.mesh.is_deleted(geometry::Face(f)); });
      CHECK(alive.size() == e.mesh.n_faces());
      if (e.op == front::SweepOperation::Creation || e.op == front::SweepOperation::Hold ||
          e.op == front::SweepOperation::Bridge)
        CHECK(e.critical != kInvalidIndex);
      closed_at_last = std::none_of(e.mesh.halfedges().begin(), e.mesh.halfedges().end(),
                                    [&](geometry::Halfedge h) { return e.mesh.is_boundary(h); });
      faces_at_last = e.mesh.n_faces();
    };
    const mesher::MeshResult res = mesher::mesh_skin(c.pts, options);
    test::check_embedded_skin_mesh(res.check);
    CHECK_FALSE(creation_after_other);
    CHECK(count[front::SweepOperation::Creation] == res.sweep.creations);
    CHECK(count[front::SweepOperation::Creep] >= res.sweep.creeps);
    CHECK(count[front::SweepOperation::Bridge] == res.sweep.bridges);
    CHECK(count[front::SweepOperation::Seal] + count[front::SweepOperation::SmallHole] == res.sweep.seals);
    CHECK(closed_at_last);
    CHECK(faces_at_last == res.mesh.triangles.size());
    CHECK(alive.size() == res.mesh.triangles.size());
  }
  CHECK(std::string(front::operation_name(front::SweepOperation::SmallHole)) == "small hole");
}

TEST_CASE("sweep + refinement: every check passes, for several height directions") {
  const Vec3 directions[] = {morse::default_height_direction(), Vec3(1, 0, 0), Vec3(0.3, 0.5, 0.8),
                             Vec3(-0.7, 0.1, 0.7)};
  for (const Case& c : cases())
    for (const Vec3& d : directions) {
      INFO(c.name);
      INFO("direction " << d.transpose());
      const mesher::MeshResult res = sweep_and_check(c.pts, /*refine=*/true, d);
      test::check_every_property(res.check);
      CHECK(res.refinement.L_left == 0);
      CHECK(res.refinement.U_left == 0);
    }
}

TEST_CASE("translation by 1e6 Å changes nothing but the coordinates") {
  // Centres on a grid of 2^-10 Å, so that adding the translation is exact:
  // the mesher works in the local frame of the points, hence the same
  // triangles, and positions that differ by the translation up to the
  // rounding of adding it back (half an ulp at 1e6 Å, 6e-11 Å).
  const Vec3 t(1e6, 1e6, -1e6);
  for (const Case& c : cases()) {
    INFO(c.name);
    std::vector<geometry::WeightedPoint> at_origin = c.pts, far = c.pts;
    for (std::size_t i = 0; i < at_origin.size(); ++i) {
      for (int k = 0; k < 3; ++k) at_origin[i].z[k] = std::ldexp(std::round(std::ldexp(c.pts[i].z[k], 10)), -10);
      far[i].z = at_origin[i].z + t;
      REQUIRE(far[i].z - t == at_origin[i].z);  // exact
    }
    const mesher::MeshResult a = sweep_and_check(at_origin), b = sweep_and_check(far);
    test::check_every_property(b.check);
    INFO("frame " << a.frame_centre.transpose() << " / " << b.frame_centre.transpose() << " tris "
                  << a.mesh.triangles.size() << " " << b.mesh.triangles.size());
    REQUIRE(a.mesh.triangles == b.mesh.triangles);
    REQUIRE(a.mesh.positions.size() == b.mesh.positions.size());
    double worst = 0;
    for (std::size_t i = 0; i < a.mesh.positions.size(); ++i)
      worst = std::max(worst, (b.mesh.positions[i] - t - a.mesh.positions[i]).cwiseAbs().maxCoeff());
    CHECK(worst <= 1.2e-10);
    CHECK(b.frame_centre - a.frame_centre == t);
  }
}

}  // TEST_SUITE

TEST_CASE("singular skins are refused with the atoms named; a gap of 2e-4 Å still meshes") {
  // Two balls of radius sqrt(8) Å (r = 1.5, probe 0.5) at distance sqrt(32) Å
  // touch exactly: the skin is a double cone there. With a third atom far away
  // (so that the touching pair is not atoms #1 and #2 by accident of order).
  const double w = skin::atom_weight(1.5, 0.5);
  const std::vector<geometry::WeightedPoint> touching = {{Vec3(20, 0, 0), w}, {Vec3(0, 0, 0), w}, {Vec3(4, 4, 0), w}};
  mesher::MeshOptions options;
  try {
    (void)mesher::mesh_skin(touching, options);
    FAIL("a skin with a cone point was meshed");
  } catch (const InputError& e) {
    const std::string what = e.what();
    CHECK(what.find("singular skin") != std::string::npos);
    CHECK(what.find("#2 and #3") != std::string::npos);
  }
  // The same, rotated by an arbitrary rotation (the tie is then broken by
  // rounding only): still refused.
  const Mat3 rot = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<geometry::WeightedPoint> rotated = touching;
  for (auto& p : rotated) p.z = rot * p.z + Vec3(13.25, -7.5, 101.0);
  CHECK_THROWS_AS((void)mesher::mesh_skin(rotated, options), InputError);
  // Moved apart by 0.05 Å in z (a gap of about 2e-4 Å between the balls): two
  // spheres, every check passed.
  std::vector<geometry::WeightedPoint> gap = touching;
  gap[2].z.z() = 0.05;
  const mesher::MeshResult res = mesher::mesh_skin(gap, options);
  REQUIRE(res.checked);
  test::check_every_property(res.check);
  CHECK(res.expected_topology.components() == 3);
}

TEST_CASE("the singular-skin test on several threads refuses with the error one loop raises") {
  // A 12 x 12 x 12 lattice of balls 6 Å apart (radius sqrt(8) Å: gaps of
  // 0.34 Å, far from singular) and two extra balls, each touching a corner
  // ball from outside: two cone points, in cells far apart in the complex's
  // numbering, which spans several blocks of the parallel test.
  const double w = skin::atom_weight(1.5, 0.5);
  constexpr int k = 12;
  std::vector<geometry::WeightedPoint> points;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      for (int l = 0; l < k; ++l) points.push_back({Vec3(6.0 * i, 6.0 * j, 6.0 * l), w});
  const double far = 6.0 * (k - 1);
  points.push_back({Vec3(far + 4, far + 4, far), w});
  points.push_back({Vec3(-4, -4, 0), w});
  const skin::SkinSurface skin(points, 2);
  REQUIRE(skin.mixed_complex().num_cells() > 2 * 16384);  // three blocks at least
  std::vector<std::string> messages;
  for (int threads : {1, 2, 4}) {
    try {
      skin::require_non_singular(skin, threads);
      FAIL("a skin with two cone points passed, threads = " << threads);
    } catch (const InputError& e) {
      messages.push_back(e.what());
    }
  }
  REQUIRE(messages.size() == 3);
  CHECK(messages[0].find("singular skin") != std::string::npos);
  const bool names_a_pair =
      messages[0].find("#1 and #1730") != std::string::npos || messages[0].find("#1728 and #1729") != std::string::npos;
  CHECK_MESSAGE(names_a_pair, messages[0]);
  CHECK(messages[1] == messages[0]);
  CHECK(messages[2] == messages[0]);
}
