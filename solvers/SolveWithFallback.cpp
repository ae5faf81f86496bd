#include <coulomb/solvers/SolveWithFallback.hpp>

#include <coulomb/solvers/Residual.hpp>

#include <algorithm>
#include <chrono>

namespace coulomb::solvers {

int PlanOutcome::iterations() const {
  int total = 0;
  for (const SolverReport& a : attempts) total += a.iterations;
  return total;
}

PlanOutcome solveWithFallback(const ContactProblem& problem, const SolvePlan& plan,
                              const SolverRegistry& registry) {
  const auto started = std::chrono::steady_clock::now();
  PlanOutcome out;
  bool haveBest = false;
  std::string tried;
  for (size_t attempt = 0; attempt < plan.solvers.size(); ++attempt) {
    const std::string& name = plan.solvers[attempt];
    if (haveBest && out.best.report.converged()) break;
    const std::unique_ptr<ContactSolver> solver = registry.create(name);
    if (!solver) {
      SolverReport missing;
      missing.solver = name;
      missing.status = SolverStatus::NotApplicable;
      missing.message = "no solver named '" + name + "' in the registry";
      out.attempts.push_back(missing);
      continue;
    }
    // The time limit is for the whole plan: each attempt gets what is left.
    SolverOptions options = plan.options;
    const double used =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (used >= options.timeLimitSeconds && haveBest) break;
    options.timeLimitSeconds = std::max(options.timeLimitSeconds - used, 1e-6);
    if (attempt < plan.iterationCaps.size() && plan.iterationCaps[attempt] > 0)
      options.maxIterations = plan.iterationCaps[attempt];
    if (attempt < plan.stallWindows.size() && plan.stallWindows[attempt] > 0)
      options.stallWindow = plan.stallWindows[attempt];
    if (attempt < plan.tolerances.size() && plan.tolerances[attempt] > 0)
      options.tolerance = plan.tolerances[attempt];
    SolveOutcome outcome = haveBest ? solver->solve(problem, options, out.best.impulses)
                                    : solver->solve(problem, options);
    if (!outcome.report.converged() && options.tolerance < plan.options.tolerance &&
        outcome.report.residual <= plan.options.tolerance &&
        (outcome.report.status == SolverStatus::MaxIterations ||
         outcome.report.status == SolverStatus::Stalled)) {
      outcome.report.status =
          SolverStatus::Converged;  // short of its own target, within the plan's
      outcome.report.note("stopped above its tighter tolerance, within the plan's");
    }
    out.attempts.push_back(outcome.report);
    tried += (tried.empty() ? "" : " -> ") + name + " (" + statusName(outcome.report.status) + ")";
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
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (!plan.reason.empty()) out.best.report.note("plan: " + plan.reason);
  if (out.attempts.size() > 1)
    out.best.report.note(std::to_string(out.attempts.size() - 1) + " fallback(s): " + tried);
  return out;
}

}  // namespace coulomb::solvers
