// tests/core/stage_clock_test.cpp: StageClock reports each stage's start,
// progress and end, in order, and times the stages back to back.
#include <doctest/doctest.h>

#include <string>
#include <utility>
#include <vector>

#include "core/stage_clock.h"

TEST_SUITE("core") {

TEST_CASE("stage clock: reports in order, seconds per ended stage") {
  std::vector<std::pair<std::string, double>> reports;
  skinmesh::StageClock clock([&reports](const std::string& stage, double f) { reports.emplace_back(stage, f); });
  clock.begin("skin");
  clock.end("skin");
  clock.report("sweep", 0.5);
  clock.end("sweep");
  const std::vector<std::pair<std::string, double>> expected = {
      {"skin", 0.0}, {"skin", 1.0}, {"sweep", 0.5}, {"sweep", 1.0}};
  CHECK(reports == expected);
  REQUIRE(clock.seconds().size() == 2);
  CHECK(clock.seconds()[0].first == "skin");
  CHECK(clock.seconds()[1].first == "sweep");
  for (const auto& [stage, s] : clock.seconds()) CHECK(s >= 0);
  skinmesh::StageClock silent;  // no callback: reports are dropped, seconds kept
  silent.begin("x");
  silent.end("x");
  CHECK(silent.seconds().size() == 1);
}

}  // TEST_SUITE
