#include <coulomb/solvers/SolveWithFallback.hpp>

#include <coulomb/solvers/Residual.hpp>

#include <algorithm>
#include <chrono>

namespace coulomb::solvers {
namespace {

// The plan is done once the best answer is within its tolerance and was not a failure (an
// attempt aimed tighter than the plan may stop at its cap there: the plan still has its answer).
bool withinPlan(const SolverReport& best, const SolvePlan& plan) {
  const bool usable = best.status == SolverStatus::Converged ||
                      best.status == SolverStatus::MaxIterations ||
                      best.status == SolverStatus::Stalled;
  return usable && best.residual <= plan.options.tolerance;
}

}  // namespace

int PlanOutcome::iterations() const {
  int total = 0;
  for (const SolverReport& a : attempts) total += a.iterations;
  return total;
}

const ContactSolver* SolverInstances::get(const std::string& name, const SolverRegistry& registry) {
  for (const auto& [known, solver] : made_)
    if (known == name) return solver.get();
  std::unique_ptr<ContactSolver> made = registry.create(name);
  if (!made) return nullptr;
  made_.emplace_back(name, std::move(made));
  return made_.back().second.get();
}

PlanOutcome solveWithFallback(const ContactProblem& problem, const SolvePlan& plan,
                              const SolverRegistry& registry) {
  SolverInstances instances;
  return solveWithFallback(problem, plan, registry, instances);
}

PlanOutcome solveWithFallback(const ContactProblem& problem, const SolvePlan& plan,
                              const SolverRegistry& registry, SolverInstances& instances) {
  const auto started = std::chrono::steady_clock::now();
  PlanOutcome out;
  bool haveBest = false;
  for (const SolveAttempt& attempt : plan.attempts) {
    if (haveBest && withinPlan(out.best.report, plan)) break;
    const ContactSolver* solver = instances.get(attempt.solver, registry);
    if (!solver) {
      SolverReport missing;
      missing.solver = attempt.solver;
      missing.status = SolverStatus::NotApplicable;
      missing.message = "no solver named '" + attempt.solver + "' in the registry";
      out.attempts.push_back(missing);
      continue;
    }
    // The time limit is for the whole plan: each attempt gets what is left.
    SolverOptions options = plan.optionsFor(attempt);
    const double used =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (used >= options.timeLimitSeconds && haveBest) break;
    options.timeLimitSeconds = std::max(options.timeLimitSeconds - used, 1e-6);
    SolveOutcome outcome = haveBest ? solver->solve(problem, options, out.best.impulses)
                                    : solver->solve(problem, options);
    out.attempts.push_back(outcome.report);
    if (outcome.report.status == SolverStatus::InvalidProblem) {
      out.best = std::move(outcome);  // the problem itself is wrong: no solver will do better
      haveBest = true;
      break;
    }
    if (outcome.report.status == SolverStatus::NotApplicable) continue;
    if (!haveBest || outcome.report.residual < out.best.report.residual) {
      out.best = std::move(outcome);
      haveBest = true;
    }
  }
  if (!haveBest) {  // nothing could run: r = 0, measured, with the last attempt's status
    out.best.impulses = Eigen::VectorXd::Zero(problem.size());
    if (!problem.validate()) {
      const ResidualValue e = commonResidual(problem, out.best.impulses, out.best.velocities);
      out.best.report.residual = e.relative;
      out.best.report.absoluteResidual = e.absolute;
    }
    out.best.report.status = SolverStatus::NotApplicable;
    out.best.report.note("no solver of the plan could run; r = 0 returned");
  }
  out.status = haveBest && withinPlan(out.best.report, plan) ? SolverStatus::Converged
                                                             : out.best.report.status;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace coulomb::solvers
