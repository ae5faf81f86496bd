#include <coulomb/engine/StepExecutor.hpp>

#ifdef COULOMB_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#endif

#include <algorithm>
#include <utility>

// ThreadSanitizer cannot see the synchronization inside a libtbb that is not instrumented (Debian's
// is not): it would report every hand-over between the calling thread and a task as a race. The
// edges oneTBB guarantees (everything before forEach happens before every task; every task
// happens before forEach returns) are told to it explicitly, so that what it still reports is a
// race between two tasks.
#if defined(__SANITIZE_THREAD__)
extern "C" void __tsan_acquire(void* address);
extern "C" void __tsan_release(void* address);
#define COULOMB_TSAN_ACQUIRE(address) __tsan_acquire(address)
#define COULOMB_TSAN_RELEASE(address) __tsan_release(address)
#else
#define COULOMB_TSAN_ACQUIRE(address) (void)(address)
#define COULOMB_TSAN_RELEASE(address) (void)(address)
#endif

namespace coulomb::engine {

#ifdef COULOMB_WITH_TBB
struct StepExecutor::Arena {
  explicit Arena(int threads) : arena(threads) {}
  tbb::task_arena arena;
};
#else
struct StepExecutor::Arena {};
#endif

StepExecutor::StepExecutor() = default;
StepExecutor::~StepExecutor() = default;
StepExecutor::StepExecutor(StepExecutor&& other) noexcept = default;
StepExecutor& StepExecutor::operator=(StepExecutor&& other) noexcept = default;

StepExecutor::StepExecutor(const StepExecutor& other) {
  setThreads(other.requested_);
}

StepExecutor& StepExecutor::operator=(const StepExecutor& other) {
  if (this != &other) setThreads(other.requested_);
  return *this;
}

bool StepExecutor::parallel() {
#ifdef COULOMB_WITH_TBB
  return true;
#else
  return false;
#endif
}

int StepExecutor::hardwareThreads() {
#ifdef COULOMB_WITH_TBB
  return std::max(1, tbb::info::default_concurrency());
#else
  return 1;
#endif
}

void StepExecutor::setThreads(int requested) {
  requested_ = requested;
  // Above the hardware's count the arena would ask the scheduler for workers it refuses (and
  // says so on stderr): the hardware's count gives the same results.
  const int hardware = hardwareThreads();
  const int threads = requested == 0 ? hardware : std::clamp(requested, 1, hardware);
  if (threads == threads_ && (threads == 1) == (arena_ == nullptr)) return;
  threads_ = threads;
  arena_.reset();
#ifdef COULOMB_WITH_TBB
  if (threads_ > 1) arena_ = std::make_unique<Arena>(threads_);
#endif
}

void StepExecutor::forEach(std::size_t count, geometry::TaskRef task) {
#ifdef COULOMB_WITH_TBB
  if (arena_ && count > 1) {
    int before = 0, after = 0;  // addresses for ThreadSanitizer's happens-before edges only
    COULOMB_TSAN_RELEASE(&before);
    arena_->arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          COULOMB_TSAN_ACQUIRE(&before);
                          for (std::size_t i = range.begin(); i != range.end(); ++i) task(i);
                          COULOMB_TSAN_RELEASE(&after);
                        });
    });
    COULOMB_TSAN_ACQUIRE(&after);
    return;
  }
#endif
  for (std::size_t i = 0; i < count; ++i) task(i);
}

void StepExecutor::forEach(std::size_t count, solvers::IndexTask task) {
  forEach(count, geometry::TaskRef([&task](std::size_t i) { task(i); }));
}

}  // namespace coulomb::engine
