// One exact-local Gauss-Seidel sweep (solvers/StartSweep) and ContactSolver's use of it
// (SolverOptions::startSweep): one contact is solved exactly in every case of its law (stick,
// slip, take-off), coupled contacts from a drifted start come closer, body space is left alone,
// and a warm-started Newton solve whose start a sweep puts within the tolerance needs no
// iteration.
#include <gtest/gtest.h>
#include <coulomb/solvers/ContactSolver.hpp>
#include <coulomb/solvers/PreparedProblem.hpp>
#include <coulomb/solvers/Residual.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>
#include <coulomb/solvers/StartSweep.hpp>

#include "TestProblems.hpp"

#include <array>
#include <cmath>
#include <random>

using namespace coulomb::solvers;

namespace {

Eigen::Matrix3d spd() {
  Eigen::Matrix3d W;
  W << 2.0, 0.3, -0.2, 0.3, 1.5, 0.1, -0.2, 0.1, 1.2;
  return W;
}

SolveOutcome exactAnswer(const ContactProblem& problem) {
  SolverOptions exact;
  exact.tolerance = 1e-13;
  return SolverRegistry::builtIn().create("ac_newton")->solve(problem, exact);
}

// A box (1 x 1 x 1 m, 2 kg) resting on the ground on its four bottom corners (12 unknowns, 6
// dofs: redundant), pushed down by gravity over one step of 0.01 s and sideways by `push` (m/s).
ContactProblem boxOnGround(double mu, double push) {
  const double mass = 2.0, inertia = mass / 6.0;
  Eigen::MatrixXd J(12, 6);
  int row = 0;
  for (const double x : {-0.5, 0.5})
    for (const double y : {-0.5, 0.5}) {
      const Eigen::Vector3d arm(x, y, -0.5);
      for (const Eigen::Vector3d& d :
           {Eigen::Vector3d::UnitZ().eval(), Eigen::Vector3d::UnitX().eval(),
            Eigen::Vector3d::UnitY().eval()}) {
        J.block<1, 3>(row, 0) = d.transpose();
        J.block<1, 3>(row, 3) = arm.cross(d).transpose();
        ++row;
      }
    }
  Eigen::Matrix<double, 6, 1> inverseMass;
  inverseMass << 1 / mass, 1 / mass, 1 / mass, 1 / inertia, 1 / inertia, 1 / inertia;
  Eigen::MatrixXd W = J * inverseMass.asDiagonal() * J.transpose();
  W = 0.5 * (W + W.transpose());
  Eigen::Matrix<double, 6, 1> velocity;
  velocity << push, 0.0, -9.81 * 0.01, 0.0, 0.0, 0.0;
  const Eigen::VectorXd q = J * velocity;
  DelassusOperator op = DelassusOperator::dense(W);
  op = DelassusOperator::blockSparse(op.toBlockSparse(std::vector<int>(4, 3)));
  return ContactProblem::contacts(op, q, {mu, mu, mu, mu}, "box on the ground");
}

double residualAfterSweep(const ContactProblem& problem, Eigen::VectorXd& r) {
  const PreparedProblem prepared = PreparedProblem::from(problem);
  EXPECT_TRUE(sweepContacts(prepared, r));
  return commonResidual(problem, r).relative;
}

}  // namespace

TEST(StartSweep, OneContactIsSolvedExactlyInEveryCaseOfItsLaw) {
  const Eigen::Vector3d rStick(1.0, -0.2, 0.1);
  struct Case {
    const char* name;
    Eigen::Vector3d q;
    double mu;
  };
  const Case cases[] = {{"stick", -spd() * rStick, 0.5},           // r = rStick, inside the cone
                        {"slip", Eigen::Vector3d(-2, 3, 4), 0.5},  // r on the cone's boundary
                        {"take-off", Eigen::Vector3d(1, 0.5, -0.2), 0.5},
                        {"frictionless", Eigen::Vector3d(-2, 1, 1), 0.0}};
  for (const Case& c : cases) {
    const ContactProblem p = fixtures::singleContact(spd(), c.q, c.mu);
    Eigen::VectorXd r = Eigen::Vector3d(0.3, 0.1, -0.1);  // any start
    EXPECT_LT(residualAfterSweep(p, r), 1e-13) << c.name;
  }
}

