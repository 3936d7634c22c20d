// Counts every heap allocation of the process: malloc, calloc, realloc, reallocarray,
// aligned_alloc, posix_memalign, memalign, valloc, pvalloc and every global operator new.
// alloc_counter.cpp replaces those functions (forwarding to glibc's __libc_* entry points), so
// link it (target ntn_alloc_counter) into the one test that needs it. Under AddressSanitizer it
// counts through ASan's allocator hooks instead (see alloc_counter.cpp).
#pragma once

#include <cstdint>

namespace ntn_test {

struct AllocationCounts {
  std::uint64_t allocations = 0;    // successful or not: every request for memory
  std::uint64_t deallocations = 0;  // free / delete of a non-null pointer
};

// Totals since the program started. Thread-safe (relaxed atomics: counts, not ordering).
AllocationCounts allocation_counts();

// Counts within a C++ scope: what was allocated between construction and counts().
class AllocationScope {
 public:
  AllocationScope() : start_(allocation_counts()) {}
  AllocationCounts counts() const {
    const AllocationCounts now = allocation_counts();
    return {now.allocations - start_.allocations, now.deallocations - start_.deallocations};
  }

 private:
  AllocationCounts start_;
};

}  // namespace ntn_test
