// tests/skin/mixed_complex_construction_test.cpp: the mixed complex's cells and
// planes against a plain scan of the triangulation with ordered maps (the
// definition of their numbering and order, papers/skin/mixed_complex.md
// "Construction"), its planes against their geometric definition, the
// complex built on 1, 2 and 3 threads against itself bit for bit, and the
// cells and planes made on first use: the same after release_made() and when
// several threads make them at once.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <span>
#include <thread>
#include <vector>

#include "skin/molecule_io.h"
#include "skin/skin_surface.h"
#include "tests/skin/skin_test_util.h"

using namespace skinmesh;

namespace {

/// The complex as a scan defines it: cells numbered as met (vertices, then
/// tetrahedra, then per tetrahedron in order and per facet leaving out its
/// sorted vertex 0..3: the facet if new, then its new edges 01, 02, 12), and
/// per cell its planes' (neighbour, extra vertex) in the order the facet /
/// coface pairs are met.
struct ScanComplex {
  std::vector<std::array<Index, 4>> vertices;
  std::vector<int> dim;
  std::vector<std::vector<std::pair<Index, Index>>> planes;
};

ScanComplex scan(const geometry::RegularTriangulation& rt) {
  ScanComplex sc;
  auto add = [&](int d, std::array<Index, 4> v) {
    sc.vertices.push_back(v);
    sc.dim.push_back(d);
    sc.planes.emplace_back();
    return static_cast<Index>(sc.vertices.size() - 1);
  };
  std::vector<Index> vertex_cell(rt.num_points(), kInvalidIndex);
  for (Index v = 0; v < rt.num_points(); ++v)
    if (rt.is_vertex(v)) vertex_cell[v] = add(0, {v, kInvalidIndex, kInvalidIndex, kInvalidIndex});
  std::vector<Index> tet_cell(rt.num_tets());
  for (Index t = 0; t < rt.num_tets(); ++t) {
    std::array<Index, 4> tv = rt.tet(t);
    std::sort(tv.begin(), tv.end());
    tet_cell[t] = add(3, tv);
  }
  auto pair = [&](Index x, Index y, Index k) {
    sc.planes[x].push_back({y, k});
    sc.planes[y].push_back({x, k});
  };
  std::map<std::array<Index, 2>, Index> edges;
  std::map<std::array<Index, 3>, Index> triangles;
  auto edge = [&](Index a, Index b) {
    auto [it, fresh] = edges.try_emplace({a, b}, 0);
    if (fresh) {
      it->second = add(1, {a, b, kInvalidIndex, kInvalidIndex});
      pair(vertex_cell[a], it->second, b);
      pair(vertex_cell[b], it->second, a);
    }
    return it->second;
  };
  for (Index t = 0; t < rt.num_tets(); ++t) {
    const std::array<Index, 4> tv = sc.vertices[tet_cell[t]];
    for (int skip = 0; skip < 4; ++skip) {
      std::array<Index, 3> f{};
      for (int i = 0, j = 0; i < 4; ++i)
        if (i != skip) f[j++] = tv[i];
      auto [it, fresh] = triangles.try_emplace(f, 0);
      if (fresh) {
        it->second = add(2, {f[0], f[1], f[2], kInvalidIndex});
        const Index e01 = edge(f[0], f[1]);
        pair(e01, it->second, f[2]);
        const Index e02 = edge(f[0], f[2]);
        pair(e02, it->second, f[1]);
        const Index e12 = edge(f[1], f[2]);
        pair(e12, it->second, f[0]);
      }
      pair(it->second, tet_cell[t], tv[skip]);
    }
  }
  return sc;
}

/// The complex of `pts` against the scan, and its planes against their
/// definition (papers/skin/skin_math.md §2.3): n is a unit vector orthogonal
/// to lin X and pointing from aff X towards z_k, the plane passes through
/// (z_a + z_Y) / 2, and the neighbour sees the same plane negated exactly.
void check_against_scan(const std::vector<geometry::WeightedPoint>& pts, int threads) {
  const skin::SkinSurface skin(pts, threads);
  const skin::MixedComplex& mc = skin.mixed_complex();
  const geometry::RegularTriangulation& rt = skin.triangulation();
  const ScanComplex sc = scan(rt);
  REQUIRE(mc.num_cells() == sc.vertices.size());
  const double L = mc.length_scale();
  std::size_t mismatches = 0;
  for (Index c = 0; c < mc.num_cells(); ++c) {
    const skin::MixedCell& m = mc.cell(c);
    if (m.dim != sc.dim[c] || m.vertices != sc.vertices[c]) ++mismatches;
    const auto range = mc.planes(c);
    if (range.size() != sc.planes[c].size()) {
      ++mismatches;
      continue;
    }
    for (std::size_t i = 0; i < range.size(); ++i) {
      const skin::CellPlane& p = range[i];
      const auto [nb, extra] = sc.planes[c][i];
      if (mc.neighbors(c)[i] != nb || mc.extra_vertex(c, nb) != extra) ++mismatches;
      // The neighbour's copy is this plane negated, bit for bit.
      bool mirrored = false;
      const auto across = mc.planes(nb);
      for (std::size_t j = 0; j < across.size(); ++j)
        mirrored =
            mirrored || (mc.neighbors(nb)[j] == c && across[j].offset == -p.offset && across[j].normal == -p.normal);
      CHECK(mirrored);
      const bool coface = mc.cell(nb).dim < m.dim;  // this cell is Y
      const skin::MixedCell& X = coface ? mc.cell(nb) : m;
      const skin::MixedCell& Y = coface ? m : mc.cell(nb);
      const Vec3 n = coface ? Vec3(-p.normal) : p.normal;
      const double off = coface ? -p.offset : p.offset;
      CHECK(std::abs(n.norm() - 1) <= 1e-12);
      for (int j = 1; j <= X.dim; ++j)
        CHECK(std::abs(n.dot((rt.point(X.vertices[j]).z - rt.point(X.vertices[0]).z).normalized())) <= 1e-9);
      CHECK(n.dot(rt.point(extra).z - rt.point(X.vertices[0]).z) > 0);
      CHECK(std::abs(n.dot(0.5 * (rt.point(X.vertices[0]).z + Y.focus)) - off) <= 1e-12 * L);
    }
  }
  CHECK(mismatches == 0);
}

/// Every plane of every cell, copied (cell by cell).
std::vector<std::vector<skin::CellPlane>> all_planes(const skin::MixedComplex& mc) {
  std::vector<std::vector<skin::CellPlane>> out(mc.num_cells());
  for (Index c = 0; c < mc.num_cells(); ++c) out[c].assign(mc.planes(c).begin(), mc.planes(c).end());
  return out;
}

/// True if the planes are those of `ref`, bit for bit.
bool same_planes(std::span<const skin::CellPlane> planes, const std::vector<skin::CellPlane>& ref) {
  if (planes.size() != ref.size()) return false;
  for (std::size_t i = 0; i < ref.size(); ++i)
    if (std::memcmp(planes[i].normal.data(), ref[i].normal.data(), sizeof(double) * 3) != 0 ||
        std::memcmp(&planes[i].offset, &ref[i].offset, sizeof(double)) != 0)
      return false;
  return true;
}

/// True if the two complexes hold the same cells and planes, bit for bit.
bool same_complex(const skin::MixedComplex& a, const skin::MixedComplex& b) {
  if (a.num_cells() != b.num_cells() || a.num_reordered_foci() != b.num_reordered_foci()) return false;
  for (Index c = 0; c < a.num_cells(); ++c) {
    const skin::MixedCell &x = a.cell(c), &y = b.cell(c);
    if (x.vertices != y.vertices || x.dim != y.dim || x.bounding != y.bounding || x.first_plane != y.first_plane ||
        x.num_planes != y.num_planes || std::memcmp(x.focus.data(), y.focus.data(), sizeof(double) * 3) != 0 ||
        std::memcmp(x.axis.data(), y.axis.data(), sizeof(double) * 3) != 0 ||
        std::memcmp(&x.focus_weight, &y.focus_weight, sizeof(double)) != 0)
      return false;
    auto pb = b.planes(c).begin();
    for (const skin::CellPlane& p : a.planes(c)) {
      const skin::CellPlane q = *pb;
      ++pb;
      if (std::memcmp(p.normal.data(), q.normal.data(), sizeof(double) * 3) != 0 ||
          std::memcmp(&p.offset, &q.offset, sizeof(double)) != 0)
        return false;
    }
  }
  return true;
}

}  // namespace

