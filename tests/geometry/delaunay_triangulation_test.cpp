// tests/geometry/delaunay_triangulation_test.cpp: tests of
// geometry/triangulation/delaunay_triangulation. Every state is checked with is_valid()
// (orientation, adjacency, local Delaunay with power_test_sos); small states are
// also compared with a brute force over all 4-subsets of the live vertices
// (bounding points included, with their ids), which is exact for degenerate
// inputs too because SoS makes the perturbed input generic.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "core/errors.h"
#include "geometry/kernel/predicates.h"
#include "geometry/triangulation/delaunay_triangulation.h"
#include "tests/geometry/test_meshes.h"

namespace sg = skinmesh::geometry;
using sg::DelaunayTriangulation;
using sg::WeightedPoint;
using skinmesh::Index;
using skinmesh::kInvalidIndex;
using skinmesh::Sign;
using skinmesh::Vec3;
using skinmesh::test::integer_sphere;

namespace {

using Quad = std::array<Index, 4>;

Quad sorted(Quad q) {
  std::sort(q.begin(), q.end());
  return q;
}

std::set<Quad> tet_set(const DelaunayTriangulation& dt) {
  std::set<Quad> out;
  dt.for_each_tet([&](Index t) { out.insert(sorted(dt.tet(t))); });
  return out;
}

std::vector<Index> live_vertices(const DelaunayTriangulation& dt) {
  std::vector<Index> out;
  for (Index v = 0; v < dt.vertex_capacity(); ++v)
    if (dt.is_vertex(v)) out.push_back(v);
  return out;
}

// The 4-subsets of the live vertices (bounding points included) that are not
// flat and whose SoS circumsphere is empty of every other live vertex.
std::set<Quad> brute_force(const DelaunayTriangulation& dt) {
  const std::vector<Index> vs = live_vertices(dt);
  const std::size_t n = vs.size();
  std::vector<WeightedPoint> p(n);
  for (std::size_t k = 0; k < n; ++k) p[k] = {dt.point(vs[k]), 0.0};
  std::set<Quad> out;
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b)
      for (std::size_t c = b + 1; c < n; ++c)
        for (std::size_t d = c + 1; d < n; ++d) {
          std::array<std::size_t, 4> q = {a, b, c, d};
          const Sign o = sg::orient3d(p[a].z, p[b].z, p[c].z, p[d].z);
          if (o == Sign::Zero) continue;
          if (o == Sign::Negative) std::swap(q[0], q[1]);
          bool empty = true;
          for (std::size_t e = 0; e < n && empty; ++e) {
            if (e == a || e == b || e == c || e == d) continue;
            empty = sg::power_test_sos(p[q[0]], p[q[1]], p[q[2]], p[q[3]], p[e], vs[q[0]], vs[q[1]], vs[q[2]], vs[q[3]],
                                       vs[e]) == Sign::Negative;
          }
          if (empty) out.insert(sorted({vs[a], vs[b], vs[c], vs[d]}));
        }
  return out;
}

void check_valid(const DelaunayTriangulation& dt) {
  std::string why;
  const bool ok = dt.is_valid(&why);
  INFO(why);
  REQUIRE(ok);
}

void check_brute_force(const DelaunayTriangulation& dt) {
  check_valid(dt);
  const std::set<Quad> expected = brute_force(dt);
  REQUIRE(tet_set(dt) == expected);
  CHECK(dt.num_tets() == expected.size());
}

const Vec3 kLo(-10, -10, -10), kHi(10, 10, 10);

std::vector<Vec3> random_points(std::mt19937_64& rng, int n, double box) {
  std::uniform_real_distribution<double> c(-box, box);
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i) {
    const double x = c(rng), y = c(rng), z = c(rng);  // one draw per statement
    pts.emplace_back(x, y, z);
  }
  return pts;
}

std::vector<Vec3> grid(int nx, int ny, int nz, double h) {
  std::vector<Vec3> out;
  for (int x = 0; x < nx; ++x)
    for (int y = 0; y < ny; ++y)
      for (int z = 0; z < nz; ++z) out.emplace_back(h * x, h * y, h * z);
  return out;
}

