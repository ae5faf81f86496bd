#include <coulomb/engine/SolverPromotion.hpp>

#include <algorithm>

namespace coulomb::engine {

solvers::SolvePlan SolverPromotion::apply(const Island& island, solvers::SolvePlan plan,
                                          bool& promoted) const {
  promoted = false;
  const std::string* name = nullptr;
  for (const std::int32_t b : island.bodies)  // ascending: the first promoted body decides
    if (static_cast<std::size_t>(b) < promoted_.size() && !promoted_[b].empty()) {
      name = &promoted_[b];
      break;
    }
  if (!name) return plan;
  const auto it = std::find(plan.solvers.begin(), plan.solvers.end(), *name);
  if (it == plan.solvers.end()) return plan;
  // The promoted attempt goes in front of the whole plan, which stays as it was behind it (with
  // its per-attempt settings): when the short promoted attempt fails, the plan runs as usual
  // from its best iterate.
  const std::size_t attempts = plan.solvers.size();
  auto prepend = [attempts](auto& perAttempt, auto fill, auto value) {
    if (!perAttempt.empty())
      perAttempt.resize(attempts, fill);
    else
      perAttempt.assign(attempts, fill);
    perAttempt.insert(perAttempt.begin(), value);
  };
  prepend(plan.iterationCaps, 0, kPromotedIterationCap);
  prepend(plan.stallWindows, 0, 0);
  prepend(plan.tolerances, 0.0, kPromotedToleranceScale * plan.options.tolerance);
  plan.solvers.insert(plan.solvers.begin(), *name);
  plan.reason += "; " + *name + " first: it finished this island's last step";
  promoted = true;
  return plan;
}

void SolverPromotion::record(const Island& island, const solvers::SolvePlan& plan,
                             const solvers::PlanOutcome& outcome, bool noPromotion) {
  std::string next;
  if (!noPromotion && outcome.attempts.size() > 1 && !plan.solvers.empty() &&
      !outcome.attempts.front().converged() &&
      outcome.attempts.front().residual <= kPromotionNearMiss * plan.options.tolerance &&
      outcome.best.report.converged() && outcome.best.report.iterations <= kPromotedIterationCap &&
      outcome.best.report.solver != plan.solvers.front())
    next = outcome.best.report.solver;
  for (const std::int32_t b : island.bodies)
    if (static_cast<std::size_t>(b) < promoted_.size()) promoted_[b] = next;
}

}  // namespace coulomb::engine
