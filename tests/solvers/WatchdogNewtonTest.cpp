// The watchdog of the nonsmooth Newton loop (NewtonSettings::watchdogSteps, docs/solvers.md
// "Watchdog Newton") on a column of box_pile_1000 just after landing: 10 boxes, 40 contacts of
// four per face, W of rank 60 for 120 unknowns, and an answer with contacts on the cone's edge
// that do not slip. Fixture: tests/data/problems/ORIGIN.md.
#include <gtest/gtest.h>
#include <coulomb/solvers/newton/AcNewtonSolver.hpp>
#include <coulomb/solvers/newton/NonsmoothNewton.hpp>

#include "PlainNewton.hpp"
#include "TestProblems.hpp"

#include <string>

using namespace coulomb::solvers;

namespace {

ContactProblem loadPileColumn() {
  return fixtures::loadCapturedProblem("box_pile_1000_step60_island92");
}

SolveOutcome solveWithWatchdog(const ContactProblem& p, int watchdogSteps) {
  AcNewtonOptions options;
  options.newton.watchdogSteps = watchdogSteps;
  SolverOptions o;
  o.tolerance = 1e-8;
  return AcNewtonSolver(options).solve(p, o);
}

}  // namespace

// Monotone, every full step crosses kinks of Phi and is cut to 1/16..1/64, and ac_newton ends its
// 200 iterations at 9e-6 (stall restart and proximal loop included); with the watchdog it
// converges (measured: 102 iterations, 7.6e-9).
TEST(WatchdogNewton, APileColumnAfterLandingConverges) {
  const ContactProblem p = loadPileColumn();
  const SolveOutcome monotone = solveWithWatchdog(p, 0);
  EXPECT_NE(monotone.report.status, SolverStatus::Converged) << monotone.report.message;
  EXPECT_GT(monotone.report.residual, 1e-6);
  const SolveOutcome watched = solveWithWatchdog(p, NewtonSettings{}.watchdogSteps);
  EXPECT_EQ(watched.report.status, SolverStatus::Converged) << watched.report.message;
  EXPECT_LE(watched.report.residual, 1e-8);
  EXPECT_LE(watched.report.iterations, 150);
}

// The watchdog lets through only the full steps the monotone search would cut (psi rising); one
// it would lengthen is left to the search. On a 1e6:1 mass ratio from r = 0 the shift (5.8),
// relative to the light box's W_ii, shortens every Newton step of the heavy box's rows about a
// hundredfold and Goldstein-Price takes alpha = 10 or 100: had the watchdog accepted those full
// steps as progress (psi does fall a little), Newton would crawl and end at 4e-2 after 200
// iterations, and the heavy box would crush the light one (DegenerateCases). Here it follows the
// monotone path but for a few relaxed steps near the answer (measured: 31 iterations, monotone 29).
TEST(WatchdogNewton, LeavesTheSearchItsLongStepsOnAMillionToOneMassRatio) {
  const ContactProblem p = fixtures::loadCapturedProblem("mass_ratio_1e6_step0_island0");
  const SolveOutcome monotone = solveWithWatchdog(p, 0);
  const SolveOutcome watched = solveWithWatchdog(p, NewtonSettings{}.watchdogSteps);
  EXPECT_EQ(watched.report.status, SolverStatus::Converged) << watched.report.message;
  EXPECT_EQ(monotone.report.status, SolverStatus::Converged) << monotone.report.message;
  EXPECT_LE(watched.report.iterations, monotone.report.iterations + 10);
}

// A return to the watchdog point takes the search along the direction kept with the point: no
// evaluation of the Jacobian and no factorization there, where recomputing them cost one
// factorization per iteration (measured on this column, plain Newton loop from r = 0 until its
// stall test: 30 iterations, 2 returns, 28 dense factorizations).
TEST(WatchdogNewton, AReturnToTheWatchdogPointCostsNoFactorization) {
  fixtures::PlainNewtonRun run;
  fixtures::runPlainNewton(loadPileColumn(), 1e-8, 200, run);
  const SolverReport& report = run.report;
  const std::size_t at = report.message.find(" returns to the watchdog point");
  ASSERT_NE(at, std::string::npos) << report.message;
  const int returns = std::stoi(report.message.substr(report.message.rfind(' ', at - 1) + 1));
  EXPECT_GT(returns, 0);
  const NewtonLinearStats& stats = run.work.linear.stats();
  EXPECT_EQ(stats.denseSolves + stats.sparseSolves + returns, report.iterations) << report.message;
}