template <class T>
void shuffle(std::vector<T>& v, std::mt19937_64& rng) {
  for (std::size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[rng() % i]);
}

// Inserts `pts` in a shuffled order, compares with the brute force, then
// removes every vertex in a shuffled order (brute force every `every`
// removals) and re-inserts all of them.
void insert_remove_all(const std::vector<Vec3>& pts, unsigned seed, int every) {
  INFO("seed " << seed);
  std::mt19937_64 rng(seed);
  DelaunayTriangulation dt(kLo, kHi);
  std::vector<Vec3> order = pts;
  shuffle(order, rng);
  std::vector<Index> ids;
  for (const Vec3& p : order) {
    ids.push_back(dt.insert(p));
    check_valid(dt);
  }
  CHECK(dt.num_vertices() == pts.size());
  check_brute_force(dt);
  shuffle(ids, rng);
  int k = 0;
  for (const Index v : ids) {
    dt.remove(v);
    CHECK_FALSE(dt.is_vertex(v));
    if (++k % every == 0)
      check_brute_force(dt);
    else
      check_valid(dt);
  }
  CHECK(dt.num_vertices() == 0);
  CHECK(dt.num_tets() == 1);
  for (const Vec3& p : order) dt.insert(p);
  check_brute_force(dt);
}

}  // namespace

TEST_SUITE("geometry") {

TEST_CASE("delaunay triangulation: bad input throws InputError") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(DelaunayTriangulation(Vec3(0, 0, 0), Vec3(1, nan, 1)), skinmesh::InputError);
  CHECK_THROWS_AS(DelaunayTriangulation(Vec3(0, 0, 0), Vec3(1, -1, 1)), skinmesh::InputError);
  CHECK_THROWS_AS(DelaunayTriangulation(Vec3(0, 0, 0), Vec3(1e300, 1, 1)), skinmesh::InputError);
  DelaunayTriangulation dt(kLo, kHi);
  const Index a = dt.insert(Vec3(1, 2, 3));
  const Index b = dt.insert(Vec3(-1, 0.5, 2));
  CHECK(a == 4);
  CHECK(b == 5);
  const std::set<Quad> before = tet_set(dt);
  CHECK_THROWS_AS(dt.insert(Vec3(11, 0, 0)), skinmesh::InputError);
  CHECK_THROWS_AS(dt.insert(Vec3(0, nan, 0)), skinmesh::InputError);
  CHECK_THROWS_WITH_AS(dt.insert(Vec3(1, 2, 3)), doctest::Contains("coincides with vertex 4"), skinmesh::InputError);
  CHECK_THROWS_AS(dt.remove(0), skinmesh::InputError);  // bounding point
  CHECK_THROWS_AS(dt.remove(3), skinmesh::InputError);
  CHECK_THROWS_AS(dt.remove(6), skinmesh::InputError);  // never used
  CHECK_THROWS_AS(dt.remove(kInvalidIndex), skinmesh::InputError);
  CHECK_THROWS_AS(dt.move(a, Vec3(-1, 0.5, 2)), skinmesh::InputError);  // onto b
  CHECK_THROWS_AS(dt.move(a, Vec3(0, 0, 20)), skinmesh::InputError);
  CHECK_THROWS_AS(dt.move(2, Vec3(0, 0, 0)), skinmesh::InputError);
  CHECK(tet_set(dt) == before);
  CHECK(dt.num_vertices() == 2);
  check_valid(dt);
  dt.remove(a);
  CHECK_THROWS_AS(dt.remove(a), skinmesh::InputError);  // already removed
  CHECK_THROWS_AS(dt.move(a, Vec3(0, 0, 0)), skinmesh::InputError);
  // The box is closed: its corners are valid points.
  dt.insert(kLo);
  dt.insert(kHi);
  check_brute_force(dt);
}

