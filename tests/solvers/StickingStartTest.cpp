// The all-sticking start (StickingStart.hpp, docs/solvers.md "Sticking start") against the statics
// of a resting tower: each of the four corner points under box k carries a quarter of the weight
// impulse of the boxes above it and of box k, no tangential impulse, and every contact stops
// (u = W r + q = 0). A contact moving apart gets nothing; a start that the cone rejects is not
// kept; a solver started from it on a resting tower ends at its start, and one whose warm start
// the sweeps cannot finish restarts from it (a restart the residual rejects changes nothing).
#include <gtest/gtest.h>
#include <coulomb/solvers/BodySpaceDelassus.hpp>
#include <coulomb/solvers/ContactProblem.hpp>
#include <coulomb/solvers/Residual.hpp>
#include <coulomb/solvers/StickingStart.hpp>
#include <coulomb/solvers/bgs/BgsSolver.hpp>
#include <coulomb/solvers/newton/AcNewtonSolver.hpp>

#include "TowerProblems.hpp"

#include <Eigen/Geometry>

#include <memory>
#include <vector>

using namespace coulomb::solvers;
using namespace coulomb::solvers::testing;

TEST(StickingStart, ATowerAtRestCarriesEachBoxsWeightEvenlyOnItsFourCorners) {
  for (const int boxes : {1, 3, 10}) {
    const ContactProblem p = tower(boxes, 0.5);
    StickingStart sticking;
    ASSERT_TRUE(sticking.compute(*p.W.bodySpaceOperator(), p.q, p.blocks, nullptr));
    const Eigen::VectorXd& r = sticking.start();
    for (int k = 0; k < boxes; ++k)
      for (int corner = 0; corner < 4; ++corner) {
        const int c = 4 * k + corner;
        const double expected = (boxes - k) * kMass * kGravity * kStep / 4.0;
        // The regularization's bias grows with the tower's height (P's conditioning): 1e-7 of
        // the load on 10 boxes, far below the solves' tolerances (1e-6 in the World).
        EXPECT_NEAR(r[3 * c], expected, 1e-6 * expected) << boxes << " boxes, contact " << c;
        EXPECT_NEAR(r[3 * c + 1], 0.0, 1e-10);
        EXPECT_NEAR(r[3 * c + 2], 0.0, 1e-10);
      }
    Eigen::VectorXd u;
    p.W.velocity(r, p.q, u);
    EXPECT_LT(u.lpNorm<Eigen::Infinity>(), 1e-7 * p.q.lpNorm<Eigen::Infinity>()) << boxes;
  }
}

TEST(StickingStart, AContactMovingApartGetsNothing) {
  ContactProblem p = tower(2, 0.5);
  for (int c = 4; c < 8; ++c) p.q[3 * c] = 0.1;  // the top box leaves the bottom one
  StickingStart sticking;
  ASSERT_TRUE(sticking.compute(*p.W.bodySpaceOperator(), p.q, p.blocks, nullptr));
  const Eigen::VectorXd& r = sticking.start();
  for (int c = 4; c < 8; ++c) EXPECT_EQ(r.segment<3>(3 * c).norm(), 0.0);
  for (int c = 0; c < 4; ++c)  // the bottom box alone on the ground
    EXPECT_NEAR(r[3 * c], kMass * kGravity * kStep / 4.0, 1e-9);
  for (int c = 0; c < 8; ++c) p.q[3 * c] = 0.1;
  EXPECT_FALSE(sticking.compute(*p.W.bodySpaceOperator(), p.q, p.blocks, nullptr));  // no contact
}

TEST(StickingStart, ASolverStartsFromItOnAFreshTowerAndEndsThere) {
  const ContactProblem p = tower(10, 0.5);
  SolverOptions options;
  options.tolerance = 1e-8;
  options.stickingStart = true;
  const SolveOutcome with = BgsSolver().solve(p, options);
  EXPECT_EQ(with.report.status, SolverStatus::Converged);
  EXPECT_EQ(with.report.iterations, 0);
  EXPECT_NE(with.report.message.find("sticking start"), std::string::npos);
  options.stickingStart = false;
  const SolveOutcome without = BgsSolver().solve(p, options);
  EXPECT_GT(without.report.iterations, 50);  // the load travels up one layer per sweep at best
  expectFacesCarryTheWeightAbove(with.impulses, 10);
}

