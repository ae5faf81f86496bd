// engine/AllocatorTuning: after a World exists, a block a step would free (here 4 MB, above
// glibc's default 128 KB thresholds) stays in the heap instead of going back to the kernel, so
// the next step does not fault its pages in again (docs/benchmarks.md, "Allocator").
#include <coulomb/engine/AllocatorTuning.hpp>
#include <coulomb/engine/World.hpp>

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace {

#if defined(__GLIBC__) && !defined(COULOMB_SANITIZE)
TEST(AllocatorTuningTest, FreedStepMemoryStaysInTheHeap) {
  if (std::getenv("COULOMB_KEEP_ALLOCATOR") != nullptr) GTEST_SKIP() << "opted out";
  const coulomb::engine::World world;  // its constructor tunes the allocator
  EXPECT_TRUE(coulomb::engine::tuneAllocatorForStepping());
  constexpr std::size_t bytes = std::size_t{4} << 20;
  void* block = std::malloc(bytes);
  ASSERT_NE(block, nullptr);
  std::memset(block, 1, bytes);
  std::free(block);
  // After the free it is kept (below the trim threshold): the arena still holds it.
  EXPECT_GE(mallinfo2().arena, bytes);
}
#endif

TEST(AllocatorTuningTest, SecondCallChangesNothing) {
  const bool first = coulomb::engine::tuneAllocatorForStepping();
  EXPECT_EQ(coulomb::engine::tuneAllocatorForStepping(), first);
}

}  // namespace
