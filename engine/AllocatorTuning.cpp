#include <coulomb/engine/AllocatorTuning.hpp>

#include <cstdlib>
#include <mutex>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#if defined(__SANITIZE_ADDRESS__)
#define COULOMB_OWN_ALLOCATOR 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer)
#define COULOMB_OWN_ALLOCATOR 1
#endif
#endif

namespace coulomb::engine {

namespace {

bool applySettings() {
#if defined(__GLIBC__) && !defined(COULOMB_OWN_ALLOCATOR)
  if (std::getenv("COULOMB_KEEP_ALLOCATOR") != nullptr) return false;
  // Fixing M_MMAP_THRESHOLD also turns off glibc's own threshold adjustment, so the behaviour no
  // longer depends on what the process freed first.
  const bool mmapSet = mallopt(M_MMAP_THRESHOLD, static_cast<int>(kMmapThresholdBytes)) == 1;
  const bool trimSet = mallopt(M_TRIM_THRESHOLD, static_cast<int>(kTrimThresholdBytes)) == 1;
  return mmapSet && trimSet;
#else
  return false;
#endif
}

}  // namespace

bool tuneAllocatorForStepping() {
  static std::once_flag once;
  static bool changed = false;
  std::call_once(once, [] { changed = applySettings(); });
  return changed;
}

}  // namespace coulomb::engine
