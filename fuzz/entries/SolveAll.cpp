#include "entries/SolveAll.hpp"

#include <coulomb/solvers/ContactSolver.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>

#include <exception>

namespace coulomb::fuzz {

std::string solveWithEverySolver(const solvers::ContactProblem& problem, int maxIterations) {
  using solvers::SolverStatus;
  const std::optional<std::string> invalid = problem.validate();
  const solvers::SolverRegistry registry = solvers::SolverRegistry::builtIn();
  solvers::SolverOptions options;
  options.maxIterations = maxIterations;
  // Inner loops have their own budgets (staggered: 500 APGD iterations per QP and outer iteration,
  // all spent on an indefinite W): the documented wall-clock guard keeps one input under a second.
  options.timeLimitSeconds = 0.25;
  for (const solvers::SolverEntry& entry : registry.entries()) {
    const std::string who = "solver '" + entry.name + "': ";
    solvers::SolveOutcome out;
    try {
      out = entry.create()->solve(problem, options);
    } catch (const std::exception& e) {
      return who + "solve() threw: " + e.what();
    }
    const solvers::SolverReport& report = out.report;
    const int status = static_cast<int>(report.status);
    if (status < static_cast<int>(SolverStatus::Converged) ||
        status > static_cast<int>(SolverStatus::NotApplicable))
      return who + "status out of range: " + std::to_string(status);
    if (invalid) {
      if (report.status != SolverStatus::InvalidProblem)
        return who + "validate() refuses (" + *invalid + ") but the status is " +
               solvers::statusName(report.status);
      continue;
    }
    if (report.status == SolverStatus::InvalidProblem)
      return who + "validate() accepts but the status is invalid_problem: " + report.message;
    if (out.impulses.size() != problem.size() || !out.impulses.allFinite())
      return who + "impulses of the wrong size or not finite (status " +
             solvers::statusName(report.status) + ")";
    if (report.status == SolverStatus::Converged && !(report.residual <= options.tolerance))
      return who + "converged with the common residual " + std::to_string(report.residual) +
             " above the tolerance";
  }
  return {};
}

}  // namespace coulomb::fuzz
