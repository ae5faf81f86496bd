#pragma once
// The promotion rule of the solve policy (solvers::PromotionRule, docs/tuning.md "The solve
// policy"): the fallback that finished an island's step after a near miss of the first solver
// runs once more, first, in that island's next step, so that the one-off correction its impulses
// carry does not come back through the warm start (docs/benchmarks.md, "Long runs").
//
// Automatic plans only. State: per body slot, the name of the solver to promote ("" = none),
// saved in snapshots so a continued run stays bit-identical. A promotion is used once: the
// promoted step never promotes.
#include <coulomb/engine/IslandBuilder.hpp>
#include <coulomb/solvers/SolvePlan.hpp>
#include <coulomb/solvers/SolvePolicy.hpp>
#include <coulomb/solvers/SolveWithFallback.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace coulomb::engine {

class SolverPromotion {
 public:
  void resize(std::size_t slots) { promoted_.resize(slots); }
  void reset(std::size_t slot) { promoted_[slot].clear(); }
  void resetAll() {
    for (std::string& name : promoted_) name.clear();
  }

  /// Puts the solver promoted for one of the island's bodies in front of `plan` (capped at
  /// rule.iterationCap, no stall window, tolerance scaled by rule.toleranceScale) with the plan as
  /// it was behind it (when the short attempt fails, the plan continues from its best iterate).
  /// Does nothing when none is promoted, the plan does not hold it, the rule is off or the island
  /// has at most rule.minUnknowns unknowns. Sets plan.promoted.
  void apply(const Island& island, const solvers::PromotionRule& rule,
             solvers::SolvePlan& plan) const;
  /// After the solve of an automatic plan: promote the solver that finished the step when the
  /// plan's first attempt did not converge but ended within rule.nearMiss of the tolerance and a
  /// later one converged within rule.iterationCap iterations; clear the island's promotions
  /// otherwise, and always after a promoted plan or a plan the rule does not cover.
  void record(const Island& island, const solvers::PromotionRule& rule, bool automaticPlan,
              const solvers::SolvePlan& plan, const solvers::PlanOutcome& outcome);

  [[nodiscard]] std::vector<std::string>& names() { return promoted_; }  // snapshots
  [[nodiscard]] const std::vector<std::string>& names() const { return promoted_; }

 private:
  std::vector<std::string> promoted_;  // per body slot
};

}  // namespace coulomb::engine
