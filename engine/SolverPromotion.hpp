#pragma once
// Fallback promotion: the solver that had to finish an island's step goes first in the next one.
//
// Why (docs/benchmarks.md, "Long runs"): when pgs stagnates just above the tolerance on a resting
// pile, ac_newton finishes the step, and its impulses then carry a one-off correction of the
// velocity error pgs left in the bodies. Warm-started from those impulses, the next step starts
// off by that correction, in the slow mode pgs could not reduce: pgs stalls again and Newton runs
// again, every other step (a 55-box pyramid from step ~4 500 on: 2 300 Newton fallbacks in 10 000
// steps, mean 3.2 ms per step). One more step with Newton first, solved to a tighter tolerance
// (kPromotedToleranceScale), returns impulses without the correction; pgs then needs 0-1 sweeps
// for the next ~15 steps (8 fallbacks in 10 000 steps, mean 0.40 ms per step).
//
// Automatic plans only (World::solveIsland). State: per body slot, the name of the solver to
// promote ("" = none), saved in snapshots so a continued run stays bit-identical. A promotion is
// used once: the promoted step never promotes.
#include <coulomb/engine/IslandBuilder.hpp>
#include <coulomb/solvers/SolvePlan.hpp>
#include <coulomb/solvers/SolveWithFallback.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace coulomb::engine {

/// [-] The promoted attempt's tolerance as a fraction of the plan's: it must actually iterate
/// (its start is often just below the plan's tolerance) and one Newton step goes from ~1e-6 to
/// ~1e-9. Default 0.01.
inline constexpr double kPromotedToleranceScale = 0.01;
/// [iterations] Cap of the promoted attempt: it polishes a step whose start is already near the
/// tolerance. Default 5: Newton needs 1-2 there; on a 55-box pyramid a few such steps needed
/// 8-49 iterations (5-50 ms each) to reach the tighter tolerance, which the cap avoids (the
/// attempt still counts as converged within the plan's tolerance).
inline constexpr int kPromotedIterationCap = 5;
/// [-] A fallback is promoted only when the plan's first solver ended within this factor of the
/// tolerance (it stagnated just above it: the alternation's signature). Default 10: on the
/// pyramid pgs ends at 1.0-2.0e-6 for a 1e-6 tolerance; on the masonry arch pgs ends at ~1e-2
/// and Newton needs 3-48 iterations after it, where a promoted 5-iteration attempt from the
/// warm start only failed (0.22) before the usual plan ran.
inline constexpr double kPromotionNearMiss = 10.0;
/// [unknowns] Only islands with more unknowns are promoted (World::solveIsland): there a Newton
/// fallback is a sparse LU (~6 ms on the 1 200-unknown pyramid), while below it it is a dense LU
/// of a few hundred rows (< 1 ms). Default 300, the Newton dense threshold. Measured: promoting
/// on the masonry arch (216 unknowns) changed its trajectory so that its final indeterminate
/// answer missed the abutment criterion (1.3 % against 1e-3); without it 7.9e-8.
inline constexpr int kPromotionMinUnknowns = 300;

class SolverPromotion {
 public:
  void resize(std::size_t slots) { promoted_.resize(slots); }
  void reset(std::size_t slot) { promoted_[slot].clear(); }

  /// `plan` with the solver promoted for one of the island's bodies run first (capped at
  /// kPromotedIterationCap, no stall window, its tolerance scaled) and then the whole plan as it
  /// was (when the short attempt fails, the plan continues from its best iterate), or unchanged
  /// when none is or when the plan does not hold it. `promoted` tells which.
  [[nodiscard]] solvers::SolvePlan apply(const Island& island, solvers::SolvePlan plan,
                                         bool& promoted) const;
  /// After the solve: promote the solver that finished the step when the plan's first solver did
  /// not converge but ended within kPromotionNearMiss of the tolerance, and a later one
  /// converged within kPromotedIterationCap iterations (a quick finish from a near miss: the
  /// alternation's signature; on the 210-box pyramid, bgs -> pgs fallbacks of ~170 sweeps
  /// promoted made it slower, 11.7 -> 14.6 ms/step over 3000 steps); clear the island's promotions
  /// otherwise, and always when `noPromotion` (the plan was itself promoted, or a named solver's:
  /// World promotes in automatic plans only, a named solver always runs first).
  void record(const Island& island, const solvers::SolvePlan& plan,
              const solvers::PlanOutcome& outcome, bool noPromotion);

  [[nodiscard]] std::vector<std::string>& names() { return promoted_; }  // snapshots
  [[nodiscard]] const std::vector<std::string>& names() const { return promoted_; }

 private:
  std::vector<std::string> promoted_;  // per body slot
};

}  // namespace coulomb::engine
