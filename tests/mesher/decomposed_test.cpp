// tests/mesher/decomposed_test.cpp: the decomposed sweep end to end
// (decompose/decomposed.h, papers/decompose/README.md): bundled molecules cut
// into many forced slabs, each slab swept from its lower cut curves, the bands
// under the cuts closed by strips and the slabs glued along the shared
// samples, then refined and checked like one sweep's mesh. The seams get no
// special treatment from the verifier: every property (closed, manifold,
// outward, embedded, on the skin, the expected topology per component,
// [L], [U], restricted Delaunay, angles above 21.5°) must hold across them.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "decompose/decomposed.h"
#include "mesher/pipeline.h"
#include "morse/morse_smale_complex.h"
#include "refine/local_refinement.h"
#include "skin/molecule_io.h"
#include "skin/skin_surface.h"
#include "tests/verify/check_expectations.h"
#include "verify/skin_mesh_check.h"

using namespace skinmesh;

namespace {

double mesh_area(const geometry::IndexedMesh& m) {
  double a = 0;
  for (const auto& t : m.triangles)
    a += 0.5 * (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]).norm();
  return a;
}

/// The mesh as a set of oriented triangles by their corners' positions, each
/// started at its lexicographically smallest corner, sorted: equal for two
/// meshes that differ only in the order of their vertices and triangles.
std::vector<std::array<double, 9>> triangle_set(const geometry::IndexedMesh& m) {
  auto less = [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end());
  };
  std::vector<std::array<double, 9>> out;
  out.reserve(m.triangles.size());
  for (const auto& t : m.triangles) {
    int first = 0;
    for (int k = 1; k < 3; ++k)
      if (less(m.positions[t[k]], m.positions[t[first]])) first = k;
    std::array<double, 9> c{};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) c[3 * k + d] = m.positions[t[(first + k) % 3]][d];
    out.push_back(c);
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// `ms` with the first saddle's integral line left without an end (as a
/// line whose trace failed): component_groups() must refuse to vouch for it.
morse::MorseSmaleComplex with_an_open_line(morse::MorseSmaleComplex ms) {
  for (morse::IntegralLine& line : ms.lines)
    if (line.saddle != kInvalidIndex) {
      line.end = kInvalidIndex;
      break;
    }
  return ms;
}

struct Case {
  const char* file;
  double probe;
  std::size_t min_slabs;  ///< slabs the cut choice finds today out of 8 asked (fewer is a regression)
};

/// The case's bundled molecule.
skin::Molecule read_case(const Case& c) { return skin::read_molecule(std::string(SKINMESH_DATA) + "/" + c.file); }

/// The pipeline's options at the case's probe, in 8 forced slabs at the
/// targets of equal heights: the cases below are the sweeps at the cuts
/// whose failures they once showed (the cut choice by predicted work has
/// its own test).
mesher::MeshOptions eight_slabs(const Case& c) {
  mesher::MeshOptions options;
  options.probe_radius = c.probe;
  options.decomposition.slabs = 8;
  options.decomposition.balance_work = false;
  return options;
}

/// The bundled molecule `file` at `probe` in `slabs` detoured slabs (every
/// cut around the critical points it meets) on 2 threads: every check
/// passes, at least `at_least` slabs are kept, and no cut is dropped for a
/// reason containing `not_why` (the failure a regression case once showed).
mesher::MeshResult detoured_slabs(const char* file, double probe, int slabs, const std::string& not_why,
                                  std::size_t at_least = 0) {
  mesher::MeshOptions options;
  options.probe_radius = probe;
  options.decomposition.slabs = slabs;
  options.decomposition.detours = true;
  options.threads = 2;
  mesher::MeshResult res = mesher::mesh_skin(read_case(Case{file, probe, 0}), options);
  for (const decompose::DroppedCut& d : res.dropped_cuts) {
    CAPTURE(d.why);
    CHECK(d.why.find(not_why) == std::string::npos);
  }
  CHECK(res.slabs >= at_least);
  REQUIRE(res.checked);
  test::check_every_property(res.check);
  return res;
}

}  // namespace

