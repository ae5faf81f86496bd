// The steady warm start of a converged solve on an island with W's entries (ContactSolver::
// steadyAnswer, docs/solvers.md "Steady warm start"): an exact answer also removes the velocity
// errors the bodies arrived with, a one-off that, kept as the next warm start, makes the next step
// miss by the same errors reversed. Newton keeps the answer for q - J v_k instead, one step with
// the factors of its last iteration. Errors beyond the tolerance are motion, not leftovers: no
// steady warm start then.
#include <gtest/gtest.h>
#include <coulomb/solvers/BlockSparseMatrix.hpp>
#include <coulomb/solvers/ContactProblem.hpp>
#include <coulomb/solvers/newton/AcNewtonSolver.hpp>
#include <coulomb/solvers/newton/FbNewtonSolver.hpp>

#include "TestProblems.hpp"
#include "TowerProblems.hpp"

#include <memory>
#include <string>
#include <utility>

using namespace coulomb::solvers;
using namespace coulomb::solvers::testing;

namespace {

// J v_k given by the caller (SolverOptions::arrivalRows), as the World lends its islands'.
class GivenArrivalRows final : public ArrivalRowVelocities {
 public:
  explicit GivenArrivalRows(Eigen::VectorXd rows) : rows_(std::move(rows)) {}
  void form(Eigen::VectorXd& out) const override { out = rows_; }

 private:
  Eigen::VectorXd rows_;
};

// The tower of towerArrivingWithErrors with W's entries (block-sparse, as the World's small
// islands), `errors` times the velocity of the tolerance: its warm start misses by twice the
// errors. `arrived`: its J v_k.
ContactProblem explicitTowerArrivingWithErrors(int boxes, double errors, double tolerance,
                                               Eigen::VectorXd& arrived) {
  const ContactProblem probe = tower(boxes, 0.5);
  const double scale = tolerance * (1.0 + probe.q.norm());
  const double unit = arrivalRowVelocities(towerArrivingWithErrors(boxes, 1.0)).norm();
  ContactProblem p = towerArrivingWithErrors(boxes, errors * scale / unit);
  arrived = arrivalRowVelocities(p);
  p.arrival.resize(0);
  auto W = std::make_shared<BlockSparseMatrix>(p.W.toBlockSparse(p.blockSizes()));
  p.W = DelassusOperator::blockSparse(W);
  return p;
}

// A solve within `tolerance` to which `arrivalRows` (may be null) is lent.
SolverOptions lentOptions(double tolerance, const ArrivalRowVelocities* arrivalRows) {
  SolverOptions options;
  options.tolerance = tolerance;
  options.arrivalRows = arrivalRows;
  return options;
}

template <class Solver>
void expectNewtonKeepsTheSteadyAnswer() {
  const double tolerance = 1e-8;
  Eigen::VectorXd arrived;
  const ContactProblem p = explicitTowerArrivingWithErrors(3, 0.3, tolerance, arrived);
  const GivenArrivalRows given(arrived);
  SolverOptions options = lentOptions(tolerance, &given);
  ASSERT_EQ(p.W.bodySpaceOperator(), nullptr);
  ASSERT_GT(residualFor(p, p.q, *p.warmStart), tolerance);  // the warm start misses
  const SolveOutcome out = Solver().solve(p, options);
  ASSERT_EQ(out.report.status, SolverStatus::Converged) << out.report.message;
  EXPECT_GE(out.report.iterations, 1);
  ASSERT_TRUE(out.hasNextWarmStart);
  // The next step of the resting island, whose bodies arrive at rest (the answer stopped them).
  const Eigen::VectorXd nextQ = p.q - arrived;
  const double applied = residualFor(p, nextQ, out.impulses);
  const double kept = residualFor(p, nextQ, out.nextWarmStart);
  EXPECT_GT(applied, 0.2 * tolerance);  // the one-off correction, left in the applied answer
  EXPECT_LT(kept, 1e-3 * tolerance);    // the load alone: the next step accepts it
  expectFacesCarryTheWeightAbove(out.nextWarmStart, 3);

  Eigen::VectorXd fast;
  const ContactProblem moving = explicitTowerArrivingWithErrors(3, 3.0, tolerance, fast);
  const GivenArrivalRows givenFast(fast);
  options.arrivalRows = &givenFast;
  const SolveOutcome large = Solver().solve(moving, options);
  ASSERT_EQ(large.report.status, SolverStatus::Converged);
  EXPECT_FALSE(large.hasNextWarmStart);
}

}  // namespace

TEST(SteadyWarmStart, AlartCurnierNewtonKeepsTheLoadWithoutTheArrivalErrors) {
  expectNewtonKeepsTheSteadyAnswer<AcNewtonSolver>();
}

TEST(SteadyWarmStart, FischerBurmeisterNewtonKeepsTheLoadWithoutTheArrivalErrors) {
  expectNewtonKeepsTheSteadyAnswer<FbNewtonSolver>();
}

