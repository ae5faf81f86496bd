#pragma once
// The per-island plan (docs/solver-derivations.md section 9, tuned on the corpus: docs/solvers.md
// "Choosing a solver") from a SolverChoice (SolvePolicy.hpp):
//   Automatic  the primary and its fallbacks from cheap features of the problem (contacts,
//              scalar rows, nu = 3n/m when the dof count m is known, the mass-ratio estimate
//              kappa from W's diagonal, size); the rule is kept in the plan (SolvePlan::reason);
//   Preferred  the choice's attempts first, then the automatic plan's other solvers (so a
//              failure never leaves an island unsolved; the report says which ran);
//   Exactly    the choice's attempts alone, in order.
// Allocation-free when `plan` is reused (its vector keeps its capacity; solver names are short).
#include <coulomb/solvers/ContactProblem.hpp>
#include <coulomb/solvers/SolvePlan.hpp>
#include <coulomb/solvers/SolvePolicy.hpp>

namespace coulomb::solvers {

/// Measures the features of docs/solver-derivations.md section 9 (one pass over q and W's diagonal
/// blocks).
ProblemFeatures measureProblemFeatures(const ContactProblem& problem,
                                       const IslandFeatures& features);

class SolverChooser {
 public:
  explicit SolverChooser(ChooserSettings settings = {}) : settings_(settings) {}

  /// Fills `plan` (reused: no allocation once its capacity suffices).
  void choose(const ContactProblem& problem, const IslandFeatures& features,
              const SolverChoice& choice, const SolverOptions& options, SolvePlan& plan) const;
  [[nodiscard]] SolvePlan choose(const ContactProblem& problem, const IslandFeatures& features,
                                 const SolverChoice& choice, const SolverOptions& options) const {
    SolvePlan plan;
    choose(problem, features, choice, options, plan);
    return plan;
  }

  [[nodiscard]] const ChooserSettings& settings() const { return settings_; }

  /// The automatic rules alone, on features already measured: sets plan.rule and
  /// plan.attempts (what choose() does for `auto` after measureProblemFeatures). Public so that
  /// the rules can be listed from the code that applies them (AutomaticRules.hpp).
  void automatic(const ProblemFeatures& f, SolvePlan& plan) const;

 private:
  ChooserSettings settings_;
};

}  // namespace coulomb::solvers
