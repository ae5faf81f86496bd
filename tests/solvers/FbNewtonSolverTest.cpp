#include <gtest/gtest.h>
#include <coulomb/solvers/CoulombLaw.hpp>
#include <coulomb/solvers/newton/AcNewtonSolver.hpp>
#include <coulomb/solvers/newton/FbNewtonSolver.hpp>

#include "TestProblems.hpp"

using namespace coulomb::solvers;

// Single contact, W = I, mu = 0.5: the analytic answers of docs/solver-derivations.md (7.4) for the
// exact cone.
TEST(FbNewtonSolver, SingleContactAnalytic) {
  const Eigen::Matrix3d W = Eigen::Matrix3d::Identity();
  const double mu = 0.5;
  // take-off: r = 0
  SolveOutcome out = FbNewtonSolver().solve(fixtures::singleContact(W, {0.3, 1, -2}, mu));
  EXPECT_EQ(out.report.status, SolverStatus::Converged);
  EXPECT_LT(out.impulses.norm(), 1e-12);
  // stick: r = -q
  out = FbNewtonSolver().solve(fixtures::singleContact(W, {-1, 0.2, -0.1}, mu));
  EXPECT_EQ(out.report.status, SolverStatus::Converged);
  EXPECT_LT((out.impulses - Eigen::Vector3d(1, -0.2, 0.1)).norm(), 1e-8);
  // slip at 30 degrees: r_N = 1, r_T = -mu (cos, sin), u_T = q_T + r_T along (cos, sin)
  const double c = std::cos(0.5236), s = std::sin(0.5236);
  out = FbNewtonSolver().solve(fixtures::singleContact(W, {-1, 2 * c, 2 * s}, mu));
  EXPECT_EQ(out.report.status, SolverStatus::Converged);
  EXPECT_NEAR(out.impulses[0], 1.0, 1e-8);
  EXPECT_NEAR(out.impulses[1], -mu * c, 1e-8);
  EXPECT_NEAR(out.impulses[2], -mu * s, 1e-8);
  EXPECT_EQ(out.report.solver, "fb_newton");
}

TEST(FbNewtonSolver, MatchesAcNewtonResidualOnRandomProblems) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const ContactProblem p = fixtures::randomMechanical(5, 30, 0.4, seed);
    const SolveOutcome fb = FbNewtonSolver().solve(p);
    const SolveOutcome ac = AcNewtonSolver().solve(p);
    EXPECT_EQ(fb.report.status, SolverStatus::Converged) << fb.report.message;
    EXPECT_LE(fb.report.residual, 1e-8);
    // nu <= 1: the solution is unique, both find it
    EXPECT_LT((fb.impulses - ac.impulses).norm(), 1e-6 * (1 + ac.impulses.norm()));
  }
}

TEST(FbNewtonSolver, GoldsteinPriceOptionAndFixtures) {
  FbNewtonOptions gp;
  gp.newton.lineSearch = NewtonSettings::LineSearch::GoldsteinPrice;
  for (const char* name : {"FC3D_Example1", "Rover1039", "OneObject-i1028-138"}) {
    const ContactProblem p = fixtures::loadFixture(name);
    EXPECT_EQ(FbNewtonSolver().solve(p).report.status, SolverStatus::Converged) << name;
    EXPECT_LE(FbNewtonSolver(gp).solve(p).report.residual, 1e-6) << name;
  }
}

TEST(FbNewtonSolver, Deterministic) {
  const ContactProblem p = fixtures::randomMechanical(8, 20, 0.6, 4);
  const SolveOutcome a = FbNewtonSolver().solve(p), b = FbNewtonSolver().solve(p);
  EXPECT_EQ(a.impulses, b.impulses);
  EXPECT_EQ(a.report.iterations, b.report.iterations);
}
