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

#include <Eigen/Geometry>

#include <memory>
#include <vector>

using namespace coulomb::solvers;

namespace {

constexpr double kMass = 2.0, kHalf = 0.5, kGravity = 9.81, kStep = 0.01;

// `boxes` unit boxes (mass 2 kg) stacked on the ground, four corner contacts per face, normal +z
// from the lower body (side 0; the ground is static) to the upper (side 1); q = J v* with
// v* = (0, 0, -g h) for every box. `lateral` adds a sideways velocity to the top box's v*.
ContactProblem tower(int boxes, double mu, double lateral = 0.0) {
  const int contacts = 4 * boxes;
  auto factors = std::make_shared<BodySpaceDelassus>(boxes, std::vector<int>(contacts, 3));
  const double inertia = kMass * (2 * kHalf) * (2 * kHalf) / 6.0;  // a cube about its centre
  Eigen::Matrix<double, 6, 6> inverseMass = Eigen::Matrix<double, 6, 6>::Zero();
  inverseMass.topLeftCorner<3, 3>().diagonal().setConstant(1.0 / kMass);
  inverseMass.bottomRightCorner<3, 3>().diagonal().setConstant(1.0 / inertia);
  std::vector<Eigen::Matrix<double, 6, 1>> freeVelocity(boxes, Eigen::Matrix<double, 6, 1>::Zero());
  for (auto& v : freeVelocity) v[2] = -kGravity * kStep;
  freeVelocity.back()[0] = lateral;
  const Eigen::Vector3d n(0, 0, 1), t1(1, 0, 0), t2(0, 1, 0);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(3 * contacts);
  for (int k = 0; k < boxes; ++k)
    for (int corner = 0; corner < 4; ++corner) {
      const int c = 4 * k + corner;
      const double x = (corner & 1) ? kHalf : -kHalf, y = (corner & 2) ? kHalf : -kHalf;
      for (int side = 0; side < 2; ++side) {
        const int body = side == 1 ? k : k - 1;  // the box above, or the one below (ground: -1)
        if (body < 0) continue;
        const Eigen::Vector3d arm(x, y, side == 1 ? -kHalf : kHalf);  // from the body's centre
        const double sign = side == 1 ? 1.0 : -1.0;
        Eigen::Matrix<double, 3, 6> J;
        int row = 0;
        for (const Eigen::Vector3d& d : {n, t1, t2}) {
          J.block<1, 3>(row, 0) = sign * d.transpose();
          J.block<1, 3>(row, 3) = sign * arm.cross(d).transpose();
          ++row;
        }
        factors->setSide(c, side, body, J, inverseMass * J.transpose());
        q.segment<3>(3 * c) += J * freeVelocity[static_cast<std::size_t>(body)];
      }
    }
  return ContactProblem::contacts(DelassusOperator::bodySpace(factors), q,
                                  std::vector<double>(contacts, mu), "tower");
}

// The tower with a warm start in which each corner carries only its own box's weight: the load
// of the boxes above still has to move down, which Gauss-Seidel does one layer per sweep.
ContactProblem towerWarmStartedWithOwnWeights(int boxes, double mu, double lateral = 0.0) {
  ContactProblem p = tower(boxes, mu, lateral);
  Eigen::VectorXd warm = Eigen::VectorXd::Zero(p.size());
  for (int c = 0; c < 4 * boxes; ++c) warm[3 * c] = kMass * kGravity * kStep / 4.0;
  p.warmStart = warm;
  return p;
}

SolverOptions restartOptions(double tolerance, int maxIterations) {
  SolverOptions options;
  options.tolerance = tolerance;
  options.maxIterations = maxIterations;
  options.stickingStart = true;
  return options;
}

// Each face of the resting tower carries the weight of the boxes above it (and its own box).
void expectFacesCarryTheWeightAbove(const Eigen::VectorXd& impulses, int boxes) {
  for (int k = 0; k < boxes; ++k) {
    double load = 0.0;
    for (int c = 4 * k; c < 4 * k + 4; ++c) load += impulses[3 * c];
    const double weight = (boxes - k) * kMass * kGravity * kStep;
    EXPECT_NEAR(load, weight, 1e-6 * weight) << k;
  }
}

}  // namespace

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

namespace {

// The rows' velocities J v_k of the bodies' arrival velocities (ContactProblem::arrival).
Eigen::VectorXd arrivalRowVelocities(const ContactProblem& p) {
  const BodySpaceDelassus& factors = *p.W.bodySpaceOperator();
  Eigen::VectorXd d = Eigen::VectorXd::Zero(p.size());
  factors.addRowVelocities(p.arrival, d.data());
  return d;
}

// The resting tower of `boxes` boxes whose bodies arrive with vertical velocity errors
// +-epsilon (alternating by box; ContactProblem::arrival): q = q0 + J v_k. Warm-started with the
// exact answer of the step before, which arrived with the opposite errors (q0 - J v_k): the warm
// start misses by twice the arrival, the pattern of a stack whose accepted warm starts leave
// errors within the tolerance.
ContactProblem towerArrivingWithErrors(int boxes, double epsilon) {
  ContactProblem p = tower(boxes, 0.5);
  p.arrival = Eigen::VectorXd::Zero(6 * boxes);
  for (int k = 0; k < boxes; ++k) p.arrival[6 * k + 2] = (k % 2 == 0 ? 1.0 : -1.0) * epsilon;
  const Eigen::VectorXd d = arrivalRowVelocities(p);
  StickingStart before;
  const Eigen::VectorXd previousQ = p.q - d;
  EXPECT_TRUE(before.compute(*p.W.bodySpaceOperator(), previousQ, p.blocks, nullptr));
  p.warmStart = before.start();
  p.q += d;
  return p;
}

// q without the arrival: the next step's, for bodies that the answer stopped.
Eigen::VectorXd steadyQ(const ContactProblem& p) {
  return p.q - arrivalRowVelocities(p);
}

double residualFor(const ContactProblem& p, const Eigen::VectorXd& q, const Eigen::VectorXd& r) {
  ContactProblem next = p;
  next.q = q;
  return commonResidual(next, r).relative;
}

}  // namespace

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
