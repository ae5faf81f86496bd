#pragma once
// What `auto`, the default solver choice, does: the automatic rules of SolverChooser in their
// order (first match wins), each with when it applies and the attempts it chains, for
// `coulomb solvers` and docs/solvers.md ("Choosing a solver"). The attempts are not copied: each
// rule's chain is what SolverChooser::automatic gives on features chosen to meet that rule, so
// the listing cannot drift from the chooser.
#include <coulomb/solvers/SolvePlan.hpp>
#include <coulomb/solvers/SolvePolicy.hpp>

#include <string>
#include <vector>

namespace coulomb::solvers {

struct AutomaticRule {
  PlanRule rule = PlanRule::WellPosed;
  std::string when;                    // the condition, with the settings' thresholds
  std::vector<SolveAttempt> attempts;  // in order; empty when the rule is off
  bool enabled = true;                 // FactoredTry is off while factoredTrySweeps == 0
};

/// The rules of `settings` in the chooser's order. Throws std::logic_error if the chooser no
/// longer picks a rule on its example features (the listing must then be updated).
std::vector<AutomaticRule> automaticRules(const ChooserSettings& settings = {});

/// "bgs cap 50, ac_newton, fb_newton": the attempts with their non-default limits.
std::string attemptsText(const std::vector<SolveAttempt>& attempts);

/// The `auto` entry of `coulomb solvers`: "auto\t<summary>" then one indented line per rule.
std::string automaticListing(const ChooserSettings& settings = {});

}  // namespace coulomb::solvers
