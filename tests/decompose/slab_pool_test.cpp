// tests/decompose/slab_pool_test.cpp: the slabs' threads (decompose/slab_pool.h)
// with a sweep that only names its slab: each round gets its own slabs' outcomes
// in its order on every thread count, a slab guessed while another runs is swept
// ahead on the idle thread and taken by the next round without a second sweep,
// the round's watch sees outcomes as they come, a slab given up is cancelled,
// and a sweep's exception reaches the round.
#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/errors.h"
#include "decompose/slab_pool.h"

using namespace skinmesh;
using decompose::SlabKey;
using decompose::SlabOutcome;
using decompose::SlabPool;

namespace {

std::string name(const SlabKey& key) { return std::to_string(key.first) + "-" + std::to_string(key.second); }

SlabOutcome named(const SlabKey& key) {
  SlabOutcome o;
  o.error = name(key);
  return o;
}

/// Counts the sweeps of each slab.
struct Calls {
  std::mutex mutex;
  std::map<SlabKey, int> count;
  void add(const SlabKey& key) {
    const std::lock_guard<std::mutex> lock(mutex);
    ++count[key];
  }
};

}  // namespace

TEST_CASE("slab pool: each round's outcomes in its keys' order, on every thread count") {
  for (int threads : {1, 2, 4}) {
    Calls calls;
    SlabPool pool(threads, [&](const SlabKey& key, const std::atomic<bool>&, const std::function<void(double)>&) {
      calls.add(key);
      return named(key);
    });
    const std::vector<SlabKey> keys{{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}};
    const std::vector<std::size_t> order{4, 2, 0, 1, 3};
    std::vector<double> reported;
    const std::vector<SlabOutcome> out = pool.sweep(keys, order, {}, [&](double f) { reported.push_back(f); });
    REQUIRE(out.size() == keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) CHECK(out[i].error == name(keys[i]));
    for (const SlabKey& key : keys) CHECK(calls.count[key] == 1);
    REQUIRE(!reported.empty());
    for (std::size_t i = 1; i < reported.size(); ++i) CHECK(reported[i] >= reported[i - 1]);
    CHECK(reported.back() == doctest::Approx(1.0));
    // A second round with other slabs.
    const std::vector<SlabKey> merged{{0, 2}};
    CHECK(pool.sweep(merged, {0}, {}, {})[0].error == "0-2");
    CHECK(pool.ahead_used() == 0);
  }
}

TEST_CASE("slab pool: a slab guessed while the round's last one runs is swept ahead and taken") {
  // Two threads: one sweeps the long slab (1,2), which waits until the
  // guessed slab (0,3) has started; the other sweeps (0,1), then, with no
  // slab of the round left, the guess. Without sweeps ahead the long slab
  // would wait for nothing and the check below fails.
  Calls calls;
  std::mutex mutex;
  std::condition_variable started;
  bool ahead_started = false, watched = false;
  SlabPool pool(2, [&](const SlabKey& key, const std::atomic<bool>&, const std::function<void(double)>&) {
    calls.add(key);
    if (key == SlabKey{0, 3}) {
      const std::lock_guard<std::mutex> lock(mutex);
      ahead_started = true;
      started.notify_all();
    }
    if (key == SlabKey{1, 2}) {
      std::unique_lock<std::mutex> lock(mutex);
      started.wait_for(lock, std::chrono::seconds(20), [&] { return ahead_started && watched; });
    }
    return named(key);
  });
  const std::vector<SlabKey> round{{1, 2}, {0, 1}};
  const SlabPool::Guess guess = [](const std::vector<const SlabOutcome*>& known) {
    // (0,1) failed: its cut 1 goes, and (0,2) would be next; (0,3) stands in for it.
    return known[1] ? std::vector<SlabKey>{{0, 3}} : std::vector<SlabKey>{};
  };
  // The watch runs on this thread and sees (0,1)'s outcome while (1,2) runs.
  const std::thread::id caller = std::this_thread::get_id();
  bool watched_here = true;
  const SlabPool::Watch watch = [&](const std::vector<const SlabOutcome*>& known) {
    watched_here = watched_here && std::this_thread::get_id() == caller;
    if (!known[1] || known[0]) return;
    const std::lock_guard<std::mutex> lock(mutex);
    watched = known[1]->error == "0-1";
    started.notify_all();
  };
  const std::vector<SlabOutcome> first = pool.sweep(round, {0, 1}, guess, {}, watch);
  CHECK(first[0].error == "1-2");
  CHECK(first[1].error == "0-1");
  {
    const std::lock_guard<std::mutex> lock(mutex);
    CHECK(ahead_started);
    CHECK(watched);
  }
  CHECK(watched_here);
  const std::vector<SlabOutcome> second = pool.sweep({{0, 3}}, {0}, {}, {});
  CHECK(second[0].error == "0-3");
  CHECK(calls.count[{0, 3}] == 1);
  CHECK(pool.ahead_used() == 1);
}

TEST_CASE("slab pool: a slab swept ahead and given up is cancelled, and a round never waits for it") {
  std::atomic<bool> saw_cancel{false};
  std::mutex mutex;
  std::condition_variable started;
  bool ahead_running = false;
  SlabPool pool(2, [&](const SlabKey& key, const std::atomic<bool>& cancel, const std::function<void(double)>&) {
    if (key == SlabKey{0, 9}) {
      {
        const std::lock_guard<std::mutex> lock(mutex);
        ahead_running = true;
        started.notify_all();
      }
      // A sweep that would not end on its own: only the cancel stops it.
      while (!cancel.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      saw_cancel = true;
      throw Cancelled();
    }
    if (key == SlabKey{1, 2}) {  // the round's last slab, until the guess runs
      std::unique_lock<std::mutex> lock(mutex);
      started.wait_for(lock, std::chrono::seconds(20), [&] { return ahead_running; });
    }
    return named(key);
  });
  const SlabPool::Guess guess = [](const std::vector<const SlabOutcome*>&) { return std::vector<SlabKey>{{0, 9}}; };
  const std::vector<SlabOutcome> out = pool.sweep({{0, 1}, {1, 2}}, {0, 1}, guess, {});
  CHECK(out[1].error == "1-2");
  {
    const std::lock_guard<std::mutex> lock(mutex);
    REQUIRE(ahead_running);
  }
  // The next round asks for other slabs while the guess still runs.
  CHECK(pool.sweep({{2, 3}}, {0}, {}, {})[0].error == "2-3");
  pool.forget([](const SlabKey& key) { return key != SlabKey{0, 9}; });
  CHECK(saw_cancel);
  CHECK(pool.ahead_used() == 0);
}

TEST_CASE("slab pool: a sweep's exception reaches the round that asks for the slab") {
  for (int threads : {1, 2}) {
    SlabPool pool(threads, [](const SlabKey& key, const std::atomic<bool>&, const std::function<void(double)>&) {
      if (key == SlabKey{1, 2}) throw std::runtime_error("out of memory, say");
      return named(key);
    });
    CHECK_THROWS_WITH_AS(pool.sweep({{0, 1}, {1, 2}, {2, 3}}, {0, 1, 2}, {}, {}), "out of memory, say",
                         std::runtime_error);
    // The pool still serves the next round.
    CHECK(pool.sweep({{0, 3}}, {0}, {}, {})[0].error == "0-3");
  }
}
