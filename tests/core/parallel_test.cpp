// tests/core/parallel_test.cpp: parallel_for visits every item once, for
// every thread count and grain, and rethrows the exception a plain loop would
// have met first.
#include <doctest/doctest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/parallel.h"

using namespace skinmesh;

TEST_SUITE("core") {

TEST_CASE("parallel_for visits every item exactly once, whatever the threads and the grain") {
  for (int threads : {1, 2, 3, 8})
    for (std::size_t grain : {1u, 3u, 64u, 1000u})
      for (std::size_t n : {0u, 1u, 7u, 257u}) {
        CAPTURE(threads);
        CAPTURE(grain);
        CAPTURE(n);
        std::vector<std::atomic<int>> hits(n);
        parallel_for(n, threads, grain, [&](std::size_t i) { hits[i].fetch_add(1); });
        for (std::size_t i = 0; i < n; ++i) CHECK(hits[i].load() == 1);
      }
}

TEST_CASE("parallel_for rethrows the exception of the lowest block, as a plain loop would") {
  for (int threads : {1, 2, 4}) {
    CAPTURE(threads);
    std::string what;
    try {
      // Items 30 and 90 throw; with grain 10 they are in blocks 3 and 9.
      parallel_for(100, threads, 10, [](std::size_t i) {
        if (i == 90 || i == 30) throw std::runtime_error("item " + std::to_string(i));
      });
    } catch (const std::runtime_error& e) {
      what = e.what();
    }
    CHECK(what == "item 30");
  }
}

TEST_CASE("parallel_select lists the indices a plain loop would, in order, whatever the threads and the grain") {
  // A predicate with runs, gaps and an irregular pattern (i*i mod 7 < 3).
  auto pred = [](std::size_t i) { return (i * i) % 7 < 3 || (i >= 500 && i < 520); };
  for (int threads : {1, 2, 3, 8})
    for (std::size_t grain : {1u, 5u, 64u, 4096u})
      for (std::size_t n : {0u, 1u, 9u, 1000u}) {
        CAPTURE(threads);
        CAPTURE(grain);
        CAPTURE(n);
        std::vector<std::size_t> plain;
        for (std::size_t i = 0; i < n; ++i)
          if (pred(i)) plain.push_back(i);
        CHECK(parallel_select(n, threads, grain, pred) == plain);
      }
}

TEST_CASE("thread_count: a positive request is kept, 0 means every core") {
  CHECK(thread_count(3) == 3);
  CHECK(thread_count(0) >= 1);
  CHECK(thread_count(-1) >= 1);
}

}  // TEST_SUITE
