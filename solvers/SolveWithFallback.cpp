#include <coulomb/solvers/SolveWithFallback.hpp>

namespace coulomb::solvers {

PlanOutcome solveWithFallback(const ContactProblem& problem, const SolvePlan& plan,
                              const SolverRegistry& registry) {
  PlanOutcome out;
  bool haveBest = false;
  for (const std::string& name : plan.solvers) {
    const std::unique_ptr<ContactSolver> solver = registry.create(name);
    if (!solver) {
      SolverReport missing;
      missing.solver = name;
      missing.status = SolverStatus::NotApplicable;
      missing.message = "no solver named '" + name + "' in the registry";
      out.attempts.push_back(missing);
      continue;
    }
    SolveOutcome outcome = haveBest ? solver->solve(problem, plan.options, out.best.impulses)
                                    : solver->solve(problem, plan.options);
    out.attempts.push_back(outcome.report);
    if (outcome.report.status == SolverStatus::InvalidProblem) {
      out.best = std::move(outcome);  // the problem itself is wrong: no solver will do better
      return out;
    }
    if (!haveBest || outcome.report.residual < out.best.report.residual) {
      out.best = std::move(outcome);
      haveBest = true;
    }
    if (out.best.report.converged()) break;
  }
  if (!haveBest && out.best.impulses.size() != problem.size())
    out.best.impulses = Eigen::VectorXd::Zero(problem.size());
  if (out.attempts.size() > 1)
    out.best.report.note(std::to_string(out.attempts.size() - 1) + " fallback(s) tried");
  return out;
}

}  // namespace coulomb::solvers
