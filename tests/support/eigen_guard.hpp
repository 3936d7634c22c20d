// Force-included (-include) before anything else in every target that links ntn_test_support.
// With EIGEN_RUNTIME_NO_MALLOC, Eigen checks each of its heap allocations against
// Eigen::internal::set_is_malloc_allowed() through eigen_assert, which NDEBUG (Release) compiles
// out. Defining eigen_assert here keeps that check, and Eigen's other asserts, live in every
// build type of the tests: a forbidden allocation aborts with a message.
#pragma once

#ifndef EIGEN_RUNTIME_NO_MALLOC
#error "eigen_guard.hpp expects EIGEN_RUNTIME_NO_MALLOC (set by the ntn_test_support target)"
#endif

#include <cstdio>
#include <cstdlib>

namespace ntn_test {
[[noreturn]] inline void eigen_assert_failed(const char* what, const char* file, int line) {
  std::fprintf(stderr, "%s:%d: Eigen assertion failed: %s\n", file, line, what);
  std::abort();
}
}  // namespace ntn_test

#define eigen_assert(x) \
  ((x) ? static_cast<void>(0) : ::ntn_test::eigen_assert_failed(#x, __FILE__, __LINE__))
