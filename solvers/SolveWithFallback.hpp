#pragma once
// Runs a SolvePlan: the primary solver, then each fallback while the best answer so far has not
// converged (status, or common residual above the tolerance after the last update), each starting
// from the best iterate so far (by the common residual). Returns the best answer with the report
// of the attempt that produced it (its message names the plan's reason and the fallbacks tried),
// and every attempt's report (golden rule 3: a fallback is counted and logged).
#include <coulomb/solvers/ContactSolver.hpp>
#include <coulomb/solvers/SolvePlan.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>

#include <vector>

namespace coulomb::solvers {

struct PlanOutcome {
  SolveOutcome best;                   // impulses, velocities and the report of the best attempt
  std::vector<SolverReport> attempts;  // in the order run; attempts.size() - 1 fallbacks
  double seconds = 0.0;                // wall clock of all attempts
  [[nodiscard]] int fallbacks() const {
    return attempts.empty() ? 0 : static_cast<int>(attempts.size()) - 1;
  }
  [[nodiscard]] int iterations() const;  // summed over the attempts
};

PlanOutcome solveWithFallback(const ContactProblem& problem, const SolvePlan& plan,
                              const SolverRegistry& registry);

}  // namespace coulomb::solvers
