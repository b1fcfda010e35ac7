// core/assert.h: invariant checks at three levels (papers/conventions.md §3,
// geogram's geo_assert / geo_debug_assert / geo_parano_assert). A failed check throws
// std::logic_error naming the expression, file and line: it is a bug, not bad input.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace skinmesh::detail {
[[noreturn]] inline void assertion_failed(const char* expr, const char* file, int line, const std::string& msg = {}) {
  std::ostringstream os;
  os << file << ":" << line << ": assertion failed: " << expr;
  if (!msg.empty()) os << " (" << msg << ")";
  throw std::logic_error(os.str());
}
}  // namespace skinmesh::detail

/// Cheap check, always on.
#define SKINMESH_ASSERT(expr) ((expr) ? (void)0 : ::skinmesh::detail::assertion_failed(#expr, __FILE__, __LINE__))
/// Cheap check with a message (any expression convertible to std::string).
#define SKINMESH_ASSERT_MSG(expr, msg) \
  ((expr) ? (void)0 : ::skinmesh::detail::assertion_failed(#expr, __FILE__, __LINE__, (msg)))

#ifndef NDEBUG
#define SKINMESH_DEBUG_ASSERT(expr) SKINMESH_ASSERT(expr)
#else
#define SKINMESH_DEBUG_ASSERT(expr) ((void)0)
#endif
