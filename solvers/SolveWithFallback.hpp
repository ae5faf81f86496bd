#pragma once
// Runs a SolvePlan: the primary solver, then each fallback while the best answer so far has not
// converged, each starting from the best iterate (by the common residual). Returns the best
// answer with the report of the attempt that produced it, and every attempt's report (golden
// rule 3: a fallback is counted and logged).
#include <coulomb/solvers/ContactSolver.hpp>
#include <coulomb/solvers/SolvePlan.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>

#include <vector>

namespace coulomb::solvers {

struct PlanOutcome {
  SolveOutcome best;                   // impulses, velocities and the report of the best attempt
  std::vector<SolverReport> attempts;  // in the order run; attempts.size() - 1 fallbacks
};

PlanOutcome solveWithFallback(const ContactProblem& problem, const SolvePlan& plan,
                              const SolverRegistry& registry);

}  // namespace coulomb::solvers