TEST_CASE("delaunay triangulation: empty, one point, bounding tetrahedron") {
  DelaunayTriangulation dt(Vec3(0, 0, 0), Vec3(0, 0, 0));  // a one-point box: L' = 1 Å
  CHECK(dt.bounding_radius() == doctest::Approx(50.0));
  CHECK(dt.num_tets() == 1);
  CHECK(dt.num_vertices() == 0);
  check_brute_force(dt);
  for (Index v = 0; v < 4; ++v) {
    CHECK(dt.is_bounding(v));
    CHECK(dt.is_vertex(v));
    CHECK((dt.point(v) - dt.bounding_centre()).norm() == doctest::Approx(50.0));
  }
  const Index v = dt.insert(Vec3(0, 0, 0));
  CHECK_FALSE(dt.is_bounding(v));
  CHECK(dt.num_tets() == 4);
  check_brute_force(dt);
  std::vector<Index> star;
  dt.incident_tets(v, star);
  CHECK(star.size() == 4);
  dt.remove(v);
  CHECK(dt.num_tets() == 1);
  check_brute_force(dt);
  const Index w = dt.insert(Vec3(0, 0, 0));
  CHECK(w == v + 1);  // ids are never reused
  check_brute_force(dt);
}

TEST_CASE("delaunay triangulation: random points equal the brute force") {
  for (const unsigned seed : {1u, 2u, 3u}) {
    std::mt19937_64 rng(seed);
    insert_remove_all(random_points(rng, 30, 9.0), seed, 6);
  }
}

TEST_CASE("delaunay triangulation: degenerate sets equal the brute force") {
  SUBCASE("3 x 3 x 3 integer grid (cospherical and coplanar)") {
    sg::reset_predicate_stats();
    insert_remove_all(grid(3, 3, 3, 1.0), 11u, 5);
    CHECK(sg::predicate_stats().power_test.sos > 0);  // SoS decided ties
  }
  SUBCASE("cube corners and centre") {
    std::vector<Vec3> pts = grid(2, 2, 2, 2.0);
    pts.emplace_back(1, 1, 1);
    insert_remove_all(pts, 12u, 1);
  }
  SUBCASE("integer points on a sphere") {
    std::vector<Vec3> pts = integer_sphere(9);  // 30 points: (±3,0,0), (±2,±2,±1), ...
    insert_remove_all(pts, 13u, 5);
    pts.emplace_back(0, 0, 0);  // plus the centre
    insert_remove_all(pts, 14u, 5);
  }
  SUBCASE("coplanar 5 x 5 grid plus a few off-plane points") {
    std::vector<Vec3> pts = grid(5, 5, 1, 1.0);
    pts.emplace_back(2, 2, 1);
    pts.emplace_back(1, 3, -1);
    pts.emplace_back(2.5, 2.5, 3);
    insert_remove_all(pts, 15u, 4);
  }
  SUBCASE("coplanar only (5 x 5 grid) and collinear points") {
    insert_remove_all(grid(5, 5, 1, 0.5), 16u, 5);
    std::vector<Vec3> line;
    for (int k = 0; k < 8; ++k) line.emplace_back(k, 0.5 * k, -0.25 * k);
    insert_remove_all(line, 17u, 1);
  }
}

TEST_CASE("delaunay triangulation: nearly degenerate inputs") {
  SUBCASE("sphere points rounded to 3 decimals") {
    std::mt19937_64 rng(21u);
    std::vector<Vec3> pts;
    std::normal_distribution<double> g(0.0, 1.0);
    for (int k = 0; k < 30; ++k) {
      const double x = g(rng), y = g(rng), z = g(rng);
      const Vec3 d = 3.0 * Vec3(x, y, z).normalized();
      pts.emplace_back(std::round(d.x() * 1000) / 1000, std::round(d.y() * 1000) / 1000,
                       std::round(d.z() * 1000) / 1000);
    }
    insert_remove_all(pts, 21u, 5);
  }
  SUBCASE("integer grid perturbed by 1e-12") {
    std::mt19937_64 rng(22u);
    std::uniform_real_distribution<double> eps(-1e-12, 1e-12);
    std::vector<Vec3> pts = grid(3, 3, 3, 1.0);
    for (Vec3& p : pts) {
      const double x = eps(rng), y = eps(rng), z = eps(rng);
      p += Vec3(x, y, z);
    }
    insert_remove_all(pts, 22u, 5);
  }
}