TEST(StickingStart, AStartOutsideTheConesIsOnlyACandidate) {
  // The top box slides: sticking it needs a tangential impulse beyond mu N. The solver projects
  // that start; it still converges, to a sliding answer with |r_T| = mu r_N on the top contacts.
  const ContactProblem p = tower(2, 0.2, 1.0);
  SolverOptions options;
  options.tolerance = 1e-10;
  options.stickingStart = true;
  const SolveOutcome out = BgsSolver().solve(p, options);
  ASSERT_EQ(out.report.status, SolverStatus::Converged);
  for (int c = 4; c < 8; ++c) {
    const Eigen::Vector3d rc = out.impulses.segment<3>(3 * c);
    EXPECT_NEAR(rc.tail<2>().norm(), 0.2 * rc[0], 1e-8) << c;
  }
}

// A warm start that Gauss-Seidel cannot finish in kStickingRestartSweeps sweeps (each corner
// carries only its own box's weight, so the load still has to move down the tower): the solver
// restarts from the sticking start and ends there. Without the option, or without a budget beyond
// those sweeps, it does not.
TEST(StickingStart, AWarmStartedSolveThatSweepsCannotFinishRestartsFromIt) {
  const ContactProblem p = towerWarmStartedWithOwnWeights(10, 0.5);
  SolverOptions options = restartOptions(1e-8, 200);
  const SolveOutcome with = BgsSolver().solve(p, options);
  EXPECT_EQ(with.report.status, SolverStatus::Converged);
  // The note of a restart is that of the start; the sweeps before it say it was a restart.
  EXPECT_EQ(with.report.iterations, ContactSolver::kStickingRestartSweeps);
  EXPECT_NE(with.report.message.find("sticking start"), std::string::npos) << with.report.message;
  expectFacesCarryTheWeightAbove(with.impulses, 10);
  options.stickingStart = false;
  const SolveOutcome without = BgsSolver().solve(p, options);
  EXPECT_GT(without.report.iterations, 50);
  EXPECT_EQ(without.report.message.find("sticking"), std::string::npos);
  options.stickingStart = true;
  options.maxIterations = ContactSolver::kStickingRestartSweeps;  // no budget beyond the sweeps
  const SolveOutcome capped = BgsSolver().solve(p, options);
  EXPECT_EQ(capped.report.status, SolverStatus::MaxIterations);
  EXPECT_EQ(capped.report.message.find("sticking"), std::string::npos);
}

// A restart that the residual rejects (the top box slides, so the projected sticking start is
// worse than the sweeps' iterate) leaves the solve as it would have been without the option: the
// same answer bit for bit, after the same sweeps plus the two repeated ones.
TEST(StickingStart, ARejectedRestartLeavesTheSolveAsWithoutIt) {
  const ContactProblem p = towerWarmStartedWithOwnWeights(3, 0.2, 1.0);
  SolverOptions options = restartOptions(1e-10, 500);
  options.stickingStart = false;
  const SolveOutcome without = BgsSolver().solve(p, options);
  options.stickingStart = true;
  const SolveOutcome with = BgsSolver().solve(p, options);
  ASSERT_EQ(without.report.status, SolverStatus::Converged);
  ASSERT_GT(without.report.iterations, ContactSolver::kStickingRestartSweeps);
  EXPECT_EQ(with.report.message.find("sticking start"), std::string::npos) << "kept";
  EXPECT_EQ(with.report.status, SolverStatus::Converged);
  EXPECT_EQ(with.report.iterations,
            without.report.iterations + ContactSolver::kStickingRestartSweeps);
  EXPECT_EQ(with.impulses, without.impulses);
}