TEST_SUITE("skin") {

TEST_CASE("mixed complex: cells and planes as the scan of the triangulation numbers them") {
  std::mt19937 rng(2004);
  SUBCASE("random weighted points") { check_against_scan(test::random_points(40, 6.0, 0.5, 2.5, rng), 1); }
  SUBCASE("a coplanar ring (flat tetrahedra)") {
    const skin::Molecule mol =
        skin::read_molecule(std::string(SKINMESH_TEST_DATA) + "/regression/ring8_probe3_coplanar_facets.xyzr");
    check_against_scan(skin::weighted_points(mol, 3.0), 2);
  }
  SUBCASE("crambin at probes 0 and 1.4, on 2 threads") {
    const skin::Molecule mol = skin::read_molecule(std::string(SKINMESH_DATA) + "/crambin_1crn.pdb");
    check_against_scan(skin::weighted_points(mol, 0.0), 2);
    check_against_scan(skin::weighted_points(mol, 1.4), 2);
  }
  SUBCASE("one atom, two atoms (only bounding tetrahedra around them)") {
    check_against_scan({{Vec3(1, 2, 3), 4.0}}, 1);
    check_against_scan({{Vec3(0, 0, 0), 4.0}, {Vec3(1.5, 0, 0), 2.0}}, 1);
  }
}

TEST_CASE("mixed complex: the same on 1, 2 and 3 threads, bit for bit") {
  // Enough tetrahedra (about 14,000) for every loop of the construction to
  // split into several blocks.
  std::mt19937 rng(42);
  const std::vector<geometry::WeightedPoint> pts = test::random_points(2000, 30.0, 0.8, 2.0, rng);
  const skin::SkinSurface one(pts, 1);
  REQUIRE(one.triangulation().num_tets() > 3 * 4096);
  for (int threads : {2, 3}) {
    const skin::SkinSurface many(pts, threads);
    CHECK(same_complex(one.mixed_complex(), many.mixed_complex()));
  }
}

TEST_CASE("mixed complex: cells and planes made on first use, again after a release, and by several threads at once") {
  std::mt19937 rng(7);
  const std::vector<geometry::WeightedPoint> pts = test::random_points(600, 18.0, 0.8, 2.0, rng);
  const skin::SkinSurface skin(pts, 1);
  const skin::MixedComplex& mc = skin.mixed_complex();
  CHECK(mc.made_bytes() == 0);  // the construction makes none
  // One plane per neighbour; each neighbour lists the cell back, and sees
  // the same extra vertex across the shared plane.
  std::size_t planes = 0;
  for (Index c = 0; c < mc.num_cells(); ++c) {
    const auto nb = mc.neighbors(c);
    const auto pl = mc.planes(c);
    REQUIRE(nb.size() == pl.size());
    for (std::size_t i = 0; i < nb.size(); ++i) {
      const auto back = mc.neighbors(nb[i]);
      CHECK(std::count(back.begin(), back.end(), c) == 1);
      CHECK(mc.extra_vertex(c, nb[i]) == mc.extra_vertex(nb[i], c));
    }
    planes += pl.size();
  }
  CHECK(mc.made_bytes() == planes * sizeof(skin::CellPlane));
  const auto ref = all_planes(mc);
  mc.release_made();
  CHECK(mc.made_bytes() == 0);
  // Four threads make them again, each visiting the cells in its own order
  // (forwards, backwards, and two strides), so that most cells are asked for
  // by several threads at about the same time.
  const Index n = mc.num_cells();
  std::vector<int> wrong(4, 0);
  std::vector<std::thread> pool;
  for (int k = 0; k < 4; ++k)
    pool.emplace_back([&, k] {
      for (Index i = 0; i < n; ++i) {
        const Index c = k == 0 ? i : (k == 1 ? n - 1 - i : (k == 2 ? (i * 7919u) % n : (i * 104729u + 13u) % n));
        wrong[k] += same_planes(mc.planes(c), ref[c]) ? 0 : 1;
      }
    });
  for (std::thread& t : pool) t.join();
  CHECK(wrong == std::vector<int>(4, 0));
  CHECK(mc.made_bytes() == planes * sizeof(skin::CellPlane));  // each cell's made once
  // A walk after a release reads the same planes: locate() finds the same cells.
  std::vector<Index> before;
  std::uniform_real_distribution<double> u(-15.0, 15.0);
  std::vector<Vec3> probes;
  for (int i = 0; i < 200; ++i) probes.emplace_back(u(rng), u(rng), u(rng));
  for (const Vec3& x : probes) before.push_back(mc.locate(x));
  mc.release_made();
  for (std::size_t i = 0; i < probes.size(); ++i) CHECK(mc.locate(probes[i]) == before[i]);
  CHECK(mc.made_bytes() < planes * sizeof(skin::CellPlane));  // only the walks' cells
  // A cell's geometry: made on first use, the same as made and not kept,
  // and again after a release; the scans' simplex is the cell's.
  mc.release_made();
  std::size_t differ = 0;
  for (Index c = 0; c < mc.num_cells(); ++c) {
    const skin::MixedCell kept = mc.cell(c), unkept = mc.cell_value(c);
    differ += kept.vertices != unkept.vertices || kept.dim != unkept.dim || kept.bounding != unkept.bounding ||
                      kept.first_plane != unkept.first_plane || kept.num_planes != unkept.num_planes ||
                      std::memcmp(kept.focus.data(), unkept.focus.data(), sizeof(double) * 3) != 0 ||
                      std::memcmp(kept.axis.data(), unkept.axis.data(), sizeof(double) * 3) != 0 ||
                      std::memcmp(&kept.focus_weight, &unkept.focus_weight, sizeof(double)) != 0
                  ? 1
                  : 0;
    const skin::CellSimplex& x = mc.simplex(c);
    differ += x.vertices != kept.vertices || x.dim != kept.dim || x.bounding != kept.bounding ||
                      x.first_plane != kept.first_plane || mc.num_planes(c) != kept.num_planes
                  ? 1
                  : 0;
  }
  CHECK(differ == 0);
  CHECK(mc.made_bytes() == std::size_t(mc.num_cells()) * sizeof(skin::MixedCell));
}

TEST_CASE("mixed complex: a cell with more planes than a block of the made store") {
  // A ball at the centre of a shell of 6,000 balls (radii jittered, so that
  // no five centres are cospherical): the centre's vertex cell has a plane
  // per shell ball it sees, more than a block of skin::MadeStore holds, so
  // its planes get a block of their own between cells with ordinary blocks.
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> jitter(0.9999, 1.0001);
  std::vector<geometry::WeightedPoint> pts{{Vec3::Zero(), 4.0}};
  for (int i = 0; i < 6000; ++i) {
    Vec3 d(g(rng), g(rng), g(rng));
    pts.push_back({40.0 * jitter(rng) * d.normalized(), 4.0});
  }
  const skin::SkinSurface skin(pts, 1);
  const skin::MixedComplex& mc = skin.mixed_complex();
  const Index centre = mc.vertex_cell(0);
  REQUIRE(centre != kInvalidIndex);
  REQUIRE(mc.num_planes(centre) > skin::MadeStore<skin::CellPlane>::kBlock);
  std::vector<std::vector<skin::CellPlane>> ref(mc.num_cells());
  for (Index c = 0; c < mc.num_cells(); ++c) mc.planes_into(c, ref[c]);  // computed and not kept
  CHECK(mc.made_bytes() == 0);
  // Ordinary cells before and after the large one, then every cell again.
  const Index before = centre > 0 ? centre - 1 : centre + 1, after = centre + 1 < mc.num_cells() ? centre + 1 : before;
  CHECK(same_planes(mc.planes(before), ref[before]));
  CHECK(same_planes(mc.planes(centre), ref[centre]));
  CHECK(same_planes(mc.planes(after), ref[after]));
  std::size_t wrong = 0, planes = 0;
  for (Index c = 0; c < mc.num_cells(); ++c) {
    wrong += same_planes(mc.planes(c), ref[c]) ? 0 : 1;
    planes += mc.num_planes(c);
  }
  CHECK(wrong == 0);
  CHECK(mc.made_bytes() == planes * sizeof(skin::CellPlane));
  CHECK(same_planes(mc.planes(centre), ref[centre]));  // still where it was made
}

}  // TEST_SUITE
