#include <gtest/gtest.h>
#include <coulomb/solvers/bgs/BgsSolver.hpp>

#include "TestProblems.hpp"

using namespace coulomb::solvers;

TEST(BgsSolver, DecoupledContactsInOneSweep) {
  // Block-diagonal W: each local solve is the global answer, one sweep suffices.
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(6, 6);
  W.block<3, 3>(0, 0) = Eigen::Vector3d(2, 1, 1).asDiagonal();
  W.block<3, 3>(3, 3) = Eigen::Vector3d(1, 3, 3).asDiagonal();
  const ContactProblem p =
      ContactProblem::contacts(DelassusOperator::dense(W),
                               (Eigen::VectorXd(6) << -2, 3, 4, -1, 0.1, 0).finished(), {0.5, 0.5});
  SolverOptions o;
  o.tolerance = 1e-14;
  const SolveOutcome out = BgsSolver().solve(p, o);
  EXPECT_EQ(out.report.status, SolverStatus::Converged);
  EXPECT_EQ(out.report.iterations, 1);
  EXPECT_LT((out.impulses.head<3>() - Eigen::Vector3d(1, -0.3, -0.4)).norm(), 1e-15);
}

TEST(BgsSolver, CoupledRandomProblems) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const ContactProblem p = fixtures::randomMechanical(5, 30, 0.6, seed);
    const SolveOutcome out = BgsSolver().solve(p);
    EXPECT_EQ(out.report.status, SolverStatus::Converged) << seed << out.report.message;
    EXPECT_LE(out.report.residual, 1e-8);
  }
}

TEST(BgsSolver, StallSwitchesOmegaThenStops) {
  const ContactProblem p = fixtures::randomMechanical(8, 9, 0.9, 3);  // nu = 2.7, redundant
  SolverOptions o;
  o.tolerance = 1e-300;  // unreachable: force the stall path
  o.maxIterations = 100000;
  o.timeLimitSeconds = 20;
  BgsOptions b;
  b.stallWindow = 20;
  const SolveOutcome out = BgsSolver(b).solve(p, o);
  EXPECT_EQ(out.report.status, SolverStatus::Stalled);
  EXPECT_NE(out.report.message.find("omega -> 0.7"), std::string::npos);
  EXPECT_TRUE(out.impulses.allFinite());
}
