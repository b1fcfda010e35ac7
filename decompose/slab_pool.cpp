// decompose/slab_pool.cpp: the threads of the decomposed sweep's slabs
// (decompose/slab_pool.h). The pool's state is under one lock; a slab is
// swept outside it, into its entry, which no other thread erases while the
// sweep runs (std::map keeps it in place).
// Notes: papers/decompose/README.md ("Threads and determinism")
#include "decompose/slab_pool.h"

#include <algorithm>
#include <chrono>
#include <utility>

#include "core/errors.h"

namespace skinmesh::decompose {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

SlabPool::SlabPool(int threads, Sweep sweep) : threads_(threads), sweep_(std::move(sweep)) {
  if (threads_ <= 1) return;
  threads_pool_.reserve(static_cast<std::size_t>(threads_));
  for (int t = 0; t < threads_; ++t) threads_pool_.emplace_back([this] { work(); });
}

SlabPool::~SlabPool() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    for (auto& [key, e] : entries_)
      if (!e.done) e.cancel = true;
  }
  changed_.notify_all();
  for (std::thread& t : threads_pool_) t.join();
}

const SlabKey* SlabPool::next_slab() {
  while (!to_start_.empty()) {
    const SlabKey key = to_start_.back();
    to_start_.pop_back();
    // A slab swept ahead (done or running) was marked asked by the round.
    if (auto [it, made] = entries_.try_emplace(key); made) {
      it->second.asked = true;
      return &it->first;
    }
  }
  if (!round_ || !guess_) return nullptr;
  std::vector<const SlabOutcome*> known(round_->size(), nullptr);
  for (std::size_t i = 0; i < round_->size(); ++i)
    if (auto it = entries_.find((*round_)[i]); it != entries_.end() && it->second.done && !it->second.error)
      known[i] = &it->second.outcome;
  for (const SlabKey& key : (*guess_)(known))
    if (auto [it, made] = entries_.try_emplace(key); made) {
      it->second.ahead = true;
      return &it->first;
    }
  return nullptr;
}

void SlabPool::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    const SlabKey* next = next_slab();
    if (!next) {
      changed_.wait(lock);
      continue;
    }
    const SlabKey key = *next;
    Entry& e = entries_.at(key);
    lock.unlock();
    const auto start = std::chrono::steady_clock::now();
    SlabOutcome outcome;
    std::exception_ptr error;
    try {
      outcome = sweep_(key, e.cancel, {});
    } catch (...) {
      error = std::current_exception();
    }
    const double seconds = seconds_since(start);
    lock.lock();
    if (e.cancel) {
      // Given up while it ran (forget() or the destructor waits for it).
      ahead_unused_seconds_ += seconds;
      entries_.erase(key);
    } else {
      e.done = true;
      e.outcome = std::move(outcome);
      e.error = error;
      e.seconds = seconds;
    }
    changed_.notify_all();
  }
}

std::vector<SlabOutcome> SlabPool::sweep(const std::vector<SlabKey>& keys, const std::vector<std::size_t>& order,
                                         const Guess& guess, const std::function<void(double)>& progress,
                                         const Watch& watch) {
  std::vector<SlabOutcome> out(keys.size());
  const double n = static_cast<double>(std::max<std::size_t>(keys.size(), 1));
  if (threads_ <= 1) {
    const std::atomic<bool> never{false};
    for (std::size_t k = 0; k < order.size(); ++k) {
      std::function<void(double)> within;
      if (progress) within = [&progress, k, n](double f) { progress((static_cast<double>(k) + f) / n); };
      out[order[k]] = sweep_(keys[order[k]], never, within);
    }
    if (progress) progress(1.0);
    return out;
  }

  std::unique_lock<std::mutex> lock(mutex_);
  for (const SlabKey& key : keys)
    if (auto it = entries_.find(key); it != entries_.end()) it->second.asked = true;
  to_start_.clear();
  for (std::size_t k = order.size(); k-- > 0;) to_start_.push_back(keys[order[k]]);
  round_ = &keys;
  guess_ = guess ? &guess : nullptr;
  changed_.notify_all();
  std::size_t reported = 0;
  for (;;) {
    std::size_t done = 0;
    std::vector<const SlabOutcome*> known(keys.size(), nullptr);
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (auto it = entries_.find(keys[i]); it != entries_.end() && it->second.done) {
        ++done;
        if (!it->second.error) known[i] = &it->second.outcome;
      }
    if (done == keys.size()) break;
    if (done != reported) {
      // A done entry of the round is neither written nor erased before the
      // round ends: `known` may be read without the lock.
      reported = done;
      lock.unlock();
      if (progress) progress(static_cast<double>(done) / n);
      if (watch) watch(known);
      lock.lock();
      continue;
    }
    changed_.wait(lock);
  }
  // Slabs swept ahead may have been done before their turn came: none of
  // this round's is left to start.
  to_start_.clear();
  round_ = nullptr;
  guess_ = nullptr;
  std::exception_ptr first;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    auto it = entries_.find(keys[i]);
    Entry& e = it->second;
    if (e.error && !first) first = e.error;
    if (e.ahead) ++ahead_used_;
    out[i] = std::move(e.outcome);
    entries_.erase(it);
  }
  lock.unlock();
  if (first) std::rethrow_exception(first);
  if (progress) progress(1.0);
  return out;
}

void SlabPool::forget(const std::function<bool(const SlabKey&)>& keep) {
  std::unique_lock<std::mutex> lock(mutex_);
  for (auto it = entries_.begin(); it != entries_.end();) {
    Entry& e = it->second;
    if (e.asked || keep(it->first)) {
      ++it;
    } else if (e.done) {
      ahead_unused_seconds_ += e.seconds;
      it = entries_.erase(it);
    } else {
      e.cancel = true;
      ++it;
    }
  }
  changed_.wait(lock, [this] {
    return std::none_of(entries_.begin(), entries_.end(), [](const auto& p) { return p.second.cancel.load(); });
  });
}

std::size_t SlabPool::ahead_used() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return ahead_used_;
}

double SlabPool::ahead_unused_seconds() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return ahead_unused_seconds_;
}

}  // namespace skinmesh::decompose
