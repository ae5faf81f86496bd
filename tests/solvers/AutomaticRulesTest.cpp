// solvers/AutomaticRules: the listing of `auto` in `coulomb solvers` says what SolverChooser does:
// every rule in the chooser's order with the chain it builds, on example features and on real
// problems.
#include <gtest/gtest.h>
#include <coulomb/solvers/AutomaticRules.hpp>
#include <coulomb/solvers/SolverChooser.hpp>

#include <string>
#include <vector>

using namespace coulomb::solvers;

namespace {

const AutomaticRule& ruleOf(const std::vector<AutomaticRule>& rules, PlanRule rule) {
  for (const AutomaticRule& r : rules)
    if (r.rule == rule) return r;
  throw std::runtime_error("no such rule");
}

/// n approaching contacts on an identity W.
ContactProblem contacts(int n, bool warmStarted = true) {
  const Eigen::MatrixXd W = Eigen::MatrixXd::Identity(3 * n, 3 * n);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(3 * n);
  for (int c = 0; c < n; ++c) q[3 * c] = -1.0;
  ContactProblem p =
      ContactProblem::contacts(DelassusOperator::dense(W), q, std::vector<double>(n, 0.5), "p");
  if (warmStarted) p.warmStart = -q;  // as after a step that loaded every contact
  return p;
}

}  // namespace

TEST(AutomaticRules, EveryRuleOfTheChooserInItsOrder) {
  const std::vector<AutomaticRule> rules = automaticRules();
  const std::vector<PlanRule> order = {
      PlanRule::ZeroIsExact,       PlanRule::OneContact,  PlanRule::EqualityRowsOnly,
      PlanRule::JointRowsOnly,     PlanRule::LargeIsland, PlanRule::MassRatio,
      PlanRule::PileByNu,          PlanRule::PileBySize,  PlanRule::FactoredTry,
      PlanRule::FewActiveContacts, PlanRule::WellPosed};
  ASSERT_EQ(rules.size(), order.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    EXPECT_EQ(rules[i].rule, order[i]) << i;
    EXPECT_FALSE(rules[i].when.empty()) << i;
    EXPECT_EQ(rules[i].enabled, order[i] != PlanRule::FactoredTry) << i;  // off by default
    EXPECT_EQ(rules[i].attempts.empty(), !rules[i].enabled) << i;
  }
  EXPECT_EQ(attemptsText(ruleOf(rules, PlanRule::EqualityRowsOnly).attempts),
            "ldlt, ac_newton, bgs");
  EXPECT_EQ(attemptsText(ruleOf(rules, PlanRule::PileByNu).attempts),
            "nncg (stall window 20), ac_newton, bgs");
  EXPECT_EQ(attemptsText(ruleOf(rules, PlanRule::LargeIsland).attempts), "nncg, pgs");
  EXPECT_EQ(attemptsText(ruleOf(rules, PlanRule::FewActiveContacts).attempts),
            "bgs (cap 50), ac_newton, fb_newton");
  // Thresholds come from the settings, and a rule switched on by them is listed with its chain.
  ChooserSettings settings;
  settings.factoredTrySweeps = 30;
  settings.newtonMaxUnknowns = 900;
  settings.pileContactsWithoutDofs = 200;
  const std::vector<AutomaticRule> tuned = automaticRules(settings);
  EXPECT_EQ(attemptsText(ruleOf(tuned, PlanRule::FactoredTry).attempts),
            "bgs (cap 30), ac_newton, fb_newton");
  EXPECT_NE(ruleOf(tuned, PlanRule::LargeIsland).when.find("newton_max_unknowns = 900"),
            std::string::npos);
}

TEST(AutomaticRules, ListedChainsAreWhatTheChooserDoesOnProblems) {
  const std::vector<AutomaticRule> rules = automaticRules();
  const SolverChooser chooser;
  const auto chosen = [&](const ContactProblem& p, int dofs) {
    return chooser.choose(p, {dofs}, SolverChoice::automatic(), {}).attempts;
  };
  EXPECT_EQ(chosen(contacts(1), 0), ruleOf(rules, PlanRule::OneContact).attempts);
  EXPECT_EQ(chosen(contacts(20), 24), ruleOf(rules, PlanRule::PileByNu).attempts);  // nu 2.5
  // From a cold start the pile's first solver is bgs_nncg (the rule's text says so).
  std::vector<SolveAttempt> cold = ruleOf(rules, PlanRule::PileByNu).attempts;
  cold.front().solver = "bgs_nncg";
  EXPECT_EQ(chosen(contacts(20, false), 24), cold);
  EXPECT_EQ(chosen(contacts(20), 120), ruleOf(rules, PlanRule::WellPosed).attempts);
  EXPECT_EQ(chosen(contacts(2), 0), ruleOf(rules, PlanRule::FewActiveContacts).attempts);
}

TEST(AutomaticRules, ListingNamesAutoAsTheDefaultWithOneLinePerRule) {
  const std::string text = automaticListing();
  EXPECT_EQ(text.rfind("auto\tthe default: per island", 0), 0u) << text;
  EXPECT_NE(text.find("\n  3. joint equality rows only (no contacts, limits, motors or joint "
                      "friction): ldlt, ac_newton, bgs\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("\n  9. body-space W (a World island) when factored_try_sweeps > 0 (now "
                      "0): off\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("\n  11. otherwise (well-posed enough for Newton): ac_newton, bgs, "
                      "fb_newton\n"),
            std::string::npos)
      << text;
}
