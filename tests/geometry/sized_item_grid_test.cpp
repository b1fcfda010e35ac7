// tests/geometry/sized_item_grid_test.cpp: SizedItemGrid (geometry/triangulation/point_grid.h),
// the grid by size of the detour balls and cut edges that the sweep's parking
// test and the cut tracer read, against brute force: every item within reach + size of a query is
// reported, for the scanned (few items) and the gridded (many) forms, with
// sizes over many octaves and some of size zero.
#include <doctest/doctest.h>

#include <random>
#include <set>
#include <utility>
#include <vector>

#include "geometry/triangulation/point_grid.h"

using namespace skinmesh;

TEST_CASE("SizedItemGrid reports every item within reach + its size, scanned or gridded") {
  // (items, largest count read one after the other): few items scanned by
  // default, few gridded as the cut tracer asks, many gridded.
  for (const auto& [n, max_scanned] : {std::pair<std::size_t, std::size_t>{40, 512}, {40, 0}, {3000, 512}}) {
    std::mt19937 rng(7 + static_cast<unsigned>(n));
    std::uniform_real_distribution<double> coord(-20, 20), octave(-12, 2), unit(0, 1);
    std::vector<Vec3> p;
    std::vector<double> s;
    for (std::size_t i = 0; i < n; ++i) {
      p.emplace_back(coord(rng), coord(rng), coord(rng));
      s.push_back(i % 17 == 0 ? 0.0 : std::exp2(octave(rng)));
    }
    geometry::SizedItemGrid grid;
    grid.build(p, s, max_scanned);
    std::size_t expected_total = 0;
    for (int k = 0; k < 300; ++k) {
      const Vec3 q(coord(rng), coord(rng), coord(rng));
      const double reach = 3 * unit(rng);
      std::set<Index> got;
      grid.for_each_near(q, reach, [&](Index i) { got.insert(i); });
      for (std::size_t i = 0; i < n; ++i)
        if ((p[i] - q).norm() <= reach + s[i]) {
          ++expected_total;
          CHECK(got.count(static_cast<Index>(i)) == 1);
        }
      if (n > max_scanned) CHECK(got.size() < n);  // the gridded form reads a part of the items
    }
    CHECK(expected_total > 0);
  }
}
