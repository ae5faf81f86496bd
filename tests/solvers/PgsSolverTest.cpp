#include <gtest/gtest.h>
#include <coulomb/solvers/pgs/PgsSolver.hpp>

#include "TestProblems.hpp"

using namespace coulomb::solvers;

TEST(PgsSolver, ScalarTangentialStepGivesTheRightSlipDirection) {
  // docs/solver-derivations.md (3.2): W_cc = diag(1, 1, 4), q = (-1, -3, -3), mu = 0.5. A matrix
  // step converges to friction at 14 degrees while -u_T points at 45; the scalar step is exact.
  const ContactProblem p = fixtures::singleContact(Eigen::Vector3d(1, 1, 4).asDiagonal(),
                                                   Eigen::Vector3d(-1, -3, -3), 0.5);
  SolverOptions o;
  o.tolerance = 1e-13;
  for (auto update : {PgsOptions::Update::ConeProjection, PgsOptions::Update::NormalThenTangent}) {
    PgsOptions po;
    po.update = update;
    const SolveOutcome out = PgsSolver(po).solve(p, o);
    EXPECT_EQ(out.report.status, SolverStatus::Converged);
    EXPECT_LT(out.report.residual, 1e-13);
    const Eigen::Vector3d u = out.velocities;
    EXPECT_NEAR(std::atan2(out.impulses[2], out.impulses[1]), std::atan2(-u[2], -u[1]), 1e-10);
  }
}

TEST(PgsSolver, RelaxationAndSpectralSteps) {
  Eigen::Matrix3d W;
  W << 2, 1, 0, 1, 3, 0, 0, 0, 1;
  EXPECT_NEAR(inverseSpectralRadius(W), 1.0 / (2.5 + std::sqrt(1.25)), 1e-14);
  EXPECT_NEAR(inverseTangentSpectralRadius(W), 1.0 / 3.0, 1e-15);
  const ContactProblem p = fixtures::randomMechanical(5, 30, 0.3, 2);
  PgsOptions under;
  under.omega = 0.8;
  const SolveOutcome out = PgsSolver(under).solve(p);
  EXPECT_EQ(out.report.status, SolverStatus::Converged);
  EXPECT_LE(out.report.residual, 1e-8);
}
