// tests/front/sweep_test.cpp: the driver of Algorithm 1: its debugging aids
// (trace, max_steps, dump, paranoid) and the refusal of a tangent-disc factor
// outside the window of C and Q.
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

TEST_CASE("debugging aids: the trace names the operations, max_steps stops and dumps, paranoid passes") {
  Fixture fx({{Vec3(0, 0, 0), w_of(1.6, 1.4)}, {Vec3(4.5, 0.8, 0.3), w_of(1.6, 1.4)}});
  std::vector<std::string> lines;
  fx.opt.trace = [&lines](const std::string& line) { lines.push_back(line); };
  fx.opt.paranoid = true;
  const front::SweepResult res = front::sweep_mesh(fx.skin, fx.ms, fx.opt);
  auto traced = [&](const std::string& word) {
    return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.rfind(word, 0) == 0; });
  };
  CHECK(traced("hold v"));
  CHECK(traced("bridge saddle"));
  CHECK(traced("seal loop of"));
  CHECK(res.stats.bridges == 2);
  CHECK(res.mesh.boundary_loops().empty());

  const std::string dump = (std::filesystem::temp_directory_path() / "skinmesh_max_steps_dump.ply").string();
  front::SweepOptions stop;
  stop.max_steps = 5;
  stop.dump_path = dump;
  std::filesystem::remove(dump);
  CHECK_THROWS_AS(front::sweep_mesh(fx.skin, fx.ms, stop), TopologyError);
  CHECK(std::filesystem::exists(dump));
  std::filesystem::remove(dump);
}

TEST_CASE("a tangent-disc factor outside the window of C and Q is refused") {
  Fixture fx({{Vec3(0, 0, 0), w_of(1.6, 1.4)}});
  fx.opt.disc_factor = 0.25;  // above 0.2077
  CHECK_THROWS_AS(front::sweep_mesh(fx.skin, fx.ms, fx.opt), std::invalid_argument);
  fx.opt.disc_factor = 0.1;  // below 0.1074
  CHECK_THROWS_AS(front::sweep_mesh(fx.skin, fx.ms, fx.opt), std::invalid_argument);
}

}  // TEST_SUITE
