#pragma once
// Runs the independent tasks of a step (one per island) on the World's threads
// (WorldSettings::threads, docs/embedding.md "Threads"): through oneTBB when Coulomb is built
// with it (CMake option COULOMB_WITH_TBB, on when libtbb-dev is found), else on the calling
// thread. Every task writes only its own island's data, so the results are the same, bit for bit,
// whatever the number of threads and however the tasks are scheduled. The World owns one executor
// (its own task arena: no process-wide scheduler setting is changed).
#include <coulomb/geometry/ParallelFor.hpp>
#include <coulomb/solvers/ParallelLoop.hpp>

#include <cstddef>
#include <memory>

namespace coulomb::engine {

class StepExecutor final : public solvers::ParallelLoop {
 public:
  StepExecutor();
  ~StepExecutor() override;
  StepExecutor(const StepExecutor& other);  // the same thread count, an arena of its own
  StepExecutor& operator=(const StepExecutor& other);
  StepExecutor(StepExecutor&& other) noexcept;
  StepExecutor& operator=(StepExecutor&& other) noexcept;

  /// WorldSettings::threads: 1 = the calling thread only; 0 = every hardware thread; N > 1 = N,
  /// at most the hardware's (a larger count runs as the hardware's: the results do not depend
  /// on it). Without oneTBB every count runs on the calling thread.
  void setThreads(int requested);
  /// The threads a step uses: 1 without oneTBB or for threads = 1.
  [[nodiscard]] int threads() const override { return threads_; }
  /// True when Coulomb was built with oneTBB (threads above 1 are used).
  [[nodiscard]] static bool parallel();
  /// The machine's hardware threads as the task system sees them (1 without oneTBB).
  [[nodiscard]] static int hardwareThreads();

  /// Calls task(i) for every i in [0, count), in any order and on any of the threads, and returns
  /// when all are done; the first exception a task throws is rethrown here.
  void forEach(std::size_t count, geometry::TaskRef task);
  /// The same for a solver (SolverOptions::parallel: the parts of a split sweep); called
  /// from inside a task too (a large island's solve), where oneTBB nests it in the same arena.
  void forEach(std::size_t count, solvers::IndexTask task) override;

 private:
  struct Arena;
  std::unique_ptr<Arena> arena_;  // null when threads_ == 1
  int requested_ = 1;
  int threads_ = 1;
};

}  // namespace coulomb::engine
