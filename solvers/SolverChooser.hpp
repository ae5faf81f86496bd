#pragma once
// The per-island plan (SOLVERS.md section 9): a named solver with a fallback, or `auto`, which
// reads cheap features of the problem (contacts, nu = 3n/m, bilateral rows) and picks the primary
// solver and its fallbacks, writing the reason into the plan.
#include <coulomb/solvers/ContactProblem.hpp>
#include <coulomb/solvers/SolvePlan.hpp>

#include <string>

namespace coulomb::solvers {

class SolverChooser {
 public:
  /// `requested` is a registry name or "auto". A named solver gets the fallbacks of its family
  /// so a failure never leaves an island unsolved (the report says which ran).
  [[nodiscard]] SolvePlan choose(const ContactProblem& problem, const IslandFeatures& features,
                                 const std::string& requested, const SolverOptions& options) const;
};

}  // namespace coulomb::solvers
