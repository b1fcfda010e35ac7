// geometry/triangulation/key_index.h: KeyIndex, a table numbering 63-bit keys densely in the
// order they are first added — the hash behind the point grids' cells
// (geometry/triangulation/point_grid.h).
#pragma once

#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace skinmesh::geometry {

/// Numbers keys below 2^63 densely, 0, 1, 2, ..., in the order they are first
/// added: an open-addressing table (linear probing, at most half full,
/// Fibonacci hashing; the all-ones key marks an empty slot). No allocation per
/// key. Callers keep per-key data in arrays indexed by the number: the point
/// grids and the mixed complex look keys up millions of times, and a node per
/// key cost more than the lookup ([measured] papers/bench/profile.md, "After").
class KeyIndex {
 public:
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

  /// Room for `expected` keys before the first growth.
  explicit KeyIndex(std::size_t expected = 0) { rehash(expected); }

  /// The number of key k (< 2^63), or kNone if it was never added.
  std::uint32_t find(std::uint64_t k) const {
    const Slot& s = slots_[probe(k)];
    return s.key == k ? s.number : kNone;
  }
  /// The number of key k (< 2^63), and true if k was new (its number is then
  /// the previous size()).
  std::pair<std::uint32_t, bool> find_or_add(std::uint64_t k) {
    if (2 * (std::size_t(size_) + 1) > slots_.size()) rehash(slots_.size());  // doubles
    Slot& s = slots_[probe(k)];
    if (s.key == k) return {s.number, false};
    s.key = k;
    s.number = size_++;
    return {s.number, true};
  }
  /// Number of keys added.
  std::uint32_t size() const { return size_; }
  /// Bytes of the table.
  std::size_t memory_bytes() const { return slots_.capacity() * sizeof(Slot); }

 private:
  static constexpr std::uint64_t kEmpty = std::numeric_limits<std::uint64_t>::max();
  struct Slot {
    std::uint64_t key = kEmpty;
    std::uint32_t number = kNone;
  };
  std::size_t home(std::uint64_t k) const {
    // Fibonacci hashing: the high bits of k times 2^64 / golden ratio.
    return static_cast<std::size_t>((k * 0x9E3779B97F4A7C15ull) >> shift_);
  }
  /// The slot holding key k, or the empty slot where it would go.
  std::size_t probe(std::uint64_t k) const {
    const std::size_t mask = slots_.size() - 1;
    std::size_t i = home(k);
    while (slots_[i].key != k && slots_[i].key != kEmpty) i = (i + 1) & mask;
    return i;
  }
  /// At least 2 `expected` slots, a power of two (64 at least); the keys added
  /// so far are placed again.
  void rehash(std::size_t expected) {
    std::size_t n = 64;
    int bits = 6;
    while (n < 2 * expected) n *= 2, ++bits;
    if (n <= slots_.size()) return;
    std::vector<Slot> old(n);
    old.swap(slots_);
    shift_ = 64 - bits;
    for (const Slot& s : old)
      if (s.key != kEmpty) slots_[probe(s.key)] = s;
  }
  std::vector<Slot> slots_;
  std::uint32_t size_ = 0;
  int shift_ = 64 - 6;  ///< 64 - log2(slots_.size())
};

}  // namespace skinmesh::geometry
