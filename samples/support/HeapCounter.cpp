#include "support/HeapCounter.hpp"

#include <atomic>
#include <cstddef>

namespace {
std::atomic<std::uint64_t> allocations{0};
std::atomic<std::uint64_t> allocatedBytes{0};

void count(std::size_t bytes) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  allocatedBytes.fetch_add(bytes, std::memory_order_relaxed);
}
}  // namespace

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* malloc(std::size_t n) {
  count(n);
  return __libc_malloc(n);
}
void* calloc(std::size_t count_, std::size_t size) {
  count(count_ * size);
  return __libc_calloc(count_, size);
}
void* realloc(void* p, std::size_t n) {
  count(n);
  return __libc_realloc(p, n);
}
}

namespace coulomb::support {
std::uint64_t heapAllocations() {
  return allocations.load(std::memory_order_relaxed);
}
std::uint64_t heapBytes() {
  return allocatedBytes.load(std::memory_order_relaxed);
}
}  // namespace coulomb::support
