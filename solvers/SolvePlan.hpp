#pragma once
// Which solvers an island gets, in order, and why (ARCHITECTURE.md section 4, SOLVERS.md section
// 9). SolverChooser fills it (automatically or from a named solver); solveWithFallback runs it.
#include <coulomb/solvers/SolverOptions.hpp>

#include <string>
#include <vector>

namespace coulomb::solvers {

struct SolvePlan {
  std::vector<std::string> solvers;  // registry names: the primary first, then the fallbacks
  std::string reason;                // human-readable: why this primary (for the StepReport)
  SolverOptions options;             // common options for every attempt
};

/// What the chooser may know about an island besides its problem.
struct IslandFeatures {
  int degreesOfFreedom = 0;  // m of nu = 3 n / m (0 = unknown: use 3n / rank-free estimate)
};

}  // namespace coulomb::solvers
