// The automatic rules listed from SolverChooser itself (AutomaticRules.hpp).
#include <coulomb/solvers/AutomaticRules.hpp>
#include <coulomb/solvers/SolverChooser.hpp>

#include <limits>
#include <sstream>
#include <stdexcept>

namespace coulomb::solvers {
namespace {

std::string number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

/// Features of an island of `contacts` active contacts (3 unknowns each), dofs and kappa unknown.
ProblemFeatures contactIsland(int contacts) {
  ProblemFeatures f;
  f.contacts = f.activeContacts = contacts;
  f.unknowns = 3 * contacts;
  return f;
}

/// Per rule, in the chooser's order: when it applies, and features that meet it (and no earlier
/// rule).
std::vector<std::pair<AutomaticRule, ProblemFeatures>> examples(const ChooserSettings& s) {
  std::vector<std::pair<AutomaticRule, ProblemFeatures>> out;
  auto add = [&out](PlanRule rule, std::string when, const ProblemFeatures& f) {
    out.push_back({AutomaticRule{rule, std::move(when), {}, true}, f});
  };
  ProblemFeatures zero = contactIsland(2);
  zero.zeroIsExact = true;
  add(PlanRule::ZeroIsExact,
      "every contact separating or resting (q_N >= 0) and no equality or bounded rows (r = 0 "
      "is exact)",
      zero);
  add(PlanRule::OneContact, "one contact, no joint rows", contactIsland(1));
  ProblemFeatures equality;
  equality.equalityRows = equality.unknowns = 12;
  add(PlanRule::EqualityRowsOnly,
      "joint equality rows only (no contacts, limits, motors or joint friction)", equality);
  ProblemFeatures joints = equality;
  joints.boundedRows = 2;
  joints.unknowns = 14;
  add(PlanRule::JointRowsOnly,
      "joint rows with limits, motors or joint friction, no contacts, at most "
      "newton_max_unknowns = " +
          std::to_string(s.newtonMaxUnknowns) + " unknowns",
      joints);
  // Warm-started examples: a cold start puts bgs_nncg where nncg is (said in the text).
  ProblemFeatures large = contactIsland(s.newtonMaxUnknowns / 3 + 1);
  large.warmStarted = true;
  add(PlanRule::LargeIsland,
      "more than newton_max_unknowns = " + std::to_string(s.newtonMaxUnknowns) +
          " unknowns (from a cold start bgs_nncg instead of nncg)",
      large);
  ProblemFeatures heavy = contactIsland(10);
  heavy.massRatio = 10.0 * s.newtonMassRatio;
  add(PlanRule::MassRatio,
      "mass ratio kappa (max / min W_NN over active contacts) above newton_mass_ratio = " +
          number(s.newtonMassRatio),
      heavy);
  ProblemFeatures pile = contactIsland(10);
  pile.warmStarted = true;
  pile.degreesOfFreedom = 6;
  pile.nu = 2.0 * s.pileNu + 1.0;
  add(PlanRule::PileByNu,
      "a pile or tower: nu = (3 active contacts + rows) / dofs above pile_nu = " +
          number(s.pileNu) + " (from a cold start bgs_nncg instead of nncg)",
      pile);
  ProblemFeatures captured = contactIsland(s.pileContactsWithoutDofs);
  captured.warmStarted = true;
  add(PlanRule::PileBySize,
      "dofs unknown (a captured problem) and at least pile_contacts_without_dofs = " +
          std::to_string(s.pileContactsWithoutDofs) +
          " contacts (from a cold start bgs_nncg instead of nncg)",
      captured);
  ProblemFeatures factored = contactIsland(10);
  factored.factored = true;
  add(PlanRule::FactoredTry,
      "body-space W (a World island) when factored_try_sweeps > 0 (now " +
          std::to_string(s.factoredTrySweeps) + ")",
      factored);
  ProblemFeatures few = contactIsland(2 * s.smallActiveContacts + 2);
  few.activeContacts = s.smallActiveContacts;
  add(PlanRule::FewActiveContacts,
      "at most small_active_contacts = " + std::to_string(s.smallActiveContacts) +
          " active contacts",
      few);
  add(PlanRule::WellPosed, "otherwise (well-posed enough for Newton)", contactIsland(10));
  return out;
}

}  // namespace

std::vector<AutomaticRule> automaticRules(const ChooserSettings& settings) {
  const SolverChooser chooser(settings);
  std::vector<AutomaticRule> rules;
  for (auto& [rule, features] : examples(settings)) {
    SolvePlan plan;
    chooser.automatic(features, plan);
    if (plan.rule == rule.rule) {
      rule.attempts = plan.attempts;
    } else if (rule.rule == PlanRule::FactoredTry && settings.factoredTrySweeps <= 0) {
      rule.enabled = false;  // the chooser skips it: off
    } else {
      throw std::logic_error(std::string("automaticRules: the example of rule '") +
                             planRuleName(rule.rule) + "' now gets rule '" +
                             planRuleName(plan.rule) + "'; update AutomaticRules.cpp");
    }
    rules.push_back(std::move(rule));
  }
  return rules;
}

std::string attemptsText(const std::vector<SolveAttempt>& attempts) {
  std::ostringstream out;
  for (std::size_t i = 0; i < attempts.size(); ++i) {
    const SolveAttempt& a = attempts[i];
    out << (i > 0 ? ", " : "") << a.solver;
    if (a.maxIterations > 0) out << " (cap " << a.maxIterations << ")";
    if (a.stallWindow > 0) out << " (stall window " << a.stallWindow << ")";
    if (a.tolerance > 0) out << " (tol " << a.tolerance << ")";
  }
  return out.str();
}

std::string automaticListing(const ChooserSettings& settings) {
  std::ostringstream out;
  out << "auto\tthe default: per island, the first rule below that applies picks a chain of "
         "solvers, tried in order from the best answer so far until one converges (every "
         "report says which rule and which solvers ran). NAME puts a solver first, NAME! runs "
         "it alone, a,b,c runs that chain\n";
  int index = 1;
  for (const AutomaticRule& rule : automaticRules(settings))
    out << "  " << index++ << ". " << rule.when << ": "
        << (rule.enabled ? attemptsText(rule.attempts) : std::string("off")) << "\n";
  return out.str();
}

}  // namespace coulomb::solvers