TEST(StartSweep, SlidingContactsAreSolvedExactlyFromAnyStart) {
  // General blocks (coupled normal and tangents, anisotropic W_TT, condition up to ~1e3) pushed
  // to slide: from no impulse, from a random one and from one near the answer (the warm start of
  // a sliding contact), the sweep's answer is exact, whichever of its slip paths finds it.
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> logScale(-1.5, 1.5);
  int sliding = 0;
  for (int trial = 0; trial < 300; ++trial) {
    Eigen::Matrix3d A;
    for (int i = 0; i < 9; ++i) A(i / 3, i % 3) = normal(rng);
    const Eigen::Vector3d scales(std::pow(10.0, logScale(rng)), std::pow(10.0, logScale(rng)),
                                 std::pow(10.0, logScale(rng)));
    const Eigen::Matrix3d W =
        A * scales.asDiagonal() * A.transpose() + 1e-3 * Eigen::Matrix3d::Identity();
    const double mu = std::array{0.1, 0.3, 0.6, 1.0, 2.0}[trial % 5];
    const Eigen::Vector3d q(-std::abs(normal(rng)) - 0.1, 3.0 * normal(rng), 3.0 * normal(rng));
    const ContactProblem p = fixtures::singleContact(W, q, mu);
    const SolveOutcome exact = exactAnswer(p);
    if (exact.report.residual > 1e-12) continue;  // a block the reference does not solve
    const Eigen::Vector3d rExact = exact.impulses;
    const Eigen::Vector3d uExact = W * rExact + q;
    if (std::hypot(uExact[1], uExact[2]) < 1e-6 * q.norm()) continue;  // sticks
    ++sliding;
    const Eigen::Vector3d nearAnswer =
        rExact + 0.05 * rExact.norm() * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    for (const Eigen::Vector3d& start :
         {Eigen::Vector3d::Zero().eval(), Eigen::Vector3d(normal(rng), normal(rng), normal(rng)),
          nearAnswer}) {
      Eigen::VectorXd r = start;
      EXPECT_LT(residualAfterSweep(p, r), 1e-12)
          << "trial " << trial << " from " << start.transpose();
    }
  }
  EXPECT_GT(sliding, 100);
}

TEST(StartSweep, ADriftedStartOfARestingOrSlidingBoxComesCloser) {
  // Sticking (push 0.01 m/s against mu = 0.5) and sliding (push 1 m/s against mu = 0.1), the
  // exact answer perturbed by 1e-4 N s: one sweep of exact local answers cuts the residual 5x.
  for (const auto& [mu, push] : {std::pair{0.5, 0.01}, std::pair{0.1, 1.0}}) {
    const ContactProblem p = boxOnGround(mu, push);
    const SolveOutcome exact = exactAnswer(p);
    ASSERT_LT(exact.report.residual, 1e-12) << mu;
    Eigen::VectorXd r = exact.impulses;
    for (int i = 0; i < r.size(); ++i) r[i] += 1e-4 * ((i * 7919) % 13 - 6) / 6.0;
    const double before = commonResidual(p, r).relative;
    const double after = residualAfterSweep(p, r);
    EXPECT_LT(after, 0.2 * before) << mu << ": " << before << " -> " << after;
  }
}

TEST(StartSweep, BodySpaceProblemsAreLeftAlone) {
  const ContactProblem p = fixtures::bodyGrid(3, 2, 0.5, 7);
  ASSERT_NE(p.W.bodySpaceOperator(), nullptr);
  const PreparedProblem prepared = PreparedProblem::from(p, /*keepBodySpace=*/true);
  Eigen::VectorXd r = Eigen::VectorXd::Constant(p.size(), 0.1);
  const Eigen::VectorXd before = r;
  EXPECT_FALSE(sweepContacts(prepared, r));
  EXPECT_EQ(r, before);
}

TEST(StartSweep, ANewtonSolveWhoseStartASweepFinishesTakesNoIteration) {
  // The resting box, warm-started at the answer of a slightly different load (the normal
  // velocities of two corners changed by 1e-7 m/s: a micro-gap's speculative allowance, gap / h):
  // the sweep brings it within the tolerance and Newton does not iterate; without it, it does.
  ContactProblem p = boxOnGround(0.5, 0.01);
  p.warmStart = exactAnswer(p).impulses;
  p.q[0] += 1e-7;
  p.q[3] += 1e-7;
  SolverOptions options;
  options.tolerance = 1e-8;
  const auto solver = SolverRegistry::builtIn().create("ac_newton");
  const SolveOutcome without = solver->solve(p, options);
  options.startSweep = true;
  const SolveOutcome with = solver->solve(p, options);
  EXPECT_GT(without.report.iterations, 0);
  EXPECT_EQ(with.report.status, SolverStatus::Converged);
  EXPECT_EQ(with.report.iterations, 0);
  EXPECT_LE(with.report.residual, options.tolerance);
  EXPECT_NE(with.report.message.find("start sweep"), std::string::npos) << with.report.message;
}
