// tests/geometry/point_grid_test.cpp: geometry/triangulation/point_grid — FlatPointGrid,
// PointGrid and LeveledPointGrid report exactly the points a linear scan with the same distance
// test reports (LeveledPointGrid: at least those of the scales asked for), on random clouds (clustered, flat, with
// duplicates and non-finite points) and random query balls, including balls outside the cloud.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "geometry/triangulation/key_index.h"
#include "geometry/triangulation/point_grid.h"

using skinmesh::Index;
using skinmesh::Vec3;
using namespace skinmesh::geometry;

namespace {

/// The ids of the finite points p with |p - q|² <= r², increasing.
std::vector<Index> scan(const std::vector<Vec3>& pts, const Vec3& q, double r) {
  std::vector<Index> out;
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (pts[i].allFinite() && (pts[i] - q).squaredNorm() <= r * r) out.push_back(Index(i));
  return out;
}

/// A random cloud: a box, a thin slab (flat grid axis), or clusters; with
/// exact duplicates and some non-finite points.
std::vector<Vec3> cloud(std::mt19937_64& rng, int kind, std::size_t n) {
  std::uniform_real_distribution<double> u(-10, 10);
  std::vector<Vec3> pts;
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 p(u(rng), u(rng), u(rng));
    if (kind == 1) p.z() = 1e-3 * p.z();                            // a slab
    if (kind == 2) p = Vec3(std::round(p.x()), 0.5, 0) + 1e-2 * p;  // clusters on a line
    pts.push_back(p);
    if (i % 17 == 0) pts.push_back(p);  // duplicate
    if (i % 53 == 0) pts.push_back(Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0));
    if (i % 71 == 0) pts.push_back(Vec3(0, std::numeric_limits<double>::infinity(), 0));
  }
  return pts;
}

}  // namespace

