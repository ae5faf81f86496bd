#include <gtest/gtest.h>
#include <coulomb/solvers/SolverChooser.hpp>

#include "TestProblems.hpp"

#include <memory>

using namespace coulomb::solvers;

namespace {

// n contacts on a diagonal W (weakly coupled), all approaching unless `separating`.
ContactProblem diagonalProblem(int contacts, bool separating, double heavyRatio = 1.0) {
  Eigen::MatrixXd W = Eigen::MatrixXd::Identity(3 * contacts, 3 * contacts);
  W(0, 0) = heavyRatio;  // inverse mass along the first normal
  Eigen::VectorXd q = Eigen::VectorXd::Zero(3 * contacts);
  for (int c = 0; c < contacts; ++c) q[3 * c] = separating ? 0.5 : -1.0;
  return ContactProblem::contacts(DelassusOperator::dense(W), q, std::vector<double>(contacts, 0.5),
                                  "diag");
}

std::vector<std::string> names(const SolvePlan& plan) {
  std::vector<std::string> out;
  for (const SolveAttempt& a : plan.attempts) out.push_back(a.solver);
  return out;
}

}  // namespace

TEST(SolverChooser, SeparatingIslandIsExactAtZero) {
  const SolvePlan plan =
      SolverChooser().choose(diagonalProblem(6, true), {}, SolverChoice::automatic(), {});
  EXPECT_TRUE(plan.features.zeroIsExact);
  EXPECT_NE(plan.reason().find("r = 0 is exact"), std::string::npos) << plan.reason();
  // an equality row forbids the shortcut
  ContactProblem p = diagonalProblem(2, true);
  p.blocks.push_back(ConstraintBlock::equality());
  Eigen::MatrixXd W = Eigen::MatrixXd::Identity(7, 7);
  p.W = DelassusOperator::dense(W);
  p.q.conservativeResize(7);
  p.q[6] = 0.1;
  const SolvePlan withJoint = SolverChooser().choose(p, {}, SolverChoice::automatic(), {});
  EXPECT_FALSE(withJoint.features.zeroIsExact);
  EXPECT_EQ(withJoint.features.equalityRows, 1);
}

TEST(SolverChooser, OneContactIsExactLocalSolve) {
  const SolvePlan plan =
      SolverChooser().choose(diagonalProblem(1, false), {}, SolverChoice::automatic(), {});
  ASSERT_FALSE(plan.attempts.empty());
  EXPECT_EQ(plan.attempts.front().solver, "bgs");
  EXPECT_NE(plan.reason().find("one contact"), std::string::npos);
}

TEST(SolverChooser, NuDecidesBetweenNewtonAndGaussSeidel) {
  const ContactProblem p = diagonalProblem(20, false);
  const SolvePlan wellPosed =
      SolverChooser().choose(p, {120}, SolverChoice::automatic(), {});  // nu = 0.5
  EXPECT_EQ(wellPosed.attempts.front().solver, "ac_newton") << wellPosed.reason();
  EXPECT_NEAR(wellPosed.features.nu, 0.5, 1e-12);
  const SolvePlan pile =
      SolverChooser().choose(p, {24}, SolverChoice::automatic(), {});  // nu = 2.5
  // A cold start (no warm start) gets bgs sweeps with momentum, a warm-started pile pgs sweeps.
  EXPECT_EQ(pile.attempts.front().solver, "bgs_nncg") << pile.reason();
  EXPECT_FALSE(pile.features.warmStarted);
  ContactProblem warm = p;
  warm.warmStart = Eigen::VectorXd::Zero(p.size());
  (*warm.warmStart)[0] = 0.1;  // one contact carried load at the last step
  const SolvePlan warmPile = SolverChooser().choose(warm, {24}, SolverChoice::automatic(), {});
  EXPECT_TRUE(warmPile.features.warmStarted);
  EXPECT_EQ(warmPile.attempts.front().solver, "nncg") << warmPile.reason();
  EXPECT_NE(pile.reason().find("nu = 2.5"), std::string::npos) << pile.reason();
  EXPECT_EQ(pile.attempts[1].solver, "ac_newton");  // Newton as the fallback of a stalled pile
  // nncg gives way to Newton once it stagnates (ChooserSettings::pileStallSweeps); a user's
  // request runs with the user's options.
  EXPECT_EQ(pile.attempts.front().stallWindow, ChooserSettings{}.pileStallSweeps);
  EXPECT_EQ(SolverChooser()
                .choose(p, {24}, SolverChoice::preferred("pgs"), {})
                .attempts.front()
                .stallWindow,
            0);
}

TEST(SolverChooser, MassRatioForcesNewton) {
  const ContactProblem p = diagonalProblem(20, false, 1e4);
  const SolvePlan plan =
      SolverChooser().choose(p, {24}, SolverChoice::automatic(), {});  // nu 2.5 but kappa 1e4
  EXPECT_NEAR(plan.features.massRatio, 1e4, 1e-9);
  EXPECT_EQ(plan.attempts.front().solver, "ac_newton") << plan.reason();
  EXPECT_NE(plan.reason().find("mass ratio"), std::string::npos);
}

TEST(SolverChooser, FewActiveContactsTryBgsFirstWithACap) {
  const SolvePlan plan =
      SolverChooser().choose(diagonalProblem(3, false), {}, SolverChoice::automatic(), {});
  EXPECT_EQ(plan.attempts.front().solver, "bgs");
  EXPECT_GT(plan.attempts.front().maxIterations, 0);
  EXPECT_EQ(plan.attempts[1].solver, "ac_newton");
}

