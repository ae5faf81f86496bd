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

}  // namespace

TEST(SolverChooser, SeparatingIslandIsExactAtZero) {
  const SolvePlan plan = SolverChooser().choose(diagonalProblem(6, true), {}, "auto", {});
  EXPECT_TRUE(plan.features.zeroIsExact);
  EXPECT_NE(plan.reason.find("r = 0 is exact"), std::string::npos) << plan.reason;
  // an equality row forbids the shortcut
  ContactProblem p = diagonalProblem(2, true);
  p.blocks.push_back(ConstraintBlock::equality());
  Eigen::MatrixXd W = Eigen::MatrixXd::Identity(7, 7);
  p.W = DelassusOperator::dense(W);
  p.q.conservativeResize(7);
  p.q[6] = 0.1;
  const SolvePlan withJoint = SolverChooser().choose(p, {}, "auto", {});
  EXPECT_FALSE(withJoint.features.zeroIsExact);
  EXPECT_EQ(withJoint.features.equalityRows, 1);
}

TEST(SolverChooser, OneContactIsExactLocalSolve) {
  const SolvePlan plan = SolverChooser().choose(diagonalProblem(1, false), {}, "auto", {});
  ASSERT_FALSE(plan.solvers.empty());
  EXPECT_EQ(plan.solvers.front(), "bgs");
  EXPECT_NE(plan.reason.find("one contact"), std::string::npos);
}

TEST(SolverChooser, NuDecidesBetweenNewtonAndGaussSeidel) {
  const ContactProblem p = diagonalProblem(20, false);
  const SolvePlan wellPosed = SolverChooser().choose(p, {120}, "auto", {});  // nu = 0.5
  EXPECT_EQ(wellPosed.solvers.front(), "ac_newton") << wellPosed.reason;
  EXPECT_NEAR(wellPosed.features.nu, 0.5, 1e-12);
  const SolvePlan pile = SolverChooser().choose(p, {24}, "auto", {});  // nu = 2.5
  EXPECT_EQ(pile.solvers.front(), "pgs") << pile.reason;
  EXPECT_NE(pile.reason.find("nu = 2.5"), std::string::npos) << pile.reason;
  EXPECT_EQ(pile.solvers[1], "ac_newton");  // Newton as the fallback of a stalled pile
  // pgs gives way to Newton once it stagnates (ChooserSettings::pileStallSweeps); a user's
  // request runs with the user's options.
  ASSERT_FALSE(pile.stallWindows.empty());
  EXPECT_EQ(pile.stallWindows.front(), ChooserSettings{}.pileStallSweeps);
  EXPECT_TRUE(SolverChooser().choose(p, {24}, "pgs", {}).stallWindows.empty());
}

TEST(SolverChooser, MassRatioForcesNewton) {
  const ContactProblem p = diagonalProblem(20, false, 1e4);
  const SolvePlan plan = SolverChooser().choose(p, {24}, "auto", {});  // nu 2.5 but kappa 1e4
  EXPECT_NEAR(plan.features.massRatio, 1e4, 1e-9);
  EXPECT_EQ(plan.solvers.front(), "ac_newton") << plan.reason;
  EXPECT_NE(plan.reason.find("mass ratio"), std::string::npos);
}

TEST(SolverChooser, FewActiveContactsTryBgsFirstWithACap) {
  const SolvePlan plan = SolverChooser().choose(diagonalProblem(3, false), {}, "auto", {});
  EXPECT_EQ(plan.solvers.front(), "bgs");
  ASSERT_FALSE(plan.iterationCaps.empty());
  EXPECT_GT(plan.iterationCaps.front(), 0);
  EXPECT_EQ(plan.solvers[1], "ac_newton");
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
  EXPECT_EQ(SolverChooser().choose(p, {120}, "auto", {}).solvers.front(), "ac_newton");  // off
  ChooserSettings s;
  s.factoredTrySweeps = 30;
  const SolvePlan plan = SolverChooser(s).choose(p, {120}, "auto", {});
  EXPECT_TRUE(plan.features.factored);
  ASSERT_EQ(plan.solvers.size(), 3u);
  EXPECT_EQ(plan.solvers.front(), "bgs") << plan.reason;
  EXPECT_EQ(plan.solvers[1], "ac_newton");
  ASSERT_FALSE(plan.iterationCaps.empty());
  EXPECT_EQ(plan.iterationCaps.front(), 30);
  EXPECT_NEAR(plan.features.massRatio, 1.0, 1e-12);  // the diagonal read from the factors
}

TEST(SolverChooser, LargeIslandsAvoidNewton) {
  ChooserSettings s;
  s.newtonMaxUnknowns = 30;
  const SolvePlan plan = SolverChooser(s).choose(diagonalProblem(20, false), {}, "auto", {});
  for (const std::string& n : plan.solvers) EXPECT_NE(n, "ac_newton");
}

TEST(SolverChooser, NamedSoloAndChainRequests) {
  const ContactProblem p = diagonalProblem(5, false);
  const SolvePlan named = SolverChooser().choose(p, {}, "pgs", {});
  EXPECT_EQ(named.solvers.front(), "pgs");
  EXPECT_GT(named.solvers.size(), 1u);  // fallbacks kept
  EXPECT_TRUE(named.iterationCaps.empty());
  const SolvePlan solo = SolverChooser().choose(p, {}, "pgs!", {});
  EXPECT_EQ(solo.solvers, std::vector<std::string>{"pgs"});
  const SolvePlan chain = SolverChooser().choose(p, {}, "fb_newton,bgs", {});
  EXPECT_EQ(chain.solvers, (std::vector<std::string>{"fb_newton", "bgs"}));
}

TEST(SolverChooser, Deterministic) {
  const ContactProblem p = fixtures::randomMechanical(12, 30, 0.5, 2);
  const SolvePlan a = SolverChooser().choose(p, {30}, "auto", {});
  const SolvePlan b = SolverChooser().choose(p, {30}, "auto", {});
  EXPECT_EQ(a.solvers, b.solvers);
  EXPECT_EQ(a.reason, b.reason);
}
