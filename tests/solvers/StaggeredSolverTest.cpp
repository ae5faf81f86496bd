#include <gtest/gtest.h>
#include <coulomb/solvers/newton/AcNewtonSolver.hpp>
#include <coulomb/solvers/staggered/StaggeredSolver.hpp>

#include "TestProblems.hpp"

#include <cmath>

using namespace coulomb::solvers;

TEST(StaggeredSolver, SingleContactAnalytic) {
  const Eigen::Matrix3d W = Eigen::Matrix3d::Identity();
  SolveOutcome out = StaggeredSolver().solve(fixtures::singleContact(W, {0.3, 1, -2}, 0.5));
  EXPECT_EQ(out.report.status, SolverStatus::Converged);
  EXPECT_LT(out.impulses.norm(), 1e-8);
  out = StaggeredSolver().solve(fixtures::singleContact(W, {-1, 0.2, -0.1}, 0.5));
  EXPECT_EQ(out.report.status, SolverStatus::Converged);
  EXPECT_LT((out.impulses - Eigen::Vector3d(1, -0.2, 0.1)).norm(), 1e-7);
  const double c = std::cos(0.3), s = std::sin(0.3);  // slip: r_T = -mu r_N (c, s)
  out = StaggeredSolver().solve(fixtures::singleContact(W, {-1, 2 * c, 2 * s}, 0.5));
  EXPECT_EQ(out.report.status, SolverStatus::Converged);
  EXPECT_NEAR(out.impulses[0], 1.0, 1e-7);
  EXPECT_NEAR(out.impulses[1], -0.5 * c, 1e-7);
  EXPECT_NEAR(out.impulses[2], -0.5 * s, 1e-7);
  EXPECT_NE(out.report.message.find("APGD iterations"), std::string::npos);
}

// nu <= 1 (unique solution): the fixed point of the staggered QPs is ac_newton's solution.
TEST(StaggeredSolver, SameSolutionAsAcNewtonOnWellPosedProblems) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const ContactProblem p = fixtures::randomMechanical(4, 30, 0.3, seed);
    SolverOptions o;
    o.tolerance = 1e-10;
    const SolveOutcome st = StaggeredSolver().solve(p, o);
    const SolveOutcome ac = AcNewtonSolver().solve(p, o);
    EXPECT_EQ(st.report.status, SolverStatus::Converged) << st.report.message;
    EXPECT_LT((st.impulses - ac.impulses).norm(), 1e-6 * (1 + ac.impulses.norm())) << seed;
    EXPECT_GT(st.report.iterations, 0);
  }
}

TEST(StaggeredSolver, ScalarRowsJoinTheNormalStep) {
  const Eigen::MatrixXd W = 2.0 * Eigen::MatrixXd::Identity(5, 5);
  ContactProblem p;
  p.W = DelassusOperator::dense(W);
  p.q = (Eigen::VectorXd(5) << -2, 0.2, 0.0, 1.0, -4.0).finished();
  p.blocks = {ConstraintBlock::contact(0.5), ConstraintBlock::equality(),
              ConstraintBlock::bounded(-0.5, 0.5)};
  const SolveOutcome out = StaggeredSolver().solve(p);
  EXPECT_EQ(out.report.status, SolverStatus::Converged) << out.report.message;
  EXPECT_NEAR(out.impulses[3], -0.5, 1e-7);
  EXPECT_NEAR(out.impulses[4], 0.5, 1e-7);
}

TEST(StaggeredSolver, DeterministicAndFixtures) {
  const ContactProblem p = fixtures::loadFixture("Rover1039");
  const SolveOutcome a = StaggeredSolver().solve(p), b = StaggeredSolver().solve(p);
  EXPECT_EQ(a.report.status, SolverStatus::Converged) << a.report.message;
  EXPECT_EQ(a.impulses, b.impulses);
}
