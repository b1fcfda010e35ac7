// apps/huge_pages.cpp: the program's global operator new and delete, which ask
// the kernel for transparent huge pages on large blocks.
//
// Why: the mesher's arrays (the mixed complex, the half-edge mesh, the check's
// tables) are large and short-lived, so a run spends much of its time faulting
// in fresh 4 KiB pages: maltoporin at probe 1.4 faults about 90,000 of them.
// Where the kernel's transparent huge pages are set to "madvise" (Debian's and
// Ubuntu's default), a block only gets 2 MiB pages if it is advised to; with
// the advice the same run faults about 36,000 and takes 15-20 % less wall time
// (papers/mesher/pipeline.md, "Page faults"). Only the programs link this file:
// a library must not replace its host's allocator. The advice changes no
// result, only where pages come from.
#include <cstdint>
#include <cstdlib>
#include <new>

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define SKINMESH_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define SKINMESH_SANITIZED 1
#endif

// Sanitizers bring their own operator new (with its mismatch checks): keep it.
#if defined(__linux__) && !defined(SKINMESH_SANITIZED)
#include <sys/mman.h>

namespace {

constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;
// Blocks from this size on are advised: smaller ones hold less than one
// aligned huge page on average, and the advice costs a system call.
constexpr std::size_t kAdviseFrom = std::size_t{4} << 20;

/// malloc(n), with the 2 MiB-aligned interior of a large block advised
/// MADV_HUGEPAGE before it is first touched. Throws std::bad_alloc when
/// malloc fails (no new_handler is consulted: the programs install none).
void* allocate(std::size_t n) {
  void* p = std::malloc(n == 0 ? 1 : n);
  if (p == nullptr) throw std::bad_alloc();
  if (n >= kAdviseFrom) {
    const auto begin = reinterpret_cast<std::uintptr_t>(p);
    const std::uintptr_t lo = (begin + kHugePage - 1) & ~(kHugePage - 1);
    const std::uintptr_t hi = (begin + n) & ~(kHugePage - 1);
    // Advice only: where the kernel refuses it, the block keeps small pages.
    if (hi > lo) (void)madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE);
  }
  return p;
}

}  // namespace

void* operator new(std::size_t n) { return allocate(n); }
void* operator new[](std::size_t n) { return allocate(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return allocate(n);
  } catch (const std::bad_alloc&) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
#endif
