#pragma once
// Threads a caller lends to one solve (SolverOptions::parallel; the World passes its executor,
// WorldSettings::threads). A solver uses them only where the result cannot depend on how the work
// is split: the interiors of a split Gauss-Seidel sweep's parts, then the blocks of one colour of
// its boundary (SweepPartition.hpp), touch disjoint bodies, so running them on any number of
// threads gives the bits of the serial sweep; fixed pieces summed in order do the same for sums.
#include <coulomb/solvers/FunctionRef.hpp>

#include <cstddef>

namespace coulomb::solvers {

using IndexTask = FunctionRef<void(std::size_t)>;

class ParallelLoop {
 public:
  virtual ~ParallelLoop() = default;
  /// Calls task(i) for every i in [0, count), in any order and on any of the lent threads, and
  /// returns when all are done (the first exception a task throws is rethrown).
  virtual void forEach(std::size_t count, IndexTask task) = 0;
  /// The threads forEach may use (1: it runs the loop on the calling thread).
  [[nodiscard]] virtual int threads() const = 0;

 protected:
  ParallelLoop() = default;
  ParallelLoop(const ParallelLoop&) = default;
  ParallelLoop& operator=(const ParallelLoop&) = default;
};

}  // namespace coulomb::solvers
