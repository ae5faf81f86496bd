#pragma once
// The C allocator's settings for a process that steps a simulation (docs/tuning.md, "Allocator").
//
// A step allocates and frees the same few megabytes every step (row blocks, W's factors, solver
// vectors). With glibc's defaults the allocator hands memory back to the kernel as soon as 128 KB
// are free at the top of the heap (M_TRIM_THRESHOLD) and serves every block of 128 KB or more by
// its own mmap (M_MMAP_THRESHOLD): each step then faults the same pages in again. glibc raises both
// thresholds by itself only after a large mmapped block is freed, so whether a run pays depends on
// its history: a 55-box pyramid continued from a snapshot took 3.4 ms per step instead of 0.35 ms
// (docs/tuning.md, "Allocator"). World's constructor therefore fixes both thresholds once per
// process: freed memory up to kTrimThresholdBytes stays mapped, blocks below kMmapThresholdBytes
// come from the heap. Other C libraries, and sanitizer builds (their own allocator), are left
// alone; so is a process that sets COULOMB_KEEP_ALLOCATOR in its environment.
#include <cstddef>

namespace coulomb::engine {

inline constexpr std::size_t kTrimThresholdBytes = std::size_t{256} << 20;  // 256 MB
inline constexpr std::size_t kMmapThresholdBytes = std::size_t{32} << 20;   // glibc's maximum

/// Applies the settings above once per process (thread-safe; later calls do nothing). True when
/// they are in effect (glibc, no sanitizer, no COULOMB_KEEP_ALLOCATOR at the first call).
bool tuneAllocatorForStepping();

}  // namespace coulomb::engine