TEST_SUITE("geometry") {

TEST_CASE("point_grid: FlatPointGrid, FlatIndexGrid and PointGrid queries equal a linear scan") {
  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> u(-12, 12), ur(0, 3);
  for (int kind = 0; kind < 3; ++kind)
    for (double cell : {1e-3, 0.05, 0.7, 5.0, 100.0}) {
      const std::vector<Vec3> pts = cloud(rng, kind, 600);
      const FlatPointGrid flat(pts, cell);
      const FlatIndexGrid index_grid(pts, cell);
      CHECK(flat.cell_size() >= cell);
      CHECK(index_grid.num_cells() == flat.num_cells());
      CHECK(flat.num_cells() <= pts.size());
      CHECK(double(flat.num_columns()) <= FlatPointGrid::kMaxCellsPerPoint * double(pts.size()) + 4096.0);
      // The visiting order: cells by increasing (x, y, z), a cell's points by index.
      Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
      for (const Vec3& p : pts)
        if (p.allFinite()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
      const double inv = 1.0 / flat.cell_size();
      auto order_key = [&](Index id) {  // the grid's cell arithmetic, clamped as it clamps
        auto c = [&](int k) {
          return std::min(std::floor((pts[id][k] - lo[k]) * inv), std::floor((hi[k] - lo[k]) / flat.cell_size()));
        };
        return std::tuple(c(0), c(1), c(2), id);
      };
      PointGrid hashed(cell);
      for (std::size_t i = 0; i < pts.size(); ++i)
        if (pts[i].allFinite()) hashed.insert(Index(i), pts[i]);
      for (int k = 0; k < 300; ++k) {
        // Queries at random places, at cloud points (r = 0 included) and far away.
        Vec3 q(u(rng), u(rng), u(rng));
        if (k % 3 == 1) q = pts[std::size_t(k) % pts.size()].allFinite() ? pts[std::size_t(k) % pts.size()] : q;
        if (k % 10 == 9) q *= 100;
        const double r = k % 7 == 0 ? 0.0 : ur(rng) * (k % 5 == 0 ? 10 : 1);
        const std::vector<Index> want = scan(pts, q, r);
        std::vector<Index> got_flat, got_hashed, got_index;
        flat.for_each_near(q, r, [&](Index id, const Vec3& p) {
          CHECK(p == pts[id]);
          got_flat.push_back(id);
        });
        // The grid of indices visits the same points in the same order.
        index_grid.for_each_near(q, r, [&](Index id, const Vec3& p) {
          CHECK(&p == &pts[id]);
          got_index.push_back(id);
        });
        CHECK(got_index == got_flat);
        for (std::size_t i = 1; i < got_flat.size(); ++i) CHECK(order_key(got_flat[i - 1]) < order_key(got_flat[i]));
        // PointGrid visits every cell of the query box: only for boxes of few cells.
        const bool small_box = std::pow(2 * r / cell + 2, 3) < 1e5;
        if (small_box) hashed.for_each_near(q, r, [&](Index id, const Vec3&) { got_hashed.push_back(id); });
        std::sort(got_flat.begin(), got_flat.end());
        std::sort(got_hashed.begin(), got_hashed.end());
        CHECK(got_flat == want);
        if (small_box) CHECK(got_hashed == want);
        // any_near stops at the first point accepted by the predicate.
        if (!want.empty()) {
          int calls = 0;
          CHECK(flat.any_near(q, r, [&](Index, const Vec3&) { return ++calls == 1; }));
          CHECK(calls == 1);
          const Index last = want.back();
          CHECK(flat.any_near(q, r, [&](Index id, const Vec3&) { return id == last; }));
        }
        CHECK_FALSE(flat.any_near(q, r, [](Index, const Vec3&) { return false; }));
      }
    }
}

TEST_CASE("point_grid: on a hollow sphere the flat grids keep the requested cell and equal a scan") {
  // 20,000 points on a sphere of radius 100 with cells of 0.5: a dense box
  // of at most 8 cells per point would need cells of 4 (each holding 64 times
  // the points it should); the columns of the box need none coarser.
  std::mt19937_64 rng(20261126);
  std::normal_distribution<double> g(0, 1);
  std::vector<Vec3> pts;
  for (int i = 0; i < 20000; ++i) pts.push_back(100 * Vec3(g(rng), g(rng), g(rng)).normalized());
  const FlatIndexGrid grid(pts, 0.5);
  CHECK(grid.cell_size() == 0.5);
  CHECK(grid.num_cells() <= pts.size());
  for (int k = 0; k < 200; ++k) {
    const Vec3 q = pts[rng() % pts.size()] + Vec3(g(rng), g(rng), g(rng));
    const double r = k % 10 == 0 ? 30.0 : 2.0;
    std::vector<Index> got;
    grid.for_each_near(q, r, [&](Index id, const Vec3&) { got.push_back(id); });
    std::sort(got.begin(), got.end());
    CHECK(got == scan(pts, q, r));
  }
}

TEST_CASE("point_grid: PointGrid visits a cell's points in insertion order, across table growth") {
  // The visiting order is part of the contract: cells in (x, y, z) order,
  // points of a cell in the order they were inserted. 5,000 points in 40
  // cells of side 1 (every other cell, so a query around a cell's centre
  // reaches no other point) force several re-hashes of the table in between.
  PointGrid grid(1.0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  std::vector<std::vector<Index>> inserted(40);
  for (Index i = 0; i < 5000; ++i) {
    const int c = int(rng() % 40);
    grid.insert(i, Vec3(2 * (c % 5) + u(rng), 2 * (c / 5) + u(rng), -3 + u(rng)));
    inserted[std::size_t(c)].push_back(i);
  }
  for (int c = 0; c < 40; ++c) {
    const Vec3 centre(2 * (c % 5) + 0.5, 2 * (c / 5) + 0.5, -2.5);
    std::vector<Index> got;
    grid.for_each_near(centre, 0.87, [&](Index id, const Vec3&) { got.push_back(id); });
    CHECK(got == inserted[std::size_t(c)]);  // the whole cell (its corners are 0.866 away), in order
  }
}

TEST_CASE("point_grid: LeveledPointGrid queries equal a scan of the points present whose scale is in range") {
  // Random clouds with scales over twelve octaves (and some zero, tiny or
  // huge), near the origin and far from it; ids inserted and erased in random
  // order. A range query reports every present point within r whose scale lies
  // in its range (and may report others); a query at one scale reports exactly
  // the points inserted for a range of scales that holds it.
  std::mt19937_64 rng(20261124);
  std::uniform_real_distribution<double> u(-12, 12), ur(0, 3), octave(-8, 4);
  for (const Vec3& shift : {Vec3(0, 0, 0), Vec3(1e5, -3e4, 7e3)})
    for (int octaves : {1, 2, 3}) {
      std::vector<Vec3> pts = cloud(rng, 0, 400);
      for (Vec3& p : pts) p = p.allFinite() ? Vec3(p + shift) : shift;
      std::vector<double> scale(pts.size());
      for (std::size_t i = 0; i < pts.size(); ++i)
        scale[i] = i % 50 == 0 ? 0.0 : i % 50 == 1 ? 1e-300 : i % 50 == 2 ? 1e300 : std::exp2(octave(rng));
      LeveledPointGrid grid(0.5, octaves);
      std::vector<char> present(pts.size(), 0);
      for (int batch = 0; batch < 4; ++batch) {
        for (int op = 0; op < 300; ++op) {
          const Index id = Index(rng() % pts.size());
          if (present[id] && rng() % 3 != 0) {
            grid.erase(id);
            present[id] = 0;
          } else if (!present[id]) {
            grid.insert(id, pts[id], scale[id]);
            present[id] = 1;
          }
        }
        for (std::size_t i = 0; i < pts.size(); ++i) CHECK(grid.contains(Index(i)) == bool(present[i]));
        for (int t = 0; t < 40; ++t) {
          const Vec3 q = Vec3(u(rng), u(rng), u(rng)) + shift;
          const double r = t % 4 == 0 ? (pts[rng() % pts.size()] - q).norm() : ur(rng);
          // Every fifth query takes every scale: then exactly the present points a scan reports.
          const bool all = t % 5 == 0;
          const double lo = all ? 0.0 : std::exp2(octave(rng));
          const double hi = all ? std::numeric_limits<double>::infinity() : lo * std::exp2(3 * ur(rng));
          std::vector<Index> got;
          grid.for_each_near(q, r, lo, hi, pts, [&](Index id, const Vec3& p) {
            CHECK(p == pts[id]);
            CHECK((p - q).squaredNorm() <= r * r);
            CHECK(present[id]);
            got.push_back(id);
          });
          std::sort(got.begin(), got.end());
          CHECK(std::adjacent_find(got.begin(), got.end()) == got.end());
          std::vector<Index> want;
          for (Index id : scan(pts, q, r))
            if (present[id] && scale[id] >= lo && scale[id] <= hi) want.push_back(id);
          for (Index id : want) CHECK(std::binary_search(got.begin(), got.end(), id));
          if (all) CHECK(got == want);
        }
      }
      // Points inserted for the queries of a range of scales.
      // The copying grid and the index grid report the same points in the same order.
      LeveledPointGrid fixed(0.5, octaves, /*erasable=*/false);
      LeveledIndexGrid ids(0.5, octaves, /*erasable=*/false);
      std::vector<double> qlo(pts.size()), qhi(pts.size());
      for (std::size_t i = 0; i < pts.size(); ++i) {
        qlo[i] = scale[i] / 1.5, qhi[i] = scale[i] * 1.5;
        fixed.insert_for_queries(Index(i), pts[i], qlo[i], qhi[i]);
        ids.insert_for_queries(Index(i), pts[i], qlo[i], qhi[i]);
      }
      for (int t = 0; t < 200; ++t) {
        const Vec3 q = Vec3(u(rng), u(rng), u(rng)) + shift;
        const double r = ur(rng), at = std::exp2(octave(rng));
        std::vector<Index> got, got_ids;
        fixed.for_each_near_at(q, r, at, pts, [&](Index id, const Vec3&) { got.push_back(id); });
        ids.for_each_near_at(q, r, at, pts, [&](Index id, const Vec3&) { got_ids.push_back(id); });
        CHECK(got_ids == got);
        std::sort(got.begin(), got.end());
        CHECK(std::adjacent_find(got.begin(), got.end()) == got.end());
        for (Index id : scan(pts, q, r))
          if (at >= qlo[id] && at <= qhi[id]) CHECK(std::binary_search(got.begin(), got.end(), id));
      }
    }
}

TEST_CASE("point_grid: an erasable LeveledPointGrid gives erased points' memory back and reuses it") {
  // 60,000 points over three octaves of scales, inserted, all erased, and
  // inserted again in the same order. Erasing frees each id's place (8 bytes
  // per id in pages) and keeps at most a 4-byte free-list slot per block; the
  // second round takes every block from the free lists, so the pool does not
  // grow (a pool that left emptied blocks behind would add 16 bytes per point).
  std::mt19937_64 rng(20261126);
  std::uniform_real_distribution<double> u(-20, 20), octave(-1, 2);
  const std::size_t n = 60000;
  std::vector<Vec3> pts(n);
  std::vector<double> scale(n);
  for (std::size_t i = 0; i < n; ++i) pts[i] = Vec3(u(rng), u(rng), u(rng)), scale[i] = std::exp2(octave(rng));
  LeveledPointGrid grid(0.5, 2);
  for (std::size_t i = 0; i < n; ++i) grid.insert(Index(i), pts[i], scale[i]);
  const std::size_t full = grid.memory_bytes();
  for (std::size_t i = 0; i < n; ++i) grid.erase(Index(i));
  const std::size_t empty = grid.memory_bytes();
  CHECK(empty + 4 * n <= full);
  for (std::size_t i = 0; i < n; ++i) CHECK(!grid.contains(Index(i)));
  for (std::size_t i = 0; i < n; ++i) grid.insert(Index(i), pts[i], scale[i]);
  CHECK(grid.memory_bytes() <= full + 4 * n);
  std::vector<Index> got;
  const Vec3 q(1, 2, 3);
  grid.for_each_near(q, 4.0, 0.0, std::numeric_limits<double>::infinity(), pts,
                     [&](Index id, const Vec3&) { got.push_back(id); });
  std::sort(got.begin(), got.end());
  CHECK(got == scan(pts, q, 4.0));
}

TEST_CASE("key_index: keys numbered densely in first-insertion order, across growth; absent keys not found") {
  // 20,000 random keys below 2^63 (with repeats and the largest admissible
  // key), from a table sized for 10: every number is the key's rank of first
  // appearance, whatever the growth in between.
  KeyIndex index(10);
  std::mt19937_64 rng(99);
  std::vector<std::uint64_t> order;
  std::map<std::uint64_t, std::uint32_t> want;
  for (int i = 0; i < 20000; ++i) {
    std::uint64_t k = rng() >> 1;
    if (i % 7 == 3 && !order.empty()) k = order[rng() % order.size()];  // a repeat
    if (i == 500) k = (std::uint64_t(1) << 63) - 1;
    const auto [number, fresh] = index.find_or_add(k);
    const bool is_new = want.find(k) == want.end();
    CHECK(fresh == is_new);
    if (is_new) want[k] = std::uint32_t(order.size()), order.push_back(k);
    CHECK(number == want[k]);
  }
  CHECK(index.size() == order.size());
  for (std::size_t i = 0; i < order.size(); ++i) CHECK(index.find(order[i]) == i);
  for (int i = 0; i < 1000; ++i) {
    const std::uint64_t k = rng() >> 1;
    if (want.find(k) == want.end()) CHECK(index.find(k) == KeyIndex::kNone);
  }
}

TEST_CASE("point_grid: FlatPointGrid on empty, all-non-finite and single-point inputs") {
  const FlatPointGrid empty(std::vector<Vec3>{}, 1.0);
  CHECK_FALSE(empty.any_near(Vec3::Zero(), 1e9, [](Index, const Vec3&) { return true; }));
  const FlatPointGrid nan(std::vector<Vec3>{Vec3(std::nan(""), 0, 0)}, 1.0);
  CHECK_FALSE(nan.any_near(Vec3::Zero(), 1e9, [](Index, const Vec3&) { return true; }));
  const FlatPointGrid one(std::vector<Vec3>{Vec3(1, 2, 3)}, 1e-9);
  CHECK(one.num_cells() == 1);
  CHECK(one.any_near(Vec3(1, 2, 3), 0.0, [](Index id, const Vec3&) { return id == 0; }));
  CHECK_FALSE(one.any_near(Vec3(1, 2, 3.5), 0.49, [](Index, const Vec3&) { return true; }));
  CHECK_FALSE(one.any_near(Vec3(std::nan(""), 2, 3), 1.0, [](Index, const Vec3&) { return true; }));
}

}  // TEST_SUITE
