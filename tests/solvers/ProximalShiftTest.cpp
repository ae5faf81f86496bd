// Two rules that decide how ac_newton spends its budget on box_pile_1000's impacts: the proximal
// loop's shift shrinks after easy subproblems (AcNewtonOptions::proximalShrink), and plain
// Newton hands over (Stalled) when its best residual falls too slowly to reach the tolerance in
// the iterations left (docs/solvers.md "The proximal shift and the slow stall"). Fixtures:
// tests/data/problems/ORIGIN.md.
#include <gtest/gtest.h>
#include <coulomb/solvers/newton/AcNewtonSolver.hpp>
#include <coulomb/solvers/newton/NonsmoothNewton.hpp>

#include "PlainNewton.hpp"
#include "TestProblems.hpp"

#include <string>

using namespace coulomb::solvers;

namespace {

SolveOutcome solveProx(const ContactProblem& p, double shrink) {
  AcNewtonOptions options;
  options.proximalFromStart = true;
  options.proximalShrink = shrink;
  SolverOptions o;
  o.tolerance = 1e-8;
  return AcNewtonSolver(options).solve(p, o);
}

int subproblemsOf(const SolverReport& report) {
  const std::size_t at = report.message.find(" subproblems");
  if (at == std::string::npos) return -1;
  return std::stoi(report.message.substr(report.message.rfind(' ', at - 1) + 1));
}

}  // namespace

// A landed column of 10 boxes (40 contacts, W of rank 60): each subproblem FC(W + s I, q - s r_k)
// takes Newton 1-2 iterations. With the shift tied to the residual alone (s = min(s, 5 e mean
// W_ii), the rule before proximalShrink) the loop gained ~6 % per subproblem: 62 subproblems and
// 93 iterations (measured). With the shift falling after easy subproblems: 15 and 44 (measured).
TEST(ProximalShift, ShrinksAfterEasySubproblemsOnAPileColumn) {
  const ContactProblem p = fixtures::loadCapturedProblem("box_pile_1000_step60_island92");
  const SolveOutcome out = solveProx(p, AcNewtonOptions{}.proximalShrink);
  ASSERT_EQ(out.report.status, SolverStatus::Converged) << out.report.message;
  EXPECT_LE(out.report.residual, 1e-8);
  EXPECT_LE(out.report.iterations, 60) << out.report.message;
  EXPECT_LE(subproblemsOf(out.report), 25) << out.report.message;
  // A shift that never falls (proximalShrink = 1 holds it at its first value, mean W_ii) shows
  // what the fall buys: the same answer takes several times the iterations.
  const SolveOutcome fixedShift = solveProx(p, 1.0);
  EXPECT_GT(fixedShift.report.iterations, 2 * out.report.iterations) << fixedShift.report.message;
}

// Step 31 of box_pile_1000 (16 contacts of boxes meeting in the air): plain Newton cycles through
// its watchdog, each return gaining ~2 %, so the old stall test (less than 1 % in 20 iterations)
// never fired and ac_newton ended its 200 iterations at 7.2e-4 with no time left for the proximal
// loop. The rate test sees that 2 % per cycle cannot reach 1e-6 in the iterations left and hands
// over; the proximal loop converges (measured: 67 iterations in all). The first return to the
// watchdog point hands over sooner (AcNewtonOptions::handOverOnWatchdogReturn): fewer iterations.
TEST(NewtonStall, ARateTooSlowForTheBudgetHandsOverToTheProximalLoop) {
  const ContactProblem p = fixtures::loadCapturedProblem("box_pile_1000_step31_island18");
  SolverOptions o;
  o.tolerance = 1e-6;
  AcNewtonOptions byRate;
  byRate.handOverOnWatchdogReturn = false;
  const SolveOutcome out = AcNewtonSolver(byRate).solve(p, o);
  EXPECT_EQ(out.report.status, SolverStatus::Converged) << out.report.message;
  EXPECT_LE(out.report.residual, 1e-6);
  EXPECT_LT(out.report.iterations, 150) << out.report.message;
  EXPECT_NE(out.report.message.find("falls too slowly"), std::string::npos) << out.report.message;

  const SolveOutcome handedOver = AcNewtonSolver().solve(p, o);
  EXPECT_EQ(handedOver.report.status, SolverStatus::Converged) << handedOver.report.message;
  EXPECT_LE(handedOver.report.residual, 1e-6);
  EXPECT_NE(handedOver.report.message.find("watchdog return: handed over"), std::string::npos)
      << handedOver.report.message;
  EXPECT_LT(handedOver.report.iterations, out.report.iterations) << handedOver.report.message;

  // The plain Newton loop alone: Stalled (the rate), well before its 200 iterations.
  fixtures::PlainNewtonRun run;
  fixtures::runPlainNewton(p, 1e-6, 200, run);
  const SolverReport& report = run.report;
  EXPECT_EQ(report.status, SolverStatus::Stalled) << report.message;
  EXPECT_LT(report.iterations, 100) << report.message;
}
