// Counts the heap allocations of a benchmark process, so that a benchmark can show that a step
// allocates nothing. With glibc, malloc and its relatives are replaced by wrappers that count
// and call glibc's own allocator (operator new and Eigen's vectors both end in malloc); elsewhere
// nothing is counted and allocationsCounted() says so. Include it in one file of a benchmark.
#pragma once

#include <atomic>
#include <cerrno>
#include <cstddef>

namespace physlab::bench {

inline std::atomic<long> allocation_count{0};

#if defined(__GLIBC__)
/// Whether allocationCount() counts (glibc only).
inline bool allocationsCounted() { return true; }
#else
inline bool allocationsCounted() { return false; }
#endif

/// Heap allocations since the process started.
inline long allocationCount() { return allocation_count.load(std::memory_order_relaxed); }

/// Allocations made by `work()`.
template <class Work>
long allocationsOf(Work&& work) {
  const long before = allocationCount();
  work();
  return allocationCount() - before;
}

}  // namespace physlab::bench

#if defined(__GLIBC__)
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);

void* malloc(std::size_t size) {
  physlab::bench::allocation_count.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  physlab::bench::allocation_count.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(count, size);
}
void* realloc(void* pointer, std::size_t size) {
  physlab::bench::allocation_count.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(pointer, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) {
  physlab::bench::allocation_count.fetch_add(1, std::memory_order_relaxed);
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** pointer, std::size_t alignment, std::size_t size) {
  physlab::bench::allocation_count.fetch_add(1, std::memory_order_relaxed);
  *pointer = __libc_memalign(alignment, size);
  return *pointer ? 0 : ENOMEM;
}
}
#endif