TEST_CASE("delaunay triangulation: move keeps the id") {
  DelaunayTriangulation dt(kLo, kHi);
  std::vector<Index> ids;
  for (const Vec3& p : grid(3, 3, 2, 2.0)) ids.push_back(dt.insert(p));
  const std::set<Quad> before = tet_set(dt);
  const auto removals = dt.stats().removals;
  dt.move(ids[4], dt.point(ids[4]));  // same position: no change at all
  CHECK(dt.stats().removals == removals);
  CHECK(tet_set(dt) == before);
  // Moving a vertex away and back gives the same triangulation (same id).
  const Vec3 home = dt.point(ids[4]);
  dt.move(ids[4], Vec3(7, 7, 7));
  check_brute_force(dt);
  CHECK(tet_set(dt) != before);
  dt.move(ids[4], home);
  CHECK(tet_set(dt) == before);
  // Onto the position of a removed vertex: allowed.
  const Vec3 freed = dt.point(ids[0]);
  dt.remove(ids[0]);
  dt.move(ids[1], freed);
  CHECK(dt.point(ids[1]) == freed);
  CHECK(dt.is_vertex(ids[1]));
  check_brute_force(dt);
}

TEST_CASE("delaunay triangulation: long random insert / remove / move sequence") {
  // 2000 operations on a pool of about 30 live points. Half the positions are
  // on a 5 x 5 x 5 integer grid (degenerate, and exact collisions exercise the
  // duplicate refusal), half uniform. Then 600 operations with 7/8 of the
  // positions on the grid (more degenerate).
  for (const auto& run : {std::tuple{20240607u, 4u, 2000}, std::tuple{77u, 7u, 600}}) {
    const unsigned seed = std::get<0>(run), grid_in_8 = std::get<1>(run);
    const int num_ops = std::get<2>(run);
    INFO("seed " << seed);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unif(-4.0, 4.0);
    auto draw = [&]() {
      if (rng() % 8 < grid_in_8) {
        const int x = int(rng() % 5), y = int(rng() % 5), z = int(rng() % 5);
        return Vec3(x - 2, y - 2, z - 2);
      }
      const double x = unif(rng), y = unif(rng), z = unif(rng);
      return Vec3(x, y, z);
    };
    DelaunayTriangulation dt(kLo, kHi);
    std::map<Index, Vec3> live;
    auto occupied = [&](const Vec3& p) {
      for (const auto& [v, q] : live)
        if (q == p) return true;
      return false;
    };
    int inserts = 0, removes = 0, moves = 0, refused = 0;
    std::map<Index, std::array<Index, 4>> before;  // live tetrahedra before the operation
    dt.for_each_tet([&](Index t) { before[t] = dt.tet(t); });
    for (int op = 0; op < num_ops; ++op) {
      INFO("operation " << op);
      const unsigned r = static_cast<unsigned>(rng() % 100);
      const std::size_t target = 30;
      const bool want_insert = live.size() < 5 || (live.size() < target ? r < 50 : r < 30);
      if (want_insert) {
        const Vec3 p = draw();
        if (occupied(p)) {
          CHECK_THROWS_AS(dt.insert(p), skinmesh::InputError);
          ++refused;
        } else {
          const Index v = dt.insert(p);
          CHECK(live.count(v) == 0);
          live[v] = p;
          ++inserts;
        }
      } else {
        auto it = live.begin();
        std::advance(it, rng() % live.size());
        const Index v = it->first;
        if (r < 75) {
          dt.remove(v);
          live.erase(it);
          ++removes;
        } else {
          const Vec3 p = rng() % 4 == 0 ? Vec3(it->second + Vec3(0.01, -0.02, 0.015)) : draw();
          if (p != it->second && occupied(p)) {
            CHECK_THROWS_AS(dt.move(v, p), skinmesh::InputError);
            ++refused;
          } else if ((p.array().abs() <= 10.0).all()) {
            dt.move(v, p);
            it->second = p;
            ++moves;
          }
        }
      }
      check_valid(dt);
      REQUIRE(dt.num_vertices() == live.size());
      if (op % 50 == 49) check_brute_force(dt);
      // last_created(): every live tetrahedron it does not list is unchanged.
      {
        std::set<Index> listed(dt.last_created().begin(), dt.last_created().end());
        std::size_t unchanged = 0;
        dt.for_each_tet([&](Index t) {
          if (listed.count(t)) return;
          ++unchanged;
          const auto it_before = before.find(t);
          REQUIRE(it_before != before.end());
          CHECK(it_before->second == dt.tet(t));
        });
        std::size_t live_listed = 0;
        for (const Index t : listed) live_listed += dt.is_live(t) ? 1 : 0;
        CHECK(unchanged + live_listed == dt.num_tets());
        before.clear();
        dt.for_each_tet([&](Index t) { before[t] = dt.tet(t); });
      }
    }
    MESSAGE("inserts " << inserts << ", removes " << removes << ", moves " << moves << ", refused duplicates "
                       << refused);
    CHECK(inserts > num_ops / 5);
    CHECK(removes > num_ops / 7);
    CHECK(moves > num_ops / 20);
    CHECK(refused > 0);
    // Small moves of a generic point keep the combinatorics: the kinetic fast
    // path of move() ran (and every state above matched the brute force).
    if (grid_in_8 == 4u) CHECK(dt.stats().kinetic_moves > 0);
    for (const auto& [v, p] : live) CHECK(dt.point(v) == p);

    // History independence: the same (id order, position) set built directly
    // gives the same tetrahedra (SoS uniqueness). Inserting in increasing id
    // order gives new ids in the same relative order.
    DelaunayTriangulation direct(kLo, kHi);
    std::map<Index, Index> old_of_new = {{0, 0}, {1, 1}, {2, 2}, {3, 3}};
    for (const auto& [v, p] : live) old_of_new[direct.insert(p)] = v;
    check_valid(direct);
    std::set<Quad> mapped;
    for (const Quad& q : tet_set(direct))
      mapped.insert(sorted({old_of_new[q[0]], old_of_new[q[1]], old_of_new[q[2]], old_of_new[q[3]]}));
    CHECK(mapped == tet_set(dt));
  }
}

