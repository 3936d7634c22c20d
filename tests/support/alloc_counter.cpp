// Replaces the C allocation functions and every global operator new / delete with counting
// versions. The C functions forward to glibc's exported __libc_* implementations (no dlsym, so
// no allocation during interposition); operator new / delete forward to the same, so a pointer
// from either family may be released by the other as glibc allows.
//
// Under AddressSanitizer (NTN_SANITIZE, preset asan) nothing is replaced: ASan owns malloc and
// operator new, and memory it did not hand out must never reach its free. The counts come from
// its allocator hooks instead, which it calls for every allocation it makes (malloc & co. and
// every operator new alike) and every release of a non-null pointer.
#include "support/alloc_counter.hpp"

#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstdlib>
#include <new>

#if defined(NTN_SANITIZE)

extern "C" int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void*,
                                                                             std::size_t),
                                                         void (*free_hook)(const volatile void*));

namespace {

std::atomic<std::uint64_t> g_allocations{0};
std::atomic<std::uint64_t> g_deallocations{0};

void on_malloc(const volatile void*, std::size_t) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
}
void on_free(const volatile void* p) {
  if (p != nullptr) g_deallocations.fetch_add(1, std::memory_order_relaxed);
}

// Installed during static initialisation, before any test runs.
const int g_hooks_installed = __sanitizer_install_malloc_and_free_hooks(on_malloc, on_free);

}  // namespace

namespace ntn_test {

AllocationCounts allocation_counts() {
  if (g_hooks_installed == 0) std::abort();  // no counts: a test relying on them must not pass
  return {g_allocations.load(std::memory_order_relaxed),
          g_deallocations.load(std::memory_order_relaxed)};
}

}  // namespace ntn_test

#else  // !NTN_SANITIZE

extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t n, std::size_t size);
void* __libc_realloc(void* p, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);
void* __libc_valloc(std::size_t size);
void* __libc_pvalloc(std::size_t size);
void __libc_free(void* p);
}

namespace {

std::atomic<std::uint64_t> g_allocations{0};
std::atomic<std::uint64_t> g_deallocations{0};

void count_allocation() {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
}
void count_deallocation(const void* p) {
  if (p != nullptr) g_deallocations.fetch_add(1, std::memory_order_relaxed);
}

bool power_of_two(std::size_t a) {
  return a != 0 && (a & (a - 1)) == 0;
}

void* new_impl(std::size_t size) {
  count_allocation();
  if (size == 0) size = 1;
  for (;;) {
    if (void* p = __libc_malloc(size)) return p;
    std::new_handler h = std::get_new_handler();
    if (h == nullptr) throw std::bad_alloc();
    h();
  }
}

void* new_aligned_impl(std::size_t size, std::align_val_t al) {
  count_allocation();
  if (size == 0) size = 1;
  auto a = static_cast<std::size_t>(al);
  if (a < sizeof(void*)) a = sizeof(void*);
  for (;;) {
    if (void* p = __libc_memalign(a, size)) return p;
    std::new_handler h = std::get_new_handler();
    if (h == nullptr) throw std::bad_alloc();
    h();
  }
}

void delete_impl(void* p) noexcept {
  count_deallocation(p);
  __libc_free(p);
}

}  // namespace

namespace ntn_test {

AllocationCounts allocation_counts() {
  return {g_allocations.load(std::memory_order_relaxed),
          g_deallocations.load(std::memory_order_relaxed)};
}

}  // namespace ntn_test

// --- C allocation functions (replace glibc's for the whole process) ---
extern "C" {

void* malloc(std::size_t size) noexcept {
  count_allocation();
  return __libc_malloc(size);
}

void* calloc(std::size_t n, std::size_t size) noexcept {
  count_allocation();
  return __libc_calloc(n, size);
}

void* realloc(void* p, std::size_t size) noexcept {
  count_allocation();
  return __libc_realloc(p, size);
}

void* reallocarray(void* p, std::size_t n, std::size_t size) noexcept {
  count_allocation();
  if (size != 0 && n > static_cast<std::size_t>(-1) / size) {
    errno = ENOMEM;
    return nullptr;
  }
  return __libc_realloc(p, n * size);
}

void free(void* p) noexcept {
  count_deallocation(p);
  __libc_free(p);
}

void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept {
  count_allocation();
  if (!power_of_two(alignment)) {
    errno = EINVAL;
    return nullptr;
  }
  return __libc_memalign(alignment, size);
}

void* memalign(std::size_t alignment, std::size_t size) noexcept {
  count_allocation();
  return __libc_memalign(alignment, size);
}

int posix_memalign(void** out, std::size_t alignment, std::size_t size) noexcept {
  count_allocation();
  if (!power_of_two(alignment) || alignment % sizeof(void*) != 0) return EINVAL;
  void* p = __libc_memalign(alignment, size);
  if (p == nullptr) return ENOMEM;
  *out = p;
  return 0;
}

void* valloc(std::size_t size) noexcept {
  count_allocation();
  return __libc_valloc(size);
}

void* pvalloc(std::size_t size) noexcept {
  count_allocation();
  return __libc_pvalloc(size);
}

}  // extern "C"

// --- Global operator new / delete: every replaceable overload ---
void* operator new(std::size_t size) {
  return new_impl(size);
}
void* operator new[](std::size_t size) {
  return new_impl(size);
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return new_impl(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return new_impl(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new(std::size_t size, std::align_val_t al) {
  return new_aligned_impl(size, al);
}
void* operator new[](std::size_t size, std::align_val_t al) {
  return new_aligned_impl(size, al);
}
void* operator new(std::size_t size, std::align_val_t al, const std::nothrow_t&) noexcept {
  try {
    return new_aligned_impl(size, al);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, std::align_val_t al, const std::nothrow_t&) noexcept {
  try {
    return new_aligned_impl(size, al);
  } catch (...) {
    return nullptr;
  }
}

void operator delete(void* p) noexcept {
  delete_impl(p);
}
void operator delete[](void* p) noexcept {
  delete_impl(p);
}
void operator delete(void* p, std::size_t) noexcept {
  delete_impl(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  delete_impl(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
  delete_impl(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
  delete_impl(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  delete_impl(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  delete_impl(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  delete_impl(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  delete_impl(p);
}
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  delete_impl(p);
}
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  delete_impl(p);
}

#endif  // NTN_SANITIZE
