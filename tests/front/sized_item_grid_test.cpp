// tests/front/sized_item_grid_test.cpp: SizedItemGrid (front/front_state.h),
// the grid by size of the detour balls and cut edges that near_upper_detour
// reads, against brute force: every item within reach + size of a query is
// reported, for the scanned (few items) and the gridded (many) forms, with
// sizes over many octaves and some of size zero.
#include <doctest/doctest.h>

#include <random>
#include <set>
#include <vector>

#include "front/front_state.h"

using namespace skinmesh;

TEST_CASE("SizedItemGrid reports every item within reach + its size, scanned or gridded") {
  for (const std::size_t n : {std::size_t{40}, std::size_t{3000}}) {
    std::mt19937 rng(7 + static_cast<unsigned>(n));
    std::uniform_real_distribution<double> coord(-20, 20), octave(-12, 2), unit(0, 1);
    std::vector<Vec3> p;
    std::vector<double> s;
    for (std::size_t i = 0; i < n; ++i) {
      p.emplace_back(coord(rng), coord(rng), coord(rng));
      s.push_back(i % 17 == 0 ? 0.0 : std::exp2(octave(rng)));
    }
    front::detail::SizedItemGrid grid;
    grid.build(p, s);
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
      if (n > 512) CHECK(got.size() < n);  // the gridded form reads a part of the items
    }
    CHECK(expected_total > 0);
  }
}
