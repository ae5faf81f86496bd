#include <coulomb/engine/SolverPromotion.hpp>

#include <algorithm>

namespace coulomb::engine {
namespace {

bool covers(const solvers::PromotionRule& rule, const solvers::SolvePlan& plan) {
  return rule.enabled && plan.features.unknowns > rule.minUnknowns;
}

}  // namespace

void SolverPromotion::apply(const Island& island, const solvers::PromotionRule& rule,
                            solvers::SolvePlan& plan) const {
  plan.promoted = false;
  if (!covers(rule, plan)) return;
  const std::string* name = nullptr;
  for (const std::int32_t b : island.bodies)  // ascending: the first promoted body decides
    if (static_cast<std::size_t>(b) < promoted_.size() && !promoted_[b].empty()) {
      name = &promoted_[b];
      break;
    }
  if (!name) return;
  const bool inPlan =
      std::any_of(plan.attempts.begin(), plan.attempts.end(),
                  [&](const solvers::SolveAttempt& a) { return a.solver == *name; });
  if (!inPlan) return;
  plan.attempts.insert(plan.attempts.begin(),
                       solvers::SolveAttempt{*name, rule.iterationCap, 0,
                                             rule.toleranceScale * plan.options.tolerance});
  plan.promoted = true;
}

void SolverPromotion::record(const Island& island, const solvers::PromotionRule& rule,
                             bool automaticPlan, const solvers::SolvePlan& plan,
                             const solvers::PlanOutcome& outcome) {
  const bool eligible = automaticPlan && covers(rule, plan) && !plan.promoted;
  const solvers::SolverReport* first = outcome.attempts.empty() ? nullptr : &outcome.attempts[0];
  const bool promote =
      eligible && outcome.attempts.size() > 1 && !plan.attempts.empty() && !first->converged() &&
      first->residual <= rule.nearMiss * plan.options.tolerance &&
      outcome.best.report.converged() && outcome.best.report.iterations <= rule.iterationCap &&
      outcome.best.report.solver != plan.attempts.front().solver;
  for (const std::int32_t b : island.bodies) {
    if (static_cast<std::size_t>(b) >= promoted_.size()) continue;
    if (promote)
      promoted_[b] = outcome.best.report.solver;
    else
      promoted_[b].clear();
  }
}

}  // namespace coulomb::engine
