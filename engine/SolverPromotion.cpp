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
  const std::size_t from = static_cast<std::size_t>(it - plan.solvers.begin());
  // Per-attempt settings follow their solver; the promoted one runs without cap or stall window.
  auto moveToFront = [from](auto& perAttempt, auto fill) {
    if (perAttempt.empty()) return;
    perAttempt.resize(std::max(perAttempt.size(), from + 1), fill);
    perAttempt.erase(perAttempt.begin() + static_cast<std::ptrdiff_t>(from));
    perAttempt.insert(perAttempt.begin(), fill);
  };
  moveToFront(plan.iterationCaps, 0);
  moveToFront(plan.stallWindows, 0);
  moveToFront(plan.tolerances, 0.0);
  if (plan.tolerances.empty()) plan.tolerances.push_back(0.0);
  plan.tolerances.front() = kPromotedToleranceScale * plan.options.tolerance;
  if (plan.iterationCaps.empty()) plan.iterationCaps.push_back(0);
  plan.iterationCaps.front() = kPromotedIterationCap;
  plan.solvers.erase(it);
  plan.solvers.insert(plan.solvers.begin(), *name);
  plan.reason += "; " + *name + " first: it finished this island's last step";
  promoted = true;
  return plan;
}

void SolverPromotion::record(const Island& island, const solvers::SolvePlan& plan,
                             const solvers::PlanOutcome& outcome, bool final) {
  std::string next;
  if (!final && outcome.attempts.size() > 1 && !plan.solvers.empty() &&
      !outcome.attempts.front().converged() && outcome.best.report.converged() &&
      outcome.best.report.solver != plan.solvers.front())
    next = outcome.best.report.solver;
  for (const std::int32_t b : island.bodies)
    if (static_cast<std::size_t>(b) < promoted_.size()) promoted_[b] = next;
}

}  // namespace coulomb::engine
