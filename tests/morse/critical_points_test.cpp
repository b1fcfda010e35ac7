// tests/morse/critical_points_test.cpp: analytic critical points and the Morse
// count #min - #saddle + #max = chi(skin) = 2 chi(K0) (papers/skin/skin_math.md
// §5, §10), against the test vectors of tests/data/skin_vectors.txt.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>

#include "morse/critical_points.h"
#include "morse/morse_smale_complex.h"
#include "skin/dual_complex.h"
#include "skin/mixed_cell_distance.h"
#include "skin/molecule_io.h"
#include "tests/skin/skin_test_util.h"
#include "tests/skin/skin_vectors.h"

using namespace skinmesh;
using morse::CriticalKind;

TEST_SUITE("morse") {

TEST_CASE("two balls, e = y: the critical points of the test vectors") {
  const test::SkinVectors v = test::load_skin_vectors("two_balls");
  REQUIRE(test::same_points(v.points, test::two_balls()));
  const auto& expected = v.counts_for(Vec3(0, 1, 0));
  skin::SkinSurface skin(test::two_balls());
  const auto cps = morse::critical_points(skin, expected.e);
  const auto m = morse::count_critical_points(cps);
  CHECK(m.minima == expected.minima);
  CHECK(m.saddles == expected.saddles);
  CHECK(m.maxima == expected.maxima);
  auto has = [&](CriticalKind k, Vec3 p) {
    for (const auto& c : cps)
      if (c.kind == k && (c.position - p).norm() < 1e-9) return true;
    return false;
  };
  // The file lists every critical point for this direction.
  const auto listed = v.critical_for(expected.e);
  REQUIRE(listed.size() == static_cast<std::size_t>(expected.minima + expected.saddles + expected.maxima));
  for (const auto& c : listed) CHECK(has(static_cast<CriticalKind>(c.index), c.position));
  // Every critical point is on the skin with normal ±e.
  for (const auto& c : cps) {
    const auto s = skin.sample(c.position, c.cell);
    CHECK(std::abs(s.f) < 1e-12);
    CHECK(std::abs(std::abs(s.gradient.normalized().y()) - 1.0) < 1e-12);
  }
  // Upper saddle of a neck: the meridian (towards the balls, along x) ascends.
  for (const auto& c : cps)
    if (c.kind == CriticalKind::Saddle && c.position.y() > 0) {
      CHECK(std::abs(c.ascent.x()) == doctest::Approx(1.0));
      CHECK(std::abs(c.descent.z()) == doctest::Approx(1.0));
    }
}

TEST_CASE("steepest directions raise and lower the height") {
  std::mt19937 rng(11);
  auto cfg = test::random_points(10, 4.0, 0.8, 2.5, rng);
  skin::SkinSurface skin(cfg);
  const Vec3 e = morse::default_height_direction();
  int saddles = 0;
  for (const auto& c : morse::critical_points(skin, e)) {
    if (c.kind != CriticalKind::Saddle) continue;
    ++saddles;
    const double h = 1e-3 * c.rho;
    for (int sg = -1; sg <= 1; sg += 2) {
      Index cell = c.cell;
      const Vec3 up = skin.pull_back(c.position + sg * h * c.ascent, cell);
      const Vec3 dn = skin.pull_back(c.position + sg * h * c.descent, cell);
      CHECK(e.dot(up) > c.height);
      CHECK(e.dot(dn) < c.height);
    }
  }
  CHECK(saddles > 0);
}

TEST_CASE("Morse count equals 2 chi(K0) for several directions and configurations") {
  const unsigned seed = 99;
  INFO("seed = " << seed);
  std::mt19937 rng(seed);
  struct Case {
    const char* name;
    std::vector<geometry::WeightedPoint> pts;
    int expected_chi;  // designed topology (test vectors where listed), -1000 if not designed
  };
  std::vector<Case> cases = {
      {"two balls", test::two_balls(), test::load_skin_vectors("two_balls").euler_skin},
      {"tetrahedron void", test::tetrahedron_void(), test::load_skin_vectors("tetrahedron_void").euler_skin},
      {"three-ball ring", test::three_ball_ring(), test::load_skin_vectors("three_ball_ring").euler_skin},
      {"cube corners (Figure 4)", test::cube_corners(1.4), -1000},
      {"cube corners, closed", test::cube_corners(2.2), -1000},
      {"random 20", test::random_points(20, 6.0, 0.5, 2.5, rng), -1000},
      {"random 30", test::random_points(30, 7.0, 0.5, 2.5, rng), -1000},
  };
  for (const auto& cs : cases) {
    INFO(cs.name);
    skin::SkinSurface skin(cs.pts);
    const auto topo = skin::dual_complex_topology(skin.mixed_complex());
    if (cs.expected_chi != -1000) CHECK(topo.euler_skin() == cs.expected_chi);
    std::vector<Vec3> dirs = {morse::default_height_direction(), Vec3(0, 0.6, 0.8)};
    for (int i = 0; i < 4; ++i) dirs.push_back(test::random_rotation(rng) * Vec3(0, 1, 0));
    for (const Vec3& e : dirs) {
      const auto m = morse::count_critical_points(morse::critical_points(skin, e));
      CHECK(m.euler() == topo.euler_skin());
      CHECK(m.minima >= topo.components());
      CHECK(m.maxima >= topo.components());
    }
  }
}

// Regression (stress cases ring/torus/n30/p0/rt, ring/beads/n12/p1.4/rt,
// ring/neck-overlap1e-4/n8/p3/rt): the atoms of a rotated planar ring are
// coplanar only up to rounding, so the regular triangulation holds sliver
// tetrahedra spanning the hole, with their focus z_T far off the ring and
// w_T larger than the atoms' weights. Such a cell mu_T = (T + z_T)/2 lies
// within max_i |z_i - z_T| / 2 of z_T, closer than the cavity sphere
// |x - z_T| = sqrt(w_T / 2): it holds no skin. Its four facet planes are
// parallel up to rounding, so tested against them with a tolerance the cell
// is an unbounded slab, and a height direction that puts a candidate
// z_T ± sqrt(w_T/2) e into that slab made it a (spurious) extremum.
TEST_CASE("rotated planar rings: no critical point on the cavity sphere of a sliver tetrahedron") {
  std::mt19937 rng(2004);
  int slivers = 0;
  for (int trial = 0; trial < 6; ++trial) {
    INFO("trial = " << trial);
    const int n = trial % 2 ? 8 : 12;
    const double r = 1.7, probe = trial % 3 == 0 ? 0.0 : 1.4;
    const double rw = r + probe;  // neighbours 1.5 r apart: a torus for probe 0
    const double ring = 1.5 * r / (2 * std::sin(M_PI / n));
    const Mat3 rot = test::random_rotation(rng);
    std::vector<geometry::WeightedPoint> pts;
    for (int i = 0; i < n; ++i) {
      const double a = 2 * M_PI * i / n;
      pts.push_back({rot * Vec3(ring * std::cos(a), ring * std::sin(a), 0), 2 * rw * rw});
    }
    skin::SkinSurface skin(pts);
    const skin::MixedComplex& mc = skin.mixed_complex();
    const int chi = skin::dual_complex_topology(mc).euler_skin();
    const Vec3 axis = rot * Vec3::UnitZ();
    for (Index c = 0; c < mc.num_cells(); ++c) {
      const skin::MixedCell& T = mc.cell(c);
      if (T.dim != 3 || T.bounding || !(T.focus_weight > 2 * rw * rw)) continue;
      ++slivers;
      // The direction whose candidate z_T + sqrt(w_T/2) e lies in the plane
      // of the flat cell (the midpoints (z_i + z_T)/2, all at one height along
      // the ring axis): inside the slab of the facet planes.
      const Vec3 za = mc.triangulation().point(T.vertices[0]).z;
      const double rad = std::sqrt(T.focus_weight / 2);
      const double along = axis.dot(za - T.focus) / 2 / rad;  // |along| < 1 since w_T > w_a
      REQUIRE(std::abs(along) < 1);
      const Vec3 side = axis.cross(Vec3(0.3, 0.5, 0.8)).normalized();
      const Vec3 e = along * axis + std::sqrt(1 - along * along) * side;
      const auto cps = morse::critical_points(skin, e);
      double reach = 0;  // max_i |z_i - z_T| / 2: the cell lies in this ball
      for (int i = 0; i < 4; ++i)
        reach = std::max(reach, (mc.triangulation().point(T.vertices[i]).z - T.focus).norm() / 2);
      for (const auto& cp : cps)
        if (cp.cell == c) CHECK((cp.position - T.focus).norm() <= reach * (1 + 1e-9));
      CHECK(morse::count_critical_points(cps).euler() == chi);
    }
    CHECK(morse::count_critical_points(morse::critical_points(skin, morse::default_height_direction())).euler() == chi);
  }
  CHECK(slivers > 0);  // the rotations did produce sliver tetrahedra
}

// Regression (papers/morse/critical_points.md "Flat tetrahedra",
// papers/skin/mixed_complex.md "Flat tetrahedra"): a rotated bcc lattice whose
// square face carries a sliver tetrahedron with a computed focus on the wrong
// side of the face. The triangle cells of the face, tested against the
// interval between their two cofaces' foci in either order, kept the two
// saddles of the face's hyperboloid (Morse sum 0 instead of chi = 2).
TEST_CASE("rotated bcc lattice: a cocircular sliver's focus adds no saddles") {
  const skin::Molecule mol =
      skin::read_molecule(std::string(SKINMESH_TEST_DATA) + "/regression/bcc3_probe0.5_rotated_square_sliver.xyzr");
  REQUIRE(mol.atoms.size() == 91);
  const auto pts = skin::weighted_points(mol, 0.5);
  for (const bool local : {false, true}) {  // as read (145 Å off) and in the local frame
    INFO("local frame = " << local);
    skin::SkinSurface skin(local ? skin::translated(pts, skin::local_frame_centre(pts)) : pts);
    const skin::MixedComplex& mc = skin.mixed_complex();
    const skin::SkinTopology topo = skin::dual_complex_topology(mc);
    REQUIRE(topo.euler_skin() == 2);
    // The case is still there (the construction had to move a flat
    // tetrahedron's focus), and every Voronoi edge through a facet now runs
    // from the focus of one coface to the other's along the outward normal.
    CHECK(mc.num_reordered_foci() > 0);
    int inverted = 0;
    for (Index t = 0; t < mc.num_cells(); ++t) {
      const skin::MixedCell& T = mc.cell(t);
      if (T.dim != 3 || T.bounding) continue;
      const auto faces = mc.planes(t);
      for (std::size_t i = 0; i < faces.size(); ++i) {
        const Index tri = mc.neighbors(t)[i];
        if (mc.cell(tri).dim != 2) continue;
        for (const Index other : mc.neighbors(tri))
          if (other != t && mc.cell(other).dim == 3 &&
              faces[i].normal.dot(mc.cell(other).focus - T.focus) < -1e-9 * mc.length_scale())
            ++inverted;  // outward normal of T at the face points away from the other focus
      }
    }
    CHECK(inverted == 0);
    const Vec3 dirs[] = {morse::default_height_direction(), Vec3(0.3, 1, 0.2), Vec3(1, 0.2, -0.4),
                         Vec3(-0.5, 0.3, 0.9)};
    for (const Vec3& e : dirs) {
      INFO("e = " << e.transpose());
      const auto m = morse::count_critical_points(morse::critical_points(skin, e));
      CHECK(m.euler() == topo.euler_skin());
    }
    const auto m = morse::count_critical_points(morse::critical_points(skin, morse::default_height_direction()));
    CHECK(m.minima == 25);  // the unrotated lattice in the same relative direction: 25/48/25
    CHECK(m.saddles == 48);
    CHECK(m.maxima == 25);
  }
}

TEST_CASE("three-ball ring, e = (0, .6, .8): 3 minima, 6 saddles, 3 maxima") {
  const test::SkinVectors v = test::load_skin_vectors("three_ball_ring");
  REQUIRE(test::same_points(v.points, test::three_ball_ring()));
  const auto& expected = v.counts_for(Vec3(0, 0.6, 0.8));
  skin::SkinSurface skin(test::three_ball_ring());
  const auto m = morse::count_critical_points(morse::critical_points(skin, expected.e));
  CHECK(m.minima == expected.minima);
  CHECK(m.saddles == expected.saddles);
  CHECK(m.maxima == expected.maxima);
}

TEST_CASE("tetrahedron void, e = y: 3 minima, 2 saddles, 3 maxima") {
  const test::SkinVectors v = test::load_skin_vectors("tetrahedron_void");
  REQUIRE(test::same_points(v.points, test::tetrahedron_void()));
  const auto& expected = v.counts_for(Vec3(0, 1, 0));
  skin::SkinSurface skin(test::tetrahedron_void());
  const auto m = morse::count_critical_points(morse::critical_points(skin, expected.e));
  CHECK(m.minima == expected.minima);
  CHECK(m.saddles == expected.saddles);
  CHECK(m.maxima == expected.maxima);
}

}  // TEST_SUITE

