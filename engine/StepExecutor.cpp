#include <coulomb/engine/StepExecutor.hpp>

#ifdef COULOMB_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#endif

#include <algorithm>
#include <utility>

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
    arena_->arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i) task(i);
                        });
    });
    return;
  }
#endif
  for (std::size_t i = 0; i < count; ++i) task(i);
}

}  // namespace coulomb::engine
