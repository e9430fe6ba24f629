#include "alloc_counter.hpp"

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<std::uint64_t> g_allocations{0};
// Initial-exec TLS of the executable: reading it never allocates, so it is safe inside malloc.
thread_local std::uint64_t t_allocations = 0;
inline void countOne() {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  ++t_allocations;
}
}  // namespace

namespace visnav::test {
std::uint64_t allocationCount() { return g_allocations.load(); }
std::uint64_t threadAllocationCount() { return t_allocations; }
#if defined(__SANITIZE_ADDRESS__)
bool countsMalloc() { return false; }
#else
bool countsMalloc() { return true; }
#endif
}  // namespace visnav::test

#if !defined(__SANITIZE_ADDRESS__)
// glibc's internal entry points: our malloc family counts, then forwards.
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void* malloc(std::size_t size) {
  countOne();
  return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) {
  countOne();
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t size) {
  countOne();
  return __libc_realloc(p, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) {
  countOne();
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) {
  countOne();
  *out = __libc_memalign(alignment, size);
  return *out != nullptr ? 0 : 12;  // ENOMEM
}
}
#endif

void* operator new(std::size_t size) {
  countOne();
  void* p = std::malloc(size == 0 ? 1 : size);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
void* operator new[](std::size_t size) { return operator new(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  countOne();
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept { return operator new(size, tag); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