TEST_CASE("delaunay triangulation: remove vertices adjacent to bounding points") {
  std::mt19937_64 rng(99u);
  DelaunayTriangulation dt(kLo, kHi);
  for (const Vec3& p : random_points(rng, 25, 9.9)) dt.insert(p);
  check_brute_force(dt);
  // Repeatedly remove a vertex that shares a tetrahedron with a bounding point
  // (a hull vertex): its link contains bounding points.
  int removed = 0;
  while (dt.num_vertices() > 0) {
    Index victim = kInvalidIndex;
    dt.for_each_tet([&](Index t) {
      const Quad& q = dt.tet(t);
      const bool bounded = std::any_of(q.begin(), q.end(), [](Index v) { return v < 4; });
      for (const Index v : q)
        if (bounded && !dt.is_bounding(v) && victim == kInvalidIndex) victim = v;
    });
    REQUIRE(victim != kInvalidIndex);
    dt.remove(victim);
    ++removed;
    check_brute_force(dt);
  }
  CHECK(removed == 25);
}

TEST_CASE("delaunay triangulation: locate, incident tets, circumcentres") {
  std::mt19937_64 rng(7u);
  DelaunayTriangulation dt(kLo, kHi);
  std::vector<Index> ids;
  Index hint = kInvalidIndex;
  for (const Vec3& p : random_points(rng, 300, 10.0)) {
    ids.push_back(dt.insert(p, hint));
    hint = dt.vertex_tet(ids.back());
  }
  check_valid(dt);
  // locate: the returned tetrahedron contains the point (exactly).
  for (const Vec3& p : random_points(rng, 200, 10.0)) {
    const Index t = dt.locate(p);
    REQUIRE(dt.is_live(t));
    const Quad& q = dt.tet(t);
    for (const auto& f : DelaunayTriangulation::kFaceVertices)
      CHECK(sg::orient3d(dt.point(q[f[0]]), dt.point(q[f[1]]), dt.point(q[f[2]]), p) != Sign::Negative);
    CHECK(dt.locate(p, t) == t);
  }
  // A vertex is located in one of its tetrahedra.
  for (int k = 0; k < 20; ++k) {
    const Index v = ids[k];
    CHECK(dt.local_index(dt.locate(dt.point(v)), v) >= 0);
  }
  // Far outside the bounding tetrahedron: kInvalidIndex.
  CHECK(dt.locate(Vec3(1e6, 0, 0)) == kInvalidIndex);
  // incident_tets equals a scan, for input and bounding vertices (large stars).
  std::vector<Index> star;
  for (const Index v : {ids[0], ids[1], ids[2], Index(0), Index(1), Index(2), Index(3)}) {
    dt.incident_tets(v, star);
    std::vector<Index> scan;
    dt.for_each_tet([&](Index t) {
      if (dt.local_index(t, v) >= 0) scan.push_back(t);
    });
    std::sort(star.begin(), star.end());
    CHECK(star == scan);
  }
  // Circumcentres are equidistant from the 4 vertices (relative 1e-9).
  int counted = 0;
  dt.for_each_tet([&](Index t) {
    ++counted;
    const Quad& q = dt.tet(t);
    const Vec3 c = dt.circumcentre(t);
    const double r = (c - dt.point(q[0])).norm();
    for (int k = 1; k < 4; ++k) CHECK((c - dt.point(q[k])).norm() == doctest::Approx(r).epsilon(1e-9));
  });
  CHECK(counted == int(dt.num_tets()));
  // Remove half, move a quarter; still valid.
  shuffle(ids, rng);
  for (std::size_t k = 0; k < ids.size() / 2; ++k) dt.remove(ids[k]);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  for (std::size_t k = ids.size() / 2; k < 3 * ids.size() / 4; ++k) {
    const Vec3 p = dt.point(ids[k]);
    const double dx = jitter(rng), dy = jitter(rng), dz = jitter(rng);
    dt.move(ids[k], (p + Vec3(dx, dy, dz)).cwiseMax(kLo).cwiseMin(kHi));
  }
  check_valid(dt);
  CHECK(dt.num_vertices() == 150);
  CHECK(dt.stats().walk_fallbacks == 0);
}

