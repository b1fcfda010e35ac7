// core/parallel.h: the project's threads — how many to use, and a
// deterministic parallel loop. Every use keeps the output independent of the
// thread count: an item writes only its own slots, and the caller merges them
// in item order (papers/bench/profile.md, "Threads").
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace skinmesh {

/// The number of threads for a request: `requested` if positive, else every
/// core of the machine (std::thread::hardware_concurrency(), at least 1).
inline int thread_count(int requested) {
  if (requested > 0) return requested;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

/// Calls fn(i) once for every i in [0, n), on up to `threads` threads (the
/// calling thread included; threads <= 1 or a small n: all on the calling
/// thread, in order). Items are handed out in blocks of `grain` consecutive
/// indices. fn must only write state owned by item i. If items throw, every
/// block still runs to its end or its first exception, and the exception of
/// the lowest block is rethrown after all threads joined — the one a plain
/// loop would have thrown first, whatever the thread count.
template <class Fn>
void parallel_for(std::size_t n, int threads, std::size_t grain, Fn&& fn) {
  grain = std::max<std::size_t>(grain, 1);
  const std::size_t blocks = (n + grain - 1) / grain;
  const std::size_t workers = std::min<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), blocks);
  if (workers <= 1) {
    for (std::size_t i = 0; i < n; ++i) fn(i);
    return;
  }
  std::vector<std::exception_ptr> errors(blocks);
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t b; (b = next.fetch_add(1, std::memory_order_relaxed)) < blocks;) {
      try {
        for (std::size_t i = b * grain, end = std::min(n, i + grain); i < end; ++i) fn(i);
      } catch (...) {
        errors[b] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (std::size_t t = 1; t < workers; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

/// The indices i in [0, n) for which pred(i) holds, in increasing order —
/// the list a plain loop would build — computed on up to `threads` threads:
/// each block of `grain` consecutive indices collects its own, and the blocks
/// are joined in order, so the result does not depend on the thread count.
/// pred must only read shared state. Exceptions as parallel_for().
template <class Pred>
std::vector<std::size_t> parallel_select(std::size_t n, int threads, std::size_t grain, Pred&& pred) {
  grain = std::max<std::size_t>(grain, 1);
  std::vector<std::size_t> out;
  if (threads <= 1 || n <= grain) {
    for (std::size_t i = 0; i < n; ++i)
      if (pred(i)) out.push_back(i);
    return out;
  }
  const std::size_t blocks = (n + grain - 1) / grain;
  std::vector<std::vector<std::size_t>> found(blocks);
  parallel_for(blocks, threads, 1, [&](std::size_t b) {
    for (std::size_t i = b * grain, end = std::min(n, i + grain); i < end; ++i)
      if (pred(i)) found[b].push_back(i);
  });
  std::size_t total = 0;
  for (const auto& f : found) total += f.size();
  out.reserve(total);
  for (const auto& f : found) out.insert(out.end(), f.begin(), f.end());
  return out;
}

}  // namespace skinmesh
