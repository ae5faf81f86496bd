#include <gtest/gtest.h>
#include <coulomb/solvers/newton/AcNewtonSolver.hpp>

#include "TestProblems.hpp"

using namespace coulomb::solvers;

TEST(AcNewtonSolver, CorpusFixturesFewIterations) {
  const SolveOutcome out = AcNewtonSolver().solve(fixtures::loadFixture("OneObject-i1028-138"));
  EXPECT_EQ(out.report.status, SolverStatus::Converged);
  EXPECT_LE(out.report.iterations, 30);
  EXPECT_GT(out.report.maxRegularization, 0.0);  // says it regularized
}

TEST(AcNewtonSolver, OptionsVariantsConverge) {
  const ContactProblem p = fixtures::randomMechanical(6, 30, 0.5, 21);
  AcNewtonOptions split;
  split.newton.rho = NewtonSettings::Rho::SplitSpectral;
  AcNewtonOptions hybrid;
  hybrid.hybridSweeps = 5;
  AcNewtonOptions radiusB;
  radiusB.radius = AlartCurnierFunction::Radius::NormalImpulse;
  for (const AcNewtonOptions& o : {split, hybrid, radiusB}) {
    const SolveOutcome out = AcNewtonSolver(o).solve(p);
    EXPECT_EQ(out.report.status, SolverStatus::Converged) << out.report.message;
    EXPECT_LE(out.report.residual, 1e-8);
  }
}

TEST(AcNewtonSolver, HistoryAndProximalFallback) {
  const ContactProblem p = fixtures::randomMechanical(10, 12, 0.8, 8);  // nu = 2.5
  SolverOptions o;
  o.recordHistory = true;
  o.tolerance = 1e-10;
  AcNewtonOptions a;
  a.newton.stallIterations = 3;  // stall early to exercise (5.9)
  a.newton.stallDecrease = 0.5;
  a.proximalInnerIterations = 100;
  a.stallRestarts = 0;  // the bgs restart would converge before (5.9) is reached
  const SolveOutcome out = AcNewtonSolver(a).solve(p, o);
  EXPECT_FALSE(out.report.history.empty());
  EXPECT_NE(out.report.message.find("proximal"), std::string::npos) << out.report.message;
  EXPECT_EQ(out.report.status, SolverStatus::Converged) << out.report.message;
}