TEST_SUITE("morse") {

TEST_CASE("Morse-Smale complex of two balls: the neck saddles join the two balls") {
  skin::SkinSurface skin(test::two_balls());
  const auto ms = morse::build_morse_smale_complex(skin, morse::default_height_direction());
  int saddles = 0;
  for (std::size_t s = 0; s < ms.critical.size(); ++s) {
    if (ms.critical[s].kind != CriticalKind::Saddle) continue;
    ++saddles;
    const Index up0 = ms.arc_end(s, 0), up1 = ms.arc_end(s, 1), dn0 = ms.arc_end(s, 2), dn1 = ms.arc_end(s, 3);
    REQUIRE(up0 != kInvalidIndex);
    REQUIRE(dn0 != kInvalidIndex);
    // Upper saddle (normal +e): its ascending arcs climb the meridian into the
    // two balls' tops; lower saddle: its descending arcs reach both bottoms.
    // (The other pair goes round the neck and may end at one extremum.)
    if (ms.critical[s].sigma > 0) CHECK(up0 != up1);
    if (ms.critical[s].sigma < 0) CHECK(dn0 != dn1);
    CHECK(ms.critical[up0].kind == CriticalKind::Maximum);
    CHECK(ms.critical[up1].kind == CriticalKind::Maximum);
    CHECK(ms.critical[dn0].kind == CriticalKind::Minimum);
    CHECK(ms.critical[dn1].kind == CriticalKind::Minimum);
    // Every traced point lies on the skin, and heights are monotone along the line.
    for (int k = 0; k < 4; ++k) {
      const auto& line = ms.lines[ms.arcs[s][k]];
      for (std::size_t i = 1; i + 1 < line.points.size(); ++i) {
        CHECK(skin.distance_estimate(line.points[i]) < 1e-10);
        const double dh = ms.height_direction.dot(line.points[i + 1] - line.points[i]);
        CHECK(line.direction * dh > -1e-12);
      }
    }
  }
  CHECK(saddles == 2);
  CHECK(ms.cancelled.empty());
}

TEST_CASE("integral lines: each point's recorded cell holds it, the hint the cut tracer starts from") {
  // Crambin at probe 1.4: a few hundred lines across thousands of cells. A
  // wrong cell (one of the walk before the pull-back's last) lies a step's
  // length away, far outside the tolerance.
  const skin::Molecule mol = skin::read_molecule(std::string(SKINMESH_DATA) + "/crambin_1crn.pdb");
  const skin::SkinSurface skin(skin::weighted_points(mol, 1.4));
  const auto ms = morse::build_morse_smale_complex(skin, morse::default_height_direction());
  REQUIRE(ms.lines.size() > 100);
  std::size_t points = 0, outside = 0;
  double worst = 0;
  for (const morse::IntegralLine& line : ms.lines) {
    REQUIRE(line.cells.size() == line.points.size());
    for (std::size_t i = 0; i < line.points.size(); ++i) {
      const double d = skin::cell_distance(skin.mixed_complex(), line.cells[i], line.points[i]);
      worst = std::max(worst, d);
      ++points, outside += d > 1e-6;
    }
  }
  INFO("points " << points << ", farthest outside its cell " << worst << " A");
  CHECK(outside == 0);
}

TEST_CASE("arc contraction: a saddle next to a maximum is cancelled and arcs are rerouted") {
  // Two heavily overlapping balls: the upper neck saddle sits 0.02 Å from the
  // top of the smaller ball (tests/data/two_atoms.xyzr, probe 1.4).
  auto w = [](double r) { return 2 * (r + 1.4) * (r + 1.4); };
  skin::SkinSurface skin({{Vec3(0, 0, 0), w(1.6)}, {Vec3(2.4, 0.3, 0.2), w(1.7)}});
  const auto ms = morse::build_morse_smale_complex(skin, morse::default_height_direction());
  CHECK(ms.cancelled.size() == 2);
  const auto live = ms.live_count();
  CHECK(live.minima == 1);
  CHECK(live.saddles == 0);
  CHECK(live.maxima == 1);
  CHECK(live.euler() == 2);
  for (const auto& pr : ms.cancelled) {
    CHECK(!ms.live[pr[0]]);
    CHECK(!ms.live[pr[1]]);
    // The replacement of a cancelled extremum is a live one of the same kind.
    const Index r = ms.replaced_by[pr[1]];
    REQUIRE(r != kInvalidIndex);
    CHECK(ms.live[r]);
    CHECK(ms.critical[r].kind == ms.critical[pr[1]].kind);
  }
}

TEST_CASE("critical points: the same list on 1, 2 and 3 threads, and no plane kept") {
  // Crambin at probe 0: about 9,000 cells, three blocks of the scan.
  const skin::Molecule mol = skin::read_molecule(std::string(SKINMESH_DATA) + "/crambin_1crn.pdb");
  const skin::SkinSurface skin(skin::weighted_points(mol, 0.0));
  REQUIRE(skin.mixed_complex().num_cells() > 2 * 4096);
  const Vec3 e = morse::default_height_direction();
  const auto one = morse::critical_points(skin, e, 1);
  // The scan tests the candidates with cells and planes it does not keep:
  // what is kept is the cells of the critical points (their curvatures).
  REQUIRE(one.size() > 100);
  CHECK(skin.mixed_complex().made_bytes() <= one.size() * sizeof(skin::MixedCell));
  for (int threads : {2, 3}) {
    const auto many = morse::critical_points(skin, e, threads);
    REQUIRE(many.size() == one.size());
    bool same = true;
    for (std::size_t i = 0; i < one.size(); ++i)
      same = same && one[i].cell == many[i].cell && one[i].position == many[i].position &&
             one[i].kind == many[i].kind && one[i].height == many[i].height;
    CHECK(same);
  }
}

}  // TEST_SUITE
