#include <coulomb/solvers/SolveWithFallback.hpp>

#include <coulomb/solvers/Residual.hpp>

#include <algorithm>

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
  PlanOutcome out;
  solveWithFallback(problem, plan, registry, instances, out);
  return out;
}

void solveWithFallback(const ContactProblem& problem, const SolvePlan& plan,
                       const SolverRegistry& registry, SolverInstances& instances,
                       PlanOutcome& out) {
  // The plan's time is its attempts' time (each solver times itself), so the plan reads no clock
  // of its own: a read costs ~25 ns, a few percent of a small island's solve.
  double used = 0.0;
  // out's reports are overwritten in place (copy-assignment keeps their strings' storage).
  std::size_t attemptCount = 0;
  auto record = [&](const SolverReport& report) {
    if (attemptCount < out.attempts.size())
      out.attempts[attemptCount] = report;
    else
      out.attempts.push_back(report);
    ++attemptCount;
    used += report.seconds;
  };
  SolveOutcome& outcome = instances.attemptOutcome();
  bool haveBest = false;
  for (const SolveAttempt& attempt : plan.attempts) {
    if (haveBest && withinPlan(out.best.report, plan)) break;
    const ContactSolver* solver = instances.get(attempt.solver, registry);
    if (!solver) {
      SolverReport missing;
      missing.solver = attempt.solver;
      missing.status = SolverStatus::NotApplicable;
      missing.message = "no solver named '" + attempt.solver + "' in the registry";
      record(missing);
      continue;
    }
    // The time limit is for the whole plan: each attempt gets what is left.
    SolverOptions options = plan.optionsFor(attempt);
    if (!options.stickingWorkspace) options.stickingWorkspace = &instances.stickingWorkspace();
    if (used >= options.timeLimitSeconds && haveBest) break;
    options.timeLimitSeconds = std::max(options.timeLimitSeconds - used, 1e-6);
    solver->solve(problem, options, haveBest ? &out.best.impulses : nullptr, outcome);
    record(outcome.report);
    if (outcome.report.status == SolverStatus::InvalidProblem) {
      std::swap(out.best, outcome);  // the problem itself is wrong: no solver will do better
      haveBest = true;
      break;
    }
    if (outcome.report.status == SolverStatus::NotApplicable) continue;
    if (!haveBest || outcome.report.residual < out.best.report.residual) {
      std::swap(out.best, outcome);  // both keep their storage for the next solve
      haveBest = true;
    }
  }
  out.attempts.resize(attemptCount);
  if (!haveBest) {  // nothing could run: r = 0, measured, with the last attempt's status
    out.best.report.reset();
    out.best.impulses.setZero(problem.size());
    out.best.velocities = problem.q;
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
  out.seconds = used;
}

}  // namespace coulomb::solvers