// A Newton solver (one that does not sweep in body space) whose warm start is above the tolerance
// takes the sticking start before its first iteration: one iteration costs W and a factorization
// of all 120 unknowns, the start two of 6 x 10. On a resting tower it ends there, exact.
TEST(StickingStart, AWarmStartedNewtonSolveTakesItBeforeItsFirstIteration) {
  const ContactProblem p = towerWarmStartedWithOwnWeights(10, 0.5);
  SolverOptions options = restartOptions(1e-8, 200);
  const SolveOutcome with = AcNewtonSolver().solve(p, options);
  EXPECT_EQ(with.report.status, SolverStatus::Converged);
  EXPECT_EQ(with.report.iterations, 0);
  EXPECT_NE(with.report.message.find("sticking start"), std::string::npos) << with.report.message;
  expectFacesCarryTheWeightAbove(with.impulses, 10);
  options.stickingStart = false;
  const SolveOutcome without = AcNewtonSolver().solve(p, options);
  EXPECT_GT(without.report.iterations, 0);
  EXPECT_EQ(without.report.message.find("sticking"), std::string::npos);
}

// The start for a second q (compute's stepQ; in a solve, q - J v_k) comes from the same
// factorizations: it is the start of a problem whose q is stepQ (the same rows stopped).
TEST(StickingStart, TheStartForStepQIsTheStartOfThatQ) {
  const ContactProblem p = tower(3, 0.5);
  Eigen::VectorXd stepQ = p.q;
  for (int c = 0; c < 12; ++c) stepQ[3 * c] *= 1.0 + 0.01 * c;  // still approaching everywhere
  StickingStart both, alone;
  ASSERT_TRUE(both.compute(*p.W.bodySpaceOperator(), p.q, p.blocks, nullptr, &stepQ));
  ASSERT_TRUE(both.hasStepStart());
  ASSERT_TRUE(alone.compute(*p.W.bodySpaceOperator(), stepQ, p.blocks, nullptr));
  EXPECT_LT((both.stepStart() - alone.start()).norm(), 1e-14 * alone.start().norm());
  ASSERT_TRUE(both.compute(*p.W.bodySpaceOperator(), p.q, p.blocks, nullptr));
  EXPECT_FALSE(both.hasStepStart());
}

// The exact answer of a step that also removes the velocity errors the bodies arrived with
// carries that one-off correction; as the next warm start it would leave the errors reversed, and
// the step after would miss again (the two-step cycle of docs/benchmarks.md). The solve keeps
// the start for q - J v_k instead: the load alone, which the next step (arriving without errors)
// meets exactly. Errors beyond the tolerance are motion, not leftovers: no such warm start.
TEST(StickingStart, AnExactAnswerKeepsTheLoadWithoutTheArrivalErrorsForTheNextStep) {
  const double tolerance = 1e-6;
  SolverOptions options = restartOptions(tolerance, 200);
  const ContactProblem probe = tower(10, 0.5);
  const double scale = tolerance * (1.0 + probe.q.norm());
  // epsilon such that ||d|| is 0.3 of the tolerance's velocity: the warm start misses by 2d.
  double unit = 0.0;
  {
    const ContactProblem p = towerArrivingWithErrors(10, 1.0);
    unit = (p.q - steadyQ(p)).norm();
  }
  const ContactProblem p = towerArrivingWithErrors(10, 0.3 * scale / unit);
  ASSERT_GT(residualFor(p, p.q, *p.warmStart), tolerance);  // the warm start misses
  const SolveOutcome out = AcNewtonSolver().solve(p, options);
  ASSERT_EQ(out.report.status, SolverStatus::Converged);
  EXPECT_EQ(out.report.iterations, 0);
  EXPECT_NE(out.report.message.find("sticking start"), std::string::npos) << out.report.message;
  ASSERT_TRUE(out.hasNextWarmStart);
  // Next step, the bodies arrive at rest (the answer stopped them): q = q0.
  const double applied = residualFor(p, steadyQ(p), out.impulses);
  const double kept = residualFor(p, steadyQ(p), out.nextWarmStart);
  EXPECT_GT(applied, 0.2 * tolerance);  // the one-off correction, left in the applied answer
  EXPECT_LT(kept, 1e-3 * tolerance);    // the load alone
  expectFacesCarryTheWeightAbove(out.nextWarmStart, 10);

  const ContactProblem moving = towerArrivingWithErrors(10, 3.0 * scale / unit);
  const SolveOutcome large = AcNewtonSolver().solve(moving, options);
  ASSERT_EQ(large.report.status, SolverStatus::Converged);
  EXPECT_FALSE(large.hasNextWarmStart);
}
