#pragma once
// Runs a SolvePlan: the primary solver, then each fallback while the best answer so far is above
// the plan's tolerance (common residual after the last update), each starting from the best
// iterate so far. Returns the best answer with the report of the attempt that produced it (its
// status is that attempt's own, never rewritten), the plan's status (Converged when the best
// residual is within the plan's tolerance), and every attempt's report (golden rule 3: a fallback
// is counted and logged).
#include <coulomb/solvers/ContactSolver.hpp>
#include <coulomb/solvers/SolvePlan.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>

#include <memory>
#include <utility>
#include <vector>

namespace coulomb::solvers {

struct PlanOutcome {
  SolveOutcome best;                   // impulses, velocities and the report of the best attempt
  std::vector<SolverReport> attempts;  // in the order run; attempts.size() - 1 fallbacks
  SolverStatus status = SolverStatus::NotApplicable;  // of the plan (see above)
  double seconds = 0.0;                               // wall clock of all attempts
  [[nodiscard]] bool converged() const { return status == SolverStatus::Converged; }
  [[nodiscard]] int fallbacks() const {
    return attempts.empty() ? 0 : static_cast<int>(attempts.size()) - 1;
  }
  [[nodiscard]] int iterations() const;  // summed over the attempts
};

/// The solvers of a registry, each created on first use and then reused (ContactSolver::solve
/// is const: a solver keeps nothing between solves). A registry only grows (SolverRegistry::add
/// refuses duplicates), so a cached instance stays the one its name means.
class SolverInstances {
 public:
  /// The solver named `name`, or nullptr when `registry` has none.
  const ContactSolver* get(const std::string& name, const SolverRegistry& registry);

  /// An outcome kept for its storage: each attempt is solved into it (solveWithFallback).
  SolveOutcome& attemptOutcome() { return attempt_; }
  /// The sticking start's workspace of this island's attempts (SolverOptions::stickingWorkspace).
  StickingStart& stickingWorkspace() { return sticking_; }

 private:
  std::vector<std::pair<std::string, std::unique_ptr<ContactSolver>>> made_;
  SolveOutcome attempt_;
  StickingStart sticking_;
};

PlanOutcome solveWithFallback(const ContactProblem& problem, const SolvePlan& plan,
                              const SolverRegistry& registry, SolverInstances& instances);
/// The same into `out`, reusing its storage and the instances' (a steady step allocates nothing).
void solveWithFallback(const ContactProblem& problem, const SolvePlan& plan,
                       const SolverRegistry& registry, SolverInstances& instances,
                       PlanOutcome& out);
/// The same with solvers created for this call.
PlanOutcome solveWithFallback(const ContactProblem& problem, const SolvePlan& plan,
                              const SolverRegistry& registry);

}  // namespace coulomb::solvers
