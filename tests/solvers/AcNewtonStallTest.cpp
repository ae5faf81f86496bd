// ac_newton's stall restart (AcNewtonOptions::stallRestarts) on the double-loop capture where plain
// Newton creeps into a local minimum of psi = 1/2 ||Phi||^2 (docs/solvers.md, "ac_newton stall
// restart"). Fixture: tests/data/problems/ORIGIN.md.
#include <gtest/gtest.h>
#include <coulomb/solvers/newton/AcNewtonSolver.hpp>

#include "TestProblems.hpp"

#include <string>
#include <vector>

using namespace coulomb::solvers;

namespace {

ContactProblem loadDoubleLoop() {
  return fixtures::loadCapturedProblem("double_loop_step326_island0");
}

// ac_newton without the stall restart, with each rho strategy, radius and line search.
std::vector<AcNewtonOptions> variantsWithoutRestart() {
  AcNewtonOptions plain;
  plain.stallRestarts = 0;
  AcNewtonOptions split = plain;
  split.newton.rho = NewtonSettings::Rho::SplitSpectral;
  AcNewtonOptions constant = plain;
  constant.newton.rho = NewtonSettings::Rho::Constant;
  AcNewtonOptions radiusB = plain;
  radiusB.radius = AlartCurnierFunction::Radius::NormalImpulse;
  AcNewtonOptions armijo = plain;
  armijo.newton.lineSearch = NewtonSettings::LineSearch::Armijo;
  return {plain, split, constant, radiusB, armijo};
}

}  // namespace

// Before the restart: MaxIterations at 8.6e-4 (Newton stalled, the proximal loop used the rest of
// the 200 iterations).
TEST(AcNewtonStall, DoubleLoopCaptureConvergesAlone) {
  const ContactProblem p = loadDoubleLoop();
  SolverOptions o;
  o.tolerance = 1e-8;
  const SolveOutcome out = AcNewtonSolver().solve(p, o);
  EXPECT_EQ(out.report.status, SolverStatus::Converged) << out.report.message;
  EXPECT_LE(out.report.residual, 1e-8);
  EXPECT_LE(out.report.iterations, 40) << out.report.message;
  EXPECT_NE(out.report.message.find("stall restart"), std::string::npos) << out.report.message;
}

// The obstacle is psi's landscape, not the options of the merit: with a monotone search, without
// the restart and without the proximal loop, no rho strategy, radius or line search converges
// (each stalls above 1e-4).
TEST(AcNewtonStall, WithoutRestartEveryVariantStalls) {
  const ContactProblem p = loadDoubleLoop();
  for (AcNewtonOptions a : variantsWithoutRestart()) {
    a.newton.watchdogSteps = 0;
    a.proximalOnStall = false;
    const SolveOutcome out = AcNewtonSolver(a).solve(p);
    EXPECT_NE(out.report.status, SolverStatus::Converged) << out.report.message;
    EXPECT_GT(out.report.residual, 1e-4);
  }
}

// Without the restart, the proximal loop (5.9) takes every variant off the kink: its shift falls
// only as fast as Newton solves the subproblems (AcNewtonOptions::proximalShrink; measured with
// the monotone search: 7-10 subproblems, 8-30 Newton iterations). With a shift that fell to
// 5 e mean W_ii at once, three of the five ended near 1e-3 (the subproblems were as hard as the
// problem), and the stall restart was what solved this capture (DoubleLoopCaptureConvergesAlone).
TEST(AcNewtonStall, WithoutRestartTheProximalLoopConvergesOnEveryVariant) {
  const ContactProblem p = loadDoubleLoop();
  for (const bool watchdog : {false, true})
    for (AcNewtonOptions a : variantsWithoutRestart()) {
      if (!watchdog) a.newton.watchdogSteps = 0;
      const SolveOutcome out = AcNewtonSolver(a).solve(p);
      EXPECT_EQ(out.report.status, SolverStatus::Converged) << out.report.message;
      EXPECT_NE(out.report.message.find("proximal point"), std::string::npos) << out.report.message;
    }
}

// The restart only acts after a stall: on the corpus (no stall) the runs are unchanged.
TEST(AcNewtonStall, CorpusUnchanged) {
  AcNewtonOptions off;
  off.stallRestarts = 0;
  for (const char* name : fixtures::kFixtures) {
    const ContactProblem p = fixtures::loadFixture(name);
    const SolveOutcome on = AcNewtonSolver().solve(p);
    const SolveOutcome without = AcNewtonSolver(off).solve(p);
    EXPECT_EQ(on.report.iterations, without.report.iterations) << name;
    EXPECT_EQ(on.report.status, without.report.status) << name;
    EXPECT_DOUBLE_EQ(on.report.residual, without.report.residual) << name;
  }
}