TEST_SUITE("mesher") {

TEST_CASE("decomposed sweep: bundled molecules in 8 forced slabs pass every check across the seams") {
  // gramicidin A at probe 0 left a parked rim that turns back on itself
  // (no outward strip until the rims' sharp corners are winged); src kinase
  // at probe 1.4 pinched off a hole of four parked vertices in a band (a
  // second rim under one curve until such holes are sealed).
  for (const Case& c : {Case{"crambin_1crn.pdb", 1.4, 8}, Case{"gramicidinA_1grm_model1.pdb", 1.4, 8},
                        Case{"gramicidinA_1grm_model1.pdb", 0.0, 6}, Case{"src_kinase_2src.pdb", 1.4, 8},
                        Case{"ligand_2zmm.pdb", 0.0, 8}, Case{"crambin_1crn.pdb", 0.0, 3}}) {
    CAPTURE(c.file);
    CAPTURE(c.probe);
    const skin::Molecule mol = read_case(c);
    mesher::MeshOptions options = eight_slabs(c);
    const mesher::MeshResult res = mesher::mesh_skin(mol, options);
    CHECK(res.slabs >= c.min_slabs);
    REQUIRE(res.cut_heights.size() + 1 == res.slabs);
    for (std::size_t i = 1; i < res.cut_heights.size(); ++i) CHECK(res.cut_heights[i - 1] < res.cut_heights[i]);
    CHECK(res.sweep.parked > 0);
    // The costs name every slab of the glued mesh, bottom to top; the slabs
    // hold most of its triangles (the bands and the refinement add the rest).
    REQUIRE(res.decomposition_costs.slabs.size() == res.slabs);
    std::size_t slab_triangles = 0;
    for (const decompose::SlabCost& cost : res.decomposition_costs.slabs) {
      CHECK(cost.triangles > 0);
      CHECK(cost.seconds >= 0);
      slab_triangles += cost.triangles;
    }
    CHECK(slab_triangles > 0.8 * static_cast<double>(res.mesh.triangles.size()));
    CHECK(slab_triangles < 1.1 * static_cast<double>(res.mesh.triangles.size()));
    REQUIRE(res.checked);
    test::check_every_property(res.check);
    if (c.probe > 0) {
      // The same skin as one sweep's mesh: the areas of two inscribed
      // meshes of edge lengths within [L]/[U] agree closely.
      options.decomposition.slabs = 1;
      const mesher::MeshResult one = mesher::mesh_skin(mol, options);
      CHECK(one.slabs == 1);
      CHECK(one.cut_heights.empty());
      CHECK(one.decomposition_costs.slabs.empty());
      CHECK(mesh_area(res.mesh) == doctest::Approx(mesh_area(one.mesh)).epsilon(2e-3));
    }
  }
}

TEST_CASE("decomposed sweep with detoured cuts: slabs start from and park at cuts that pass around balls") {
  // The cuts pass around the critical points they meet (morse::cut_curves):
  // the slab above a cluster that goes up starts from the arcs below it and
  // meshes the whole cluster; the slab below parks at those arcs. Every
  // property must hold across such seams too, and the mesh must not depend
  // on the thread count.
  // Crambin at probe 0 dropped a cut when its slab parked around a live
  // saddle 0.05 Å under it instead of bridging it (two curves, one rim:
  // Region::holds_before_parking); gramicidin A at probe 0 dropped two, one
  // where the cut ran along the arcs of a cluster that went down (now up:
  // decompose::choose_cuts). Neither may drop a cut now.
  std::size_t detoured_cuts = 0, most_balls = 0;
  for (const Case& c :
       {Case{"crambin_1crn.pdb", 1.4, 8}, Case{"crambin_1crn.pdb", 0.0, 8}, Case{"gramicidinA_1grm_model1.pdb", 0.0, 8},
        Case{"ligand_1hpv_amprenavir.pdb", 0.0, 7}, Case{"hivprotease_xk263_1hvr.pdb", 1.4, 7}}) {
    CAPTURE(c.file);
    CAPTURE(c.probe);
    const skin::Molecule mol = read_case(c);
    mesher::MeshOptions options = eight_slabs(c);
    options.decomposition.detours = true;
    options.threads = 1;
    const mesher::MeshResult res = mesher::mesh_skin(mol, options);
    CHECK(res.slabs >= c.min_slabs);
    if (c.min_slabs == 8) CHECK(res.dropped_cuts.empty());
    REQUIRE(res.cut_balls.size() == res.cut_heights.size());
    for (std::size_t balls : res.cut_balls) {
      if (balls > 0) ++detoured_cuts;
      most_balls = std::max(most_balls, balls);
    }
    REQUIRE(res.checked);
    test::check_every_property(res.check);
    options.threads = 2;
    const mesher::MeshResult two = mesher::mesh_skin(mol, options);
    CHECK(two.cut_heights == res.cut_heights);
    CHECK(two.mesh.positions == res.mesh.positions);
    CHECK(two.mesh.triangles == res.mesh.triangles);
  }
  MESSAGE("detoured cuts " << detoured_cuts << ", most balls in one cut " << most_balls);
  CHECK(detoured_cuts >= 10);
  CHECK(most_balls >= 10);
}

TEST_CASE("decomposed sweep: level cuts where the skin admits them, detoured cuts where it does not") {
  // The default (DecompositionOptions::detour_fallback): a target with an
  // admissible level cut keeps it; a target without one gets a detoured cut
  // that fits between its neighbours. Where every target has a level cut,
  // the mesh is that of level cuts alone.
  mesher::MeshOptions options;
  CHECK(options.decomposition.detour_fallback);
  options.threads = 2;
  options.decomposition.slabs = 8;
  {
    const skin::Molecule mol = read_case(Case{"crambin_1crn.pdb", 0.0, 0});
    options.probe_radius = 0;
    options.decomposition.detour_fallback = false;
    const mesher::MeshResult level = mesher::mesh_skin(mol, options);
    options.decomposition.detour_fallback = true;
    const mesher::MeshResult both = mesher::mesh_skin(mol, options);
    CHECK(level.slabs < 8);  // crambin at probe 0 admits few level cuts
    CHECK(both.slabs > level.slabs);
    for (double h : level.cut_heights)
      CHECK(std::find(both.cut_heights.begin(), both.cut_heights.end(), h) != both.cut_heights.end());
    CHECK(std::any_of(both.cut_balls.begin(), both.cut_balls.end(), [](std::size_t b) { return b > 0; }));
    REQUIRE(both.checked);
    test::check_every_property(both.check);
  }
  {
    const skin::Molecule mol = read_case(Case{"crambin_1crn.pdb", 1.4, 0});
    options.probe_radius = 1.4;
    options.decomposition.detour_fallback = false;
    const mesher::MeshResult level = mesher::mesh_skin(mol, options);
    options.decomposition.detour_fallback = true;
    const mesher::MeshResult both = mesher::mesh_skin(mol, options);
    REQUIRE(level.slabs == 8);
    CHECK(both.cut_heights == level.cut_heights);
    CHECK(both.mesh.positions == level.mesh.positions);
    CHECK(both.mesh.triangles == level.mesh.triangles);
  }
}

TEST_CASE("decomposed sweep: the automatic slab count follows the atoms, then their root, within its bounds") {
  decompose::DecompositionOptions opt;
  CHECK(decompose::automatic_slabs(0, opt) == 1);
  CHECK(decompose::automatic_slabs(327, opt) == 1);      // crambin: one sweep
  CHECK(decompose::automatic_slabs(10123, opt) == 4);    // maltoporin
  CHECK(decompose::automatic_slabs(7800, opt) == 3);     // the linear rule up to 7,812 atoms
  CHECK(decompose::automatic_slabs(101230, opt) == 11);  // ten maltoporins: sqrt(126.5)
  CHECK(decompose::automatic_slabs(218760, opt) == 17);  // the shell of bench/assembly.py --t 1
  CHECK(decompose::automatic_slabs(1214760, opt) == 39);
  CHECK(decompose::automatic_slabs(100000000, opt) == opt.max_slabs);
  opt.atoms_per_slab = 1;  // the root rule alone
  CHECK(decompose::automatic_slabs(40000, opt) == 7);
  opt.atoms_per_root_slab = 0;  // the linear rule alone
  CHECK(decompose::automatic_slabs(40000, opt) == opt.max_slabs);
  opt.atoms_per_slab = 2500;
  CHECK(decompose::automatic_slabs(101230, opt) == 40);
  opt.atoms_per_slab = 100;
  CHECK(decompose::automatic_slabs(327, opt) == 3);  // (the root rule off above)
}

TEST_CASE("decomposed sweep: groups of whole skin components are swept on their own") {
  // Two copies of crambin 60 Å apart at probe 1.4 (two bodies), and crambin
  // at probe 0 (one body and its cavities). Each group's sweep sees only its
  // own critical points; the appended meshes must pass every check, as one
  // sweep of everything does, with the same components.
  skin::Molecule two = skin::read_molecule(std::string(SKINMESH_DATA) + "/crambin_1crn.pdb");
  const std::size_t n = two.atoms.size();
  for (std::size_t i = 0; i < n; ++i) {
    skin::Atom a = two.atoms[i];
    a.centre += Vec3(60, 0, 0);
    two.atoms.push_back(a);
  }
  const skin::Molecule one = skin::read_molecule(std::string(SKINMESH_DATA) + "/crambin_1crn.pdb");
  struct Input {
    const skin::Molecule* mol;
    double probe;
  };
  for (const Input& in : {Input{&two, 1.4}, Input{&one, 0.0}}) {
    CAPTURE(in.probe);
    mesher::MeshOptions options;
    options.probe_radius = in.probe;
    options.threads = 1;
    const mesher::MeshResult res = mesher::mesh_skin(*in.mol, options);
    REQUIRE(res.checked);
    test::check_every_property(res.check);
    CHECK(res.components_fallback.empty());
    CHECK(res.slabs == 1);
    const std::size_t groups = res.decomposition_costs.components.size();
    CHECK(groups >= 2);
    CHECK(groups <= res.check.mesh.components.size());
    std::size_t group_triangles = 0;
    for (const decompose::SlabCost& g : res.decomposition_costs.components) {
      CHECK(g.triangles > 0);
      group_triangles += g.triangles;
    }
    CHECK(group_triangles > 0.8 * static_cast<double>(res.mesh.triangles.size()));

    // One sweep of the whole skin: the same components and Euler
    // characteristics, the same area to the meshes' accuracy.
    options.decomposition.components = false;
    const mesher::MeshResult whole = mesher::mesh_skin(*in.mol, options);
    REQUIRE(whole.checked);
    test::check_every_property(whole.check);
    CHECK(whole.decomposition_costs.components.empty());
    CHECK(res.check.component_euler == whole.check.component_euler);
    CHECK(mesh_area(res.mesh) == doctest::Approx(mesh_area(whole.mesh)).epsilon(2e-3));

    // The groups depend on the input only.
    options.decomposition.components = true;
    options.threads = 2;
    const mesher::MeshResult two_threads = mesher::mesh_skin(*in.mol, options);
    CHECK(two_threads.mesh.positions == res.mesh.positions);
    CHECK(two_threads.mesh.triangles == res.mesh.triangles);
    CHECK(two_threads.vertex_data.atom == res.vertex_data.atom);

    // Each group refined on its own, its output written in its place, gives
    // the triangles that refining the glued groups as one mesh gives (an
    // observer of the stages keeps them glued): nothing in the refinement or
    // the angle improvement reads another component's mesh. Each group's
    // vertices and triangles are contiguous, in group order.
    int stages_seen = 0;
    options.observers.stage_end = [&](const char*, const skin::SkinSurface&, const geometry::SurfaceMesh&) {
      ++stages_seen;
    };
    const mesher::MeshResult glued = mesher::mesh_skin(*in.mol, options);
    options.observers.stage_end = nullptr;
    CHECK(stages_seen == 3);
    REQUIRE(glued.checked);
    test::check_every_property(glued.check);
    CHECK(glued.mesh.triangles.size() == res.mesh.triangles.size());
    CHECK(triangle_set(glued.mesh) == triangle_set(res.mesh));
    CHECK(glued.refinement.insertions == res.refinement.insertions);
    CHECK(glued.refinement.contractions == res.refinement.contractions);
    CHECK(glued.angle_improvement.moves == res.angle_improvement.moves);
    // Blocks: places where every triangle before uses only vertices below
    // every vertex of every triangle after. Groups written one after the
    // other give at least one block per group.
    const auto& T = res.mesh.triangles;
    std::vector<Index> suffix_min(T.size() + 1, std::numeric_limits<Index>::max());
    for (std::size_t t = T.size(); t-- > 0;) suffix_min[t] = std::min({suffix_min[t + 1], T[t][0], T[t][1], T[t][2]});
    std::size_t blocks = 1;
    Index prefix_max = 0;
    for (std::size_t t = 0; t + 1 < T.size(); ++t) {
      prefix_max = std::max({prefix_max, T[t][0], T[t][1], T[t][2]});
      if (prefix_max < suffix_min[t + 1]) ++blocks;
    }
    CHECK(blocks >= groups);
  }
}

TEST_CASE("morse: component groups follow the integral lines, and refuse what they cannot vouch for") {
  const auto complex_of = [](const std::vector<geometry::WeightedPoint>& pts) {
    const skin::SkinSurface skin(pts);
    return morse::build_morse_smale_complex(skin, morse::default_height_direction());
  };
  {
    // Two separate balls: two spheres without saddles (a minimum and a
    // maximum each), which form one group together.
    const morse::MorseSmaleComplex ms = complex_of({{Vec3(0, 0, 0), 4.0}, {Vec3(20, 0, 0), 4.0}});
    REQUIRE(ms.critical.size() == 4);
    const morse::ComponentGroups g = morse::component_groups(ms);
    CHECK(g.count == 1);
    CHECK(g.group == std::vector<Index>(4, 0));
  }
  // Two separate dumbbells lying across the height direction: each has two
  // minima, two saddles (under and over its neck) and two maxima, all
  // linked by the saddles' lines: one group per dumbbell.
  const morse::MorseSmaleComplex ms =
      complex_of({{Vec3(0, 0, 0), 4.0}, {Vec3(3.5, 0, 0), 4.0}, {Vec3(40, 0, 0), 4.0}, {Vec3(43.5, 0, 0), 4.0}});
  REQUIRE(ms.critical.size() == 12);
  const morse::ComponentGroups g = morse::component_groups(ms);
  REQUIRE(g.count == 2);
  for (std::size_t i = 0; i < ms.critical.size(); ++i) {
    CAPTURE(i);
    CHECK(g.group[i] == (ms.critical[i].position.x() < 20 ? g.group[0] : 1 - g.group[0]));
  }
  // A line without an end: the partition is refused (one group).
  CHECK(morse::component_groups(with_an_open_line(ms)).count == 1);
}

TEST_CASE("decomposed sweep: the default slab count follows the largest group of components") {
  const auto complex_of = [](const std::vector<geometry::WeightedPoint>& pts) {
    const skin::SkinSurface skin(pts);
    return morse::build_morse_smale_complex(skin, morse::default_height_direction());
  };
  CHECK(mesher::MeshOptions{}.decomposition.slabs == 0);  // automatic unless asked
  decompose::DecompositionOptions opt;
  opt.atoms_per_slab = 1;  // a slab per atom: small inputs tell the rule
  opt.atoms_per_root_slab = 0;
  const front::SweepOptions sweep;
  // A dumbbell (6 critical points, linked by its saddles' lines) and two
  // separate balls (a minimum and a maximum each, one group together): the
  // dumbbell's group holds 6 of the 10 points, so the 6 atoms count as 3.6.
  const morse::MorseSmaleComplex uneven =
      complex_of({{Vec3(0, 0, 0), 4.0}, {Vec3(3.5, 0, 0), 4.0}, {Vec3(40, 0, 0), 4.0}, {Vec3(60, 0, 0), 4.0}});
  REQUIRE(uneven.critical.size() == 10);
  REQUIRE(morse::component_groups(uneven).count == 2);
  CHECK(decompose::automatic_slabs(6, uneven, opt, sweep) == 4);
  CHECK(decompose::automatic_slabs(6000, uneven, decompose::DecompositionOptions{}, sweep) == 1);  // 3,600 atoms: 1
  CHECK(decompose::automatic_slabs(6500, uneven, decompose::DecompositionOptions{}, sweep) == 2);  // 3,900 atoms: 2
  // Two equal dumbbells: no group holds more than half; the groups share the threads.
  const morse::MorseSmaleComplex even =
      complex_of({{Vec3(0, 0, 0), 4.0}, {Vec3(3.5, 0, 0), 4.0}, {Vec3(40, 0, 0), 4.0}, {Vec3(43.5, 0, 0), 4.0}});
  REQUIRE(morse::component_groups(even).count == 2);
  CHECK(decompose::automatic_slabs(4, even, opt, sweep) == 1);
  // One group (here a refused partition): every atom counts.
  const morse::MorseSmaleComplex broken = with_an_open_line(even);
  REQUIRE(morse::component_groups(broken).count == 1);
  CHECK(decompose::automatic_slabs(4, broken, opt, sweep) == 4);
  // One front where groups are off or someone follows the sweep.
  decompose::DecompositionOptions one_front = opt;
  one_front.components = false;
  CHECK(decompose::automatic_slabs(6, uneven, one_front, sweep) == 1);
  front::SweepOptions traced;
  traced.trace = [](const std::string&) {};
  CHECK(decompose::automatic_slabs(6, uneven, opt, traced) == 1);
  front::SweepOptions observed;
  observed.observer = [](const front::SweepEvent&) {};
  CHECK(decompose::automatic_slabs(4, broken, opt, observed) == 1);
}

TEST_CASE("decomposed sweep: the detoured cuts are traced on the threads and the same for every count") {
  // choose_cuts traces each target's first admitted candidate on the
  // threads, then walks the targets in order, tracing on where that
  // candidate is too near the cut below; 24 slabs of crambin at probe 0 put
  // the targets close together.
  const skin::Molecule mol = skin::read_molecule(std::string(SKINMESH_DATA) + "/crambin_1crn.pdb");
  const skin::SkinSurface skin(skin::weighted_points(mol, 0.0));
  const morse::MorseSmaleComplex ms = morse::build_morse_smale_complex(skin, Vec3(0.36, -0.48, 0.8));
  decompose::DecompositionOptions opt;
  opt.slabs = 24;
  opt.detours = true;
  const front::SweepOptions sweep;
  skin::RunContext run;
  run.threads = 1;
  const std::vector<decompose::Cut> one = decompose::choose_cuts(skin, ms, opt, sweep, run);
  REQUIRE(one.size() >= 12);
  for (std::size_t k = 1; k < one.size(); ++k) CHECK(one[k].height > one[k - 1].height);
  for (int threads : {2, 3}) {
    CAPTURE(threads);
    run.threads = threads;
    const std::vector<decompose::Cut> cuts = decompose::choose_cuts(skin, ms, opt, sweep, run);
    REQUIRE(cuts.size() == one.size());
    for (std::size_t k = 0; k < cuts.size(); ++k) {
      CHECK(cuts[k].height == one[k].height);
      REQUIRE(cuts[k].curves.size() == one[k].curves.size());
      for (std::size_t i = 0; i < cuts[k].curves.size(); ++i)
        CHECK(cuts[k].curves[i].points == one[k].curves[i].points);
    }
  }
}

TEST_CASE("decomposed sweep: the mesh is the same for every thread count") {
  const skin::Molecule mol = skin::read_molecule(std::string(SKINMESH_DATA) + "/crambin_1crn.pdb");
  mesher::MeshOptions options;
  options.decomposition.slabs = 8;
  options.threads = 1;
  const mesher::MeshResult one = mesher::mesh_skin(mol, options);
  REQUIRE(one.slabs > 2);
  for (int threads : {2, 3}) {
    CAPTURE(threads);
    options.threads = threads;
    const mesher::MeshResult res = mesher::mesh_skin(mol, options);
    CHECK(res.cut_heights == one.cut_heights);
    CHECK(res.mesh.positions == one.mesh.positions);
    CHECK(res.mesh.triangles == one.mesh.triangles);
  }
}

TEST_CASE("decomposed sweep: the regions are refined on the threads before the glue, their seams after") {
  // DecompositionOptions::refine_regions: each region's mesh is refined on
  // its own thread with its boundary kept, so the glue still finds the cut
  // samples and the rims; the pass over the glued mesh then has the seams
  // left. The glued mesh is closed and the same for every thread count,
  // and after that pass every property holds.
  const skin::Molecule mol = skin::read_molecule(std::string(SKINMESH_DATA) + "/src_kinase_2src.pdb");
  const skin::SkinSurface skin(skin::weighted_points(mol, 1.4));
  const morse::MorseSmaleComplex ms = morse::build_morse_smale_complex(skin, morse::default_height_direction());
  decompose::DecompositionOptions opt;
  opt.slabs = 8;
  const std::vector<decompose::Cut> cuts = decompose::choose_cuts(skin, ms, opt, {});
  REQUIRE(cuts.size() >= 5);
  opt.refine_regions = true;
  skin::RunContext run;
  run.threads = 1;
  const decompose::DecomposedSweep one = decompose::sweep_decomposed(skin, ms, cuts, opt, {}, run);
  REQUIRE(one.cut_heights.size() >= 4);
  CHECK(one.region_refinement.flips > 1000);
  CHECK(one.region_refinement.insertions > 100);
  for (geometry::Vertex v : one.sweep.mesh.vertices()) REQUIRE_FALSE(one.sweep.mesh.is_boundary(v));
  // The pass over the glued mesh: the seams (the bands' strips and the
  // triangles next to the regions' boundaries) refined as well.
  geometry::SurfaceMesh glued = one.sweep.mesh;
  const refine::RefineStats seams = refine::refine_mesh(skin, glued, {}, run);
  CHECK(seams.L_left + seams.U_left == 0);
  glued.garbage_collection();
  test::check_every_property(verify::check_skin_mesh(skin, glued.to_indexed_mesh()));
  // The same pass started from the seams (DecomposedSweep::seams: the
  // bands' triangles and those around their corners) finds the same work:
  // away from the seams the regions left nothing to flip or refine.
  REQUIRE(!one.seams.empty());
  CHECK(one.seams.size() < one.sweep.mesh.n_faces() / 5);
  geometry::SurfaceMesh from_seams = one.sweep.mesh;
  const refine::RefineStats seeded = refine::refine_seams(skin, from_seams, one.seams, {}, run);
  CHECK(seeded.L_left + seeded.U_left == 0);
  CHECK(seeded.flips == seams.flips);
  CHECK(seeded.insertions == seams.insertions);
  CHECK(seeded.contractions == seams.contractions);
  from_seams.garbage_collection();
  const geometry::IndexedMesh s = from_seams.to_indexed_mesh(), g = glued.to_indexed_mesh();
  CHECK(s.positions == g.positions);
  CHECK(s.triangles == g.triangles);
  for (int threads : {2, 3}) {
    CAPTURE(threads);
    run.threads = threads;
    const decompose::DecomposedSweep more = decompose::sweep_decomposed(skin, ms, cuts, opt, {}, run);
    const geometry::IndexedMesh a = one.sweep.mesh.to_indexed_mesh(), b = more.sweep.mesh.to_indexed_mesh();
    CHECK(b.positions == a.positions);
    CHECK(b.triangles == a.triangles);
  }
}

TEST_CASE("regression: a band with no outward strip drops its cut, random atoms at probe 0.5") {
  // A stress case whose cut crosses a nearly level stretch of skin: the
  // parked rim juts towards the curve there, so no strip of outward
  // triangles joins them. The cut is dropped and its two slabs are swept
  // as one; the other slabs are kept.
  const skin::Molecule mol =
      skin::read_molecule(std::string(SKINMESH_TEST_DATA) + "/regression/cluster60_probe0.5_band_without_strip.xyzr");
  mesher::MeshOptions options;
  options.probe_radius = 0.5;
  options.decomposition.slabs = 8;
  options.decomposition.balance_work = false;  // the cuts of the failure
  const mesher::MeshResult res = mesher::mesh_skin(mol, options);
  REQUIRE(!res.dropped_cuts.empty());
  CHECK(res.dropped_cuts.front().why.find("no outward strip") != std::string::npos);
  CHECK(res.slabs > 1);
  REQUIRE(res.cut_heights.size() + 1 == res.slabs);
  for (const decompose::DroppedCut& d : res.dropped_cuts)
    for (double h : res.cut_heights) CHECK(d.height != h);
  REQUIRE(res.checked);
  test::check_every_property(res.check);
}

TEST_CASE("regression: a saddle under a detoured cut, reached from one side, is bridged to its parked side") {
  // Gramicidin A at probe 0 in 16 detoured slabs: a live saddle 0.03 Å
  // under the cut near -5.3 Å, 0.21 Å from a small curve of it, is reached
  // by the front from one side while its other side parks below the cut
  // before it enters the hold region. Released unbridged, the saddle left
  // that curve and its neighbour one parked rim ("0 parked rims below it")
  // and the cut was dropped; lent the parked side, the saddle is bridged and
  // every cut holds.
  const mesher::MeshResult res = detoured_slabs("gramicidinA_1grm_model1.pdb", 0.0, 16, "parked rims");
  CHECK(res.dropped_cuts.empty());
}

TEST_CASE("regression: the ghost strip bisects a detoured cut's sharp junctions") {
  // Gramicidin A at probe 0 in 32 detoured slabs: where a cut leaves the
  // level set for a ball's circle it turns by about 112° between edges of
  // 0.159 and 0.114 Å. The ghost of the junction's sample, sent along the
  // chord's normal, turned past its neighbour's and the strip folded there
  // (the cut near -4.4 Å was dropped); along the bisector of the two edges
  // it does not.
  detoured_slabs("gramicidinA_1grm_model1.pdb", 0.0, 32, "ghost strip", 20);
}

TEST_CASE("regression: a detour's cluster with a live minimum under the cut keeps its side") {
  // Gramicidin A at probe 1.4 in 32 detoured slabs: near -15.2 Å a minimum
  // 0.16 Å under the cut and a saddle 0.09 Å under it form a cluster that the
  // level set enters. Sent up, the part of the minimum's dent outside the
  // balls stayed with the slab below, which had no front to reach it: its
  // 18-sample curve got no parked rim and the cut was dropped. Kept down, the
  // slab below makes the minimum's bowl and sweeps the dent.
  const mesher::MeshResult res = detoured_slabs("gramicidinA_1grm_model1.pdb", 1.4, 32, "parked rims");
  CHECK(res.dropped_cuts.empty());
}

TEST_CASE("regression: a saddle held from one side is lent its other side's parked vertices from farther") {
  // Crambin at probe 0 in 16 detoured slabs: a saddle just under a cut was
  // held from one side only; its other side had parked before its discs met
  // the protecting sphere, farther than the held side's reach. Released
  // unbridged, the saddle left a hole of 6 vertices that no plane showed as a
  // simple polygon, and the seal dropped the cut.
  const mesher::MeshResult res = detoured_slabs("crambin_1crn.pdb", 0.0, 16, "seal");
  CHECK(res.dropped_cuts.empty());
}

}  // TEST_SUITE
