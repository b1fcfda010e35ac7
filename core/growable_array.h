// core/growable_array.h: a contiguous array that grows with realloc, for
// the half-edge mesh's property arrays (geometry/mesh/surface_mesh.h).
// Why: papers/bench/profile.md ("After", the memory rows): large property
// arrays grow in place without a copy and go back to the system when freed.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <new>
#include <span>
#include <type_traits>
#include <utility>

// Mapped blocks on Linux, except under AddressSanitizer, which checks the
// bounds of heap blocks and not of pages mapped by hand (make sanitize).
#if defined(__SANITIZE_ADDRESS__)
#define SKINMESH_GROWABLE_ARRAY_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)  // clang
#define SKINMESH_GROWABLE_ARRAY_ASAN 1
#endif
#endif
#if defined(__linux__) && !defined(SKINMESH_GROWABLE_ARRAY_ASAN)
#define SKINMESH_GROWABLE_ARRAY_MMAP 1
#include <sys/mman.h>  // mmap, mremap, munmap, madvise
#include <unistd.h>    // sysconf
#else
#define SKINMESH_GROWABLE_ARRAY_MMAP 0
#endif

namespace skinmesh {

/// True for the value types GrowableArray may move with realloc: trivially
/// copyable types, and Eigen's fixed-size vectors of doubles (plain arrays of
/// doubles with no pointer into themselves; their copy constructor is
/// user-provided, so the trait has to say so).
template <class T>
inline constexpr bool kRelocatable = std::is_trivially_copyable_v<T>;
template <int N>
inline constexpr bool kRelocatable<Eigen::Matrix<double, N, 1>> = true;

/// A contiguous array of T (kRelocatable<T>, trivially destructible). Blocks of
/// 64 KiB and more grow by an eighth of their capacity at a time; they are mapped
/// pages of their own (Linux: mmap), grown with mremap, which moves the pages
/// instead of copying them: the array never holds an old and a new block at
/// once and needs at most 1.125 times its size, where std::vector (doubling,
/// copying) needs up to 3 times at the moment it grows, and its memory goes
/// back to the system when freed. Smaller blocks use malloc/realloc and
/// double. Elsewhere than Linux, and under AddressSanitizer, every block uses
/// realloc and doubles. Indices, data() and spans are
/// invalidated by growth, as with std::vector. Throws std::bad_alloc when
/// memory runs out.
template <class T>
class GrowableArray {
  static_assert(kRelocatable<T> && std::is_trivially_destructible_v<T>,
                "GrowableArray: T must be relocatable and trivially destructible");

 public:
  using value_type = T;
  using reference = T&;
  using const_reference = const T&;

  GrowableArray() = default;
  GrowableArray(const GrowableArray& o) { *this = o; }
  GrowableArray(GrowableArray&& o) noexcept
      : data_(std::exchange(o.data_, nullptr)), size_(std::exchange(o.size_, 0)), cap_(std::exchange(o.cap_, 0)) {}
  GrowableArray& operator=(const GrowableArray& o) {
    if (this == &o) return *this;
    size_ = 0;
    reserve(o.size_);
    if (o.size_) std::memcpy(static_cast<void*>(data_), static_cast<const void*>(o.data_), o.size_ * sizeof(T));
    size_ = o.size_;
    return *this;
  }
  GrowableArray& operator=(GrowableArray&& o) noexcept {
    if (this == &o) return *this;
    release(data_, cap_);
    data_ = std::exchange(o.data_, nullptr);
    size_ = std::exchange(o.size_, 0);
    cap_ = std::exchange(o.cap_, 0);
    return *this;
  }
  ~GrowableArray() { release(data_, cap_); }

