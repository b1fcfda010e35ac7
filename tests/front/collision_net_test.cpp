// tests/front/collision_net_test.cpp: the collision safety net (not in the
// paper): a contact joins two front parts that meet outside every protecting
// sphere.
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

#include "tests/front/front_fixture.h"
#include "core/errors.h"
#include "morse/critical_points.h"
#include "morse/morse_smale_complex.h"
#include "skin/skin_surface.h"
#include "tests/skin/skin_test_util.h"

using namespace skinmesh;
using namespace skinmesh::front::detail;
using namespace skinmesh::test;

TEST_SUITE("front operations") {

TEST_CASE("contact: without the saddle's hold, the safety net joins the two fronts at the neck") {
  Fixture fx({{Vec3(0, 0, 0), w_of(1.6, 1.4)}, {Vec3(4.5, 0.8, 0.3), w_of(1.6, 1.4)}});
  // Silence every saddle: nothing holds the fronts, which meet outside any
  // protecting sphere, the situation the safety net exists for.
  for (std::size_t i = 0; i < fx.ms.critical.size(); ++i)
    if (fx.ms.critical[i].kind == morse::CriticalKind::Saddle) fx.ms.live[i] = 0;
  FrontState s(fx.skin, fx.ms, fx.opt);
  create_initial_front(s);
  REQUIRE(front_loops(s) == 2);
  bool seen = false;
  for (int step = 0; step < 20000 && !seen; ++step) {
    const std::size_t contacts = s.stats.contacts, loops = front_loops(s);
    const long chi = euler(s);
    REQUIRE(departure_step(s));
    if (s.stats.contacts == contacts) continue;
    seen = true;
    CHECK(s.stats.contacts == contacts + 1);
    CHECK(front_loops(s) == loops - 1);  // the two bowls' fronts are one now
    CHECK(euler(s) == chi - 1);          // one ladder row: 3 edges, 2 faces
    check_partial_mesh(s, fx.skin);
  }
  CHECK(seen);
}

}  // TEST_SUITE
TEST_CASE("explore collisions") {
  for (int variant = 0; variant < 4; ++variant) {
    Fixture fx(variant == 3 ? test::three_ball_ring() : std::vector<geometry::WeightedPoint>{{Vec3(0, 0, 0), w_of(1.6, 1.4)}, {Vec3(4.5, 0.8, 0.3), w_of(1.6, 1.4)}});
    if (variant < 3)
      for (std::size_t i = 0; i < fx.ms.critical.size(); ++i)
        if (fx.ms.critical[i].kind == morse::CriticalKind::Saddle) fx.ms.live[i] = 0;
    if (variant == 1) fx.opt.contact_radius = 0;
    if (variant == 2) fx.opt.contact_radius = 0.5;
    FrontState s(fx.skin, fx.ms, fx.opt);
    create_initial_front(s);
    int step = 0, first = -1;
    try {
    for (; step < 20000; ++step) {
      const std::size_t c = s.stats.collisions;
      if (!departure_step(s)) break;
      if (s.stats.collisions > c && first < 0) first = step;
    }
    } catch (const std::exception& e) { MESSAGE("threw " << e.what()); }
    MESSAGE("variant " << variant << " steps " << step << " first " << first << " coll " << s.stats.collisions << " contacts " << s.stats.contacts << " deferred " << s.stats.deferred << " held " << s.stats.held << " stuck " << s.stats.stuck);
  }
}
