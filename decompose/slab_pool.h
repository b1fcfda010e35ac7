// decompose/slab_pool.h: how the decomposed sweep's slabs are carried out on
// the threads — asked for round by round, and swept ahead on a thread that
// would otherwise wait for a round's last slab. What a slab is and how the
// rounds decide belong to decompose/decomposed.cpp; this layer decides only
// when and on which thread a slab is swept.
// Notes: papers/decompose/README.md ("Threads and determinism")
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

#include "decompose/decomposed.h"

namespace skinmesh::decompose {

/// The threads that sweep the slabs of the decomposed sweep's rounds. A round
/// asks for its slabs (sweep()) and waits for them; a thread with no slab of
/// the round left to start asks the round's guess for slabs a later round may
/// need (merged slabs, given the failures known so far or feared) and sweeps
/// one ahead. Its outcome is kept until a round asks for it, or until
/// forget() gives it up (its sweep is cancelled if it still runs). A slab's outcome
/// depends on its key only (its two cuts), so a guess changes when a slab is
/// swept, never what it becomes: the mesh depends neither on the guesses nor
/// on the thread count. With one thread there is no guess and no thread of
/// its own: the slabs are swept on the calling thread, in the order asked.
class SlabPool {
 public:
  /// Sweeps the slab `key`. Once `cancel` is set it may throw skin::Cancelled
  /// (the outcome is no longer wanted); `progress`, when not empty, takes
  /// the fraction of the slab done. Other exceptions reach the round that
  /// asks for the slab.
  using Sweep = std::function<SlabOutcome(const SlabKey& key, const std::atomic<bool>& cancel,
                                          const std::function<void(double)>& progress)>;
  /// Given, per slab the round asked for, its outcome if known (nullptr:
  /// not yet), the slabs worth sweeping ahead, the most wanted first. Called
  /// on the pool's threads under its lock: it must only read.
  using Guess = std::function<std::vector<SlabKey>(const std::vector<const SlabOutcome*>& known)>;

  /// A pool of `threads` threads (<= 1: none; every slab on the caller's).
  SlabPool(int threads, Sweep sweep);
  /// Cancels the slabs swept ahead that still run and joins the threads.
  ~SlabPool();
  SlabPool(const SlabPool&) = delete;
  SlabPool& operator=(const SlabPool&) = delete;

  /// Called on the calling thread while the round runs, each time outcomes
  /// have come in, with every outcome known so far (as Guess's `known`;
  /// they stay put until the round ends). Not called with one thread.
  using Watch = std::function<void(const std::vector<const SlabOutcome*>& known)>;

  /// The outcomes of `keys`, in that order: each taken from the slabs swept
  /// ahead, or swept now, started in the order `order` (a permutation of
  /// keys' indices). `guess` and `watch` may be empty (no slab swept ahead,
  /// nothing watches). `progress` takes the fraction of the round done, on
  /// the calling thread. Rethrows the exception of the first key (in key
  /// order) whose sweep threw one.
  std::vector<SlabOutcome> sweep(const std::vector<SlabKey>& keys, const std::vector<std::size_t>& order,
                                 const Guess& guess, const std::function<void(double)>& progress,
                                 const Watch& watch = {});

  /// Gives up every slab swept ahead for which `keep` is false: its outcome
  /// is freed, or its sweep cancelled and waited for.
  void forget(const std::function<bool(const SlabKey&)>& keep);

  /// The slabs swept ahead that a round took, and the wall-clock seconds of
  /// those given up (freed or cancelled).
  std::size_t ahead_used() const;
  double ahead_unused_seconds() const;

 private:
  struct Entry {
    bool done = false;
    bool asked = false;  ///< by the round that runs
    bool ahead = false;  ///< started as a guess
    std::atomic<bool> cancel{false};
    SlabOutcome outcome;
    std::exception_ptr error;
    double seconds = 0;  ///< the sweep's wall clock, done or cancelled
  };

  /// The thread's loop: the round's slabs first, then guesses.
  void work();
  /// The next slab to start, its entry made (under the lock); nullptr when
  /// there is none.
  const SlabKey* next_slab();

  int threads_;
  Sweep sweep_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::map<SlabKey, Entry> entries_;
  std::vector<SlabKey> to_start_;  ///< the round's slabs not started, last first
  const std::vector<SlabKey>* round_ = nullptr;
  const Guess* guess_ = nullptr;
  bool stop_ = false;
  std::size_t ahead_used_ = 0;
  double ahead_unused_seconds_ = 0;
  std::vector<std::thread> threads_pool_;
};

}  // namespace skinmesh::decompose