  std::size_t size() const { return size_; }
  std::size_t capacity() const { return cap_; }
  bool empty() const { return size_ == 0; }
  T* data() { return data_; }
  const T* data() const { return data_; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  T* begin() { return data_; }
  T* end() { return data_ + size_; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }
  T& back() { return data_[size_ - 1]; }
  operator std::span<T>() { return {data_, size_}; }
  operator std::span<const T>() const { return {data_, size_}; }

  /// Appends a copy of v (v may be an element of this array).
  void push_back(const T& v) {
    if (size_ == cap_) {
      const T copy = v;
      grow(size_ + 1);
      ::new (static_cast<void*>(data_ + size_)) T(copy);
    } else {
      ::new (static_cast<void*>(data_ + size_)) T(v);
    }
    ++size_;
  }
  void pop_back() { --size_; }
  /// Sets the size to n; new elements are copies of v.
  void resize(std::size_t n, const T& v) {
    if (n > cap_) grow(n);
    for (std::size_t i = size_; i < n; ++i) ::new (static_cast<void*>(data_ + i)) T(v);
    size_ = n;
  }
  /// Sets the size to n; new elements are value-initialized (T()), as by
  /// std::vector::resize(n).
  void resize(std::size_t n) {
    if (n > cap_) grow(n);
    for (std::size_t i = size_; i < n; ++i) ::new (static_cast<void*>(data_ + i)) T();
    size_ = n;
  }
  /// Capacity at least n (exactly n if it grows).
  void reserve(std::size_t n) {
    if (n > cap_) reallocate(n);
  }
  void clear() { size_ = 0; }
  /// Gives the whole pages that hold only elements [0, n) back to the system
  /// (a mapped block's; a no-op for the others and elsewhere than Linux):
  /// their values are lost, the size and capacity stay. For a consumer that
  /// has copied the front of the array and reads only the elements from n on
  /// (SurfaceMesh::append_consuming): the two copies never coexist.
  void discard_front(std::size_t n) {
#if SKINMESH_GROWABLE_ARRAY_MMAP
    if (!mapped(cap_)) return;
    static const std::size_t page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
    const std::size_t bytes = std::min(n, size_) * sizeof(T) / page * page;
    // MADV_DONTNEED on private anonymous pages cannot fail on a valid range;
    // if it did, the pages would stay resident and nothing else changes.
    if (bytes > 0) (void)::madvise(static_cast<void*>(data_), bytes, MADV_DONTNEED);
#else
    (void)n;
#endif
  }
  void shrink_to_fit() {
    if (size_ < cap_) reallocate(size_);
  }

 private:
  /// Small blocks double (realloc copies them: an eighth at a time, the
  /// copies cost 2 % of a small sweep); mapped ones grow by an eighth.
  void grow(std::size_t need) {
    const std::size_t step = mapped(cap_) ? cap_ / 8 : cap_;
    reallocate(std::max({need, cap_ + step, std::size_t{16}}));
  }
  /// Blocks of at least this many bytes are mapped pages (Linux). Small
  /// enough that the heap never holds the growing arrays (under valgrind,
  /// whose heap is bounded, realloc of ~1 MB blocks failed).
  static constexpr std::size_t kMapBytes = std::size_t{1} << 16;
  static bool mapped(std::size_t cap) {
#if SKINMESH_GROWABLE_ARRAY_MMAP
    return cap * sizeof(T) >= kMapBytes;
#else
    (void)cap;
    return false;
#endif
  }
  static void release(T* p, std::size_t cap) {
    if (p == nullptr) return;
#if SKINMESH_GROWABLE_ARRAY_MMAP
    if (mapped(cap)) {
      ::munmap(static_cast<void*>(p), cap * sizeof(T));
      return;
    }
#else
    (void)cap;
#endif
    std::free(static_cast<void*>(p));
  }
  /// Moves the elements to a block of capacity n >= size_ (n = 0: frees).
  void reallocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T) / 2) throw std::bad_alloc();
    void* p = nullptr;
    if (n == 0) {
      release(data_, cap_);
    } else if (!mapped(n) && !mapped(cap_)) {
      p = std::realloc(static_cast<void*>(data_), n * sizeof(T));
      if (p == nullptr) throw std::bad_alloc();
    } else {
#if SKINMESH_GROWABLE_ARRAY_MMAP
      if (mapped(n) && mapped(cap_)) {
        p = ::mremap(static_cast<void*>(data_), cap_ * sizeof(T), n * sizeof(T), MREMAP_MAYMOVE);
        if (p == MAP_FAILED) throw std::bad_alloc();
      } else {
        if (mapped(n)) {
          p = ::mmap(nullptr, n * sizeof(T), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
          if (p == MAP_FAILED) throw std::bad_alloc();
        } else {
          p = std::malloc(n * sizeof(T));
          if (p == nullptr) throw std::bad_alloc();
        }
        if (size_) std::memcpy(p, static_cast<const void*>(data_), size_ * sizeof(T));
        release(data_, cap_);
      }
#endif
    }
    data_ = static_cast<T*>(p);
    cap_ = n;
  }

  T* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t cap_ = 0;
};

}  // namespace skinmesh