TEST_CASE("delaunay triangulation: larger sets, lattice deletions") {
  // 6 x 6 x 6 lattice: every removal has a highly degenerate link.
  DelaunayTriangulation dt(kLo, kHi);
  std::vector<Index> ids;
  for (const Vec3& p : grid(6, 6, 6, 1.5)) ids.push_back(dt.insert(p - Vec3(3.75, 3.75, 3.75)));
  check_valid(dt);
  std::mt19937_64 rng(5u);
  shuffle(ids, rng);
  for (std::size_t k = 0; k < ids.size(); ++k) {
    dt.remove(ids[k]);
    if (k % 20 == 0) check_valid(dt);
  }
  CHECK(dt.num_tets() == 1);
  check_valid(dt);
  // 3000 random points, remove 2000, re-insert 1000.
  std::vector<Index> r;
  for (const Vec3& p : random_points(rng, 3000, 10.0)) r.push_back(dt.insert(p));
  for (std::size_t k = 0; k < 2000; ++k) dt.remove(r[k]);
  for (const Vec3& p : random_points(rng, 1000, 10.0)) dt.insert(p);
  check_valid(dt);
  CHECK(dt.num_vertices() == 2000);
  const auto& st = dt.stats();
  MESSAGE("insertions " << st.insertions << ", removals " << st.removals << ", per removal: star "
                        << double(st.star_tets) / st.removals << " tets, link "
                        << double(st.link_vertices) / st.removals << " vertices (with the 4 bounding), "
                        << double(st.local_tets) / st.removals
                        << " link tets; per insertion: " << double(st.walk_steps) / st.insertions << " walk steps, "
                        << double(st.conflict_tets) / st.insertions << " conflict tets");
  CHECK(st.walk_fallbacks == 0);
}

}  // TEST_SUITE
