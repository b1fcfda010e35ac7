// tests/front/bridge_test.cpp: bridge() (Figure 8) changes the number of front
// loops by one (two loops merge below a saddle, one splits above it) and the
// Euler characteristic by -1.
// Through the sweep's state and operations (front/operations.h), on small
// synthetic skins; after every step the partial mesh keeps its invariants
// (tests/front/front_fixture.h).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/errors.h"
#include "morse/critical_points.h"
#include "morse/morse_smale_complex.h"
#include "skin/skin_surface.h"
#include "tests/front/front_fixture.h"
#include "tests/skin/skin_test_util.h"

using namespace skinmesh;
using namespace skinmesh::front::detail;
using namespace skinmesh::test;

TEST_SUITE("front operations") {

TEST_CASE("bridge: two loops merge below the neck's saddle, one splits above it; chi drops by one") {
  Fixture fx({{Vec3(0, 0, 0), w_of(1.6, 1.4)}, {Vec3(4.5, 0.8, 0.3), w_of(1.6, 1.4)}});
  REQUIRE(fx.ms.live_count().saddles == 2);
  REQUIRE(fx.ms.live_count().minima == 2);
  FrontState s(fx.skin, fx.ms, fx.opt);
  create_initial_front(s);
  CHECK(front_loops(s) == 2);
  std::vector<long> loop_changes;
  for (;;) {
    const std::size_t bridges = s.stats.bridges, loops = front_loops(s);
    const long chi = euler(s);
    if (!departure_step(s)) break;
    if (s.stats.bridges == bridges) continue;
    REQUIRE(s.stats.bridges == bridges + 1);
    loop_changes.push_back(static_cast<long>(front_loops(s)) - static_cast<long>(loops));
    CHECK(euler(s) == chi - 1);  // a 1-handle: a ladder adds 2(k-1) vertices, 4k-1 edges, 2k faces
    check_partial_mesh(s, fx.skin);
  }
  // Index-1 critical points: the lower saddle joins the two bowls' fronts, the
  // upper one splits the front around the neck into two caps.
  CHECK(loop_changes == std::vector<long>{-1, +1});
  CHECK(s.stats.released == 0);
}

}  // TEST_SUITE
