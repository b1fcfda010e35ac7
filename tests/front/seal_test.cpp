// tests/front/seal_test.cpp: seal() closes each hole left at the maxima, gluing in a disc.
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

TEST_CASE("seal closes each hole left at the maxima; the mesh is closed with chi = 2") {
  Fixture fx({{Vec3(0, 0, 0), w_of(1.6, 1.4)}, {Vec3(4.5, 0.8, 0.3), w_of(1.6, 1.4)}});
  FrontState s(fx.skin, fx.ms, fx.opt);
  create_initial_front(s);
  while (departure_step(s) || release_saddles(s)) {
  }
  check_partial_mesh(s, fx.skin);
  std::size_t loops = front_loops(s);
  REQUIRE(loops >= 1);
  while (loops > 0) {
    const long chi = euler(s);
    const std::size_t seals = s.stats.seals;
    seal_loop(s, s.mesh.boundary_loops().front().front(), fx.opt.max_hole_enlargements);
    CHECK(front_loops(s) == loops - 1);
    CHECK(euler(s) == chi + 1);  // a disc glued in
    CHECK(s.stats.seals == seals + 1);
    loops = front_loops(s);
  }
  check_partial_mesh(s, fx.skin);
  CHECK(euler(s) == 2);
  for (Vertex v : s.mesh.vertices())
    if (!s.mesh.is_deleted(v)) CHECK(s.state[v] == VState::Interior);
}

}  // TEST_SUITE