// Without the rows' arrival velocities (no SolverOptions::arrivalRows for W's entries, as for a
// captured problem) nothing is removed: the answer is the next warm start.
TEST(SteadyWarmStart, NoArrivalVelocitiesNoSteadyAnswer) {
  const double tolerance = 1e-8;
  Eigen::VectorXd arrived;
  const ContactProblem p = explicitTowerArrivingWithErrors(3, 0.3, tolerance, arrived);
  const SolveOutcome out = AcNewtonSolver().solve(p, lentOptions(tolerance, nullptr));
  ASSERT_EQ(out.report.status, SolverStatus::Converged);
  EXPECT_GE(out.report.iterations, 1);
  EXPECT_FALSE(out.hasNextWarmStart);
}

// A start sweep (SolverOptions::startSweep) that puts the warm start back within the tolerance is
// the answer and the next warm start: one more sweep on q - J v_k would not be exact, and a warm
// start that misses by nearly the tolerance, accepted step after step, lets a resting box creep
// (docs/solvers.md "Steady warm start").
TEST(SteadyWarmStart, AStartSweepAnswerIsKeptAsItIs) {
  const double tolerance = 1e-6;
  Eigen::VectorXd arrived;
  const ContactProblem p = explicitTowerArrivingWithErrors(1, 0.8, tolerance, arrived);
  const GivenArrivalRows given(arrived);
  SolverOptions options = lentOptions(tolerance, &given);
  options.startSweep = true;
  ASSERT_GT(residualFor(p, p.q, *p.warmStart), tolerance);
  const SolveOutcome out = AcNewtonSolver().solve(p, options);
  ASSERT_EQ(out.report.status, SolverStatus::Converged) << out.report.message;
  EXPECT_EQ(out.report.iterations, 0);
  EXPECT_NE(out.report.message.find("start sweep"), std::string::npos) << out.report.message;
  EXPECT_FALSE(out.hasNextWarmStart);
}

namespace {

// One contact pressed onto the ground (W = I, q = (-1, 0, 0): r = (1, 0, 0)), solved exactly,
// whose steady answer is the exact one for the shifted q, or that one off by `miss` on the normal.
class ExactOnTheGround final : public ContactSolver {
 public:
  explicit ExactOnTheGround(double miss) : miss_(miss) {}
  [[nodiscard]] std::string name() const override { return "exact_on_the_ground"; }
  void solvePrepared(const PreparedProblem& p, const SolveContext& /*context*/, Eigen::VectorXd& r,
                     SolverReport& report) const override {
    r = -p.q;
    Eigen::VectorXd u;
    p.velocity(r, u);
    double absolute = 0.0;
    const double e = p.residualFromVelocity(r, u, &absolute);
    p.recordEnd(r, u, e, absolute);
    report.status = SolverStatus::Converged;
    report.iterations = 1;
    report.nativeResidual = e;
  }
  [[nodiscard]] bool steadyAnswer(const PreparedProblem& /*p*/, const Eigen::VectorXd& r,
                                  const Eigen::VectorXd& uShifted,
                                  Eigen::VectorXd& out) const override {
    out = r - uShifted;  // W = I: r' = r - (W r + q')
    out[0] += miss_;
    return true;
  }

 private:
  double miss_;
};

}  // namespace

// A steady answer is kept as the next warm start only when it answers the shifted problem within
// the tolerance: one Newton step on kept factors can miss it (coplanar contact points under a
// 1000:1 mass ratio), and the kept impulses are the contact forces a user reads.
TEST(SteadyWarmStart, ASteadyAnswerThatMissesTheShiftedProblemIsNotKept) {
  const double tolerance = 1e-8;
  ContactProblem p = coulomb::solvers::fixtures::singleContact(Eigen::Matrix3d::Identity(),
                                                               Eigen::Vector3d(-1, 0, 0), 0.5);
  p.warmStart = Eigen::Vector3d(0.5, 0.0, 0.0);  // misses: the solver runs
  const GivenArrivalRows given(Eigen::Vector3d(0.3 * tolerance, 0.0, 0.0));
  const SolverOptions options = lentOptions(tolerance, &given);
  const SolveOutcome exact = ExactOnTheGround(0.0).solve(p, options);
  ASSERT_EQ(exact.report.status, SolverStatus::Converged);
  ASSERT_TRUE(exact.hasNextWarmStart);
  EXPECT_NEAR(exact.nextWarmStart[0], 1.0 + 0.3 * tolerance, 1e-15);
  const SolveOutcome missing = ExactOnTheGround(1e3 * tolerance).solve(p, options);
  ASSERT_EQ(missing.report.status, SolverStatus::Converged);
  EXPECT_EQ(missing.impulses, exact.impulses);
  EXPECT_FALSE(missing.hasNextWarmStart);
}
