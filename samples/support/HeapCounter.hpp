#pragma once
// Counts every heap allocation of a program (calls and bytes of malloc, calloc and realloc, so
// operator new and Eigen's aligned malloc alike). For measuring programs only (bench/StepCost,
// tests/performance): link the `coulomb_heap_counter` object library, which interposes glibc's
// malloc family for the whole process and forwards to glibc's own entry points. The library
// proper never touches the allocator. Not with AddressSanitizer, which owns the allocator.
#include <cstdint>

namespace coulomb::support {

[[nodiscard]] std::uint64_t heapAllocations();  // calls so far
[[nodiscard]] std::uint64_t heapBytes();        // bytes requested so far

}  // namespace coulomb::support