TEST(SolverChooser, BodySpaceIslandsTryShortBgsBeforeNewton) {
  // 20 contacts, each on its own body (W = identity in body space), nu = 0.5: Newton-sized, but
  // a sweep costs O(contacts) and one Newton step a factorization of W.
  auto factors = std::make_shared<BodySpaceDelassus>(20, std::vector<int>(20, 3));
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3, 6);
  J.leftCols<3>().setIdentity();
  for (int c = 0; c < 20; ++c) factors->setSide(c, 1, c, J, J.transpose());
  ContactProblem p = diagonalProblem(20, false);
  p.W = DelassusOperator::bodySpace(factors);
  EXPECT_EQ(SolverChooser().choose(p, {120}, SolverChoice::automatic(), {}).attempts.front().solver,
            "ac_newton");  // off
  ChooserSettings s;
  s.factoredTrySweeps = 30;
  const SolvePlan plan = SolverChooser(s).choose(p, {120}, SolverChoice::automatic(), {});
  EXPECT_TRUE(plan.features.factored);
  ASSERT_EQ(plan.attempts.size(), 3u);
  EXPECT_EQ(plan.attempts.front().solver, "bgs") << plan.reason();
  EXPECT_EQ(plan.attempts[1].solver, "ac_newton");
  EXPECT_EQ(plan.attempts.front().maxIterations, 30);
  EXPECT_NEAR(plan.features.massRatio, 1.0, 1e-12);  // the diagonal read from the factors
}

TEST(SolverChooser, LargeIslandsAvoidNewton) {
  ChooserSettings s;
  s.newtonMaxUnknowns = 30;
  const SolvePlan plan =
      SolverChooser(s).choose(diagonalProblem(20, false), {}, SolverChoice::automatic(), {});
  for (const SolveAttempt& a : plan.attempts) EXPECT_NE(a.solver, "ac_newton");
}

TEST(SolverChooser, NamedSoloAndChainRequests) {
  const ContactProblem p = diagonalProblem(5, false);
  const SolvePlan named = SolverChooser().choose(p, {}, SolverChoice::preferred("pgs"), {});
  EXPECT_EQ(named.attempts.front().solver, "pgs");
  EXPECT_GT(named.attempts.size(), 1u);                // fallbacks kept
  EXPECT_EQ(named.attempts.front().maxIterations, 0);  // a user's choice: the user's options
  const SolvePlan solo = SolverChooser().choose(p, {}, SolverChoice::only("pgs"), {});
  EXPECT_EQ(names(solo), std::vector<std::string>{"pgs"});
  const SolvePlan chain =
      SolverChooser().choose(p, {}, SolverChoice::chain({"fb_newton", "bgs"}), {});
  EXPECT_EQ(names(chain), (std::vector<std::string>{"fb_newton", "bgs"}));
}

TEST(SolverChooser, Deterministic) {
  const ContactProblem p = fixtures::randomMechanical(12, 30, 0.5, 2);
  const SolvePlan a = SolverChooser().choose(p, {30}, SolverChoice::automatic(), {});
  const SolvePlan b = SolverChooser().choose(p, {30}, SolverChoice::automatic(), {});
  EXPECT_EQ(a.attempts, b.attempts);
  EXPECT_EQ(a.reason(), b.reason());
}

// A plan is numbers and enums: its reason is formatted only when asked, and says the rule.
TEST(SolverChooser, TheReasonIsFormattedFromTheRule) {
  const SolvePlan pile =
      SolverChooser().choose(diagonalProblem(20, false), {24}, SolverChoice::automatic(), {});
  EXPECT_EQ(pile.rule, PlanRule::PileByNu);
  EXPECT_NE(pile.reason().find(planRuleName(PlanRule::PileByNu)), std::string::npos);
  EXPECT_NE(pile.reason().find("20 contacts"), std::string::npos) << pile.reason();
}

// Per-attempt limits of a user's chain reach the plan unchanged, and a preferred solver keeps its
// own limits in front of the automatic fallbacks.
TEST(SolverChooser, AttemptLimitsOfAChoiceAreKept) {
  SolverChoice chain = SolverChoice::chain({"bgs", "ac_newton"});
  chain.attempts[0].maxIterations = 7;
  chain.attempts[0].tolerance = 1e-9;
  const SolvePlan plan = SolverChooser().choose(diagonalProblem(5, false), {}, chain, {});
  EXPECT_EQ(plan.rule, PlanRule::Exactly);
  EXPECT_EQ(plan.attempts, chain.attempts);
  EXPECT_EQ(plan.optionsFor(plan.attempts[0]).maxIterations, 7);
  EXPECT_EQ(plan.optionsFor(plan.attempts[0]).tolerance, 1e-9);
  SolverChoice preferred = SolverChoice::preferred("bgs_nncg");
  preferred.attempts[0].stallWindow = 9;
  const SolvePlan p = SolverChooser().choose(diagonalProblem(20, false), {24}, preferred, {});
  EXPECT_EQ(p.attempts.front(), preferred.attempts.front());
  EXPECT_EQ(p.attempts[1].solver, "ac_newton");  // the pile's fallbacks, bgs_nncg not repeated
  for (std::size_t k = 1; k < p.attempts.size(); ++k) EXPECT_NE(p.attempts[k].solver, "bgs_nncg");
}
