// removeRedundantDemands (docs/solver-derivations.md (10.3)): a problem whose equality rows are
// dependent up to drift has no bounded exact answer (every solver stalls at the floor
// |q_c| / (1 + ||q||)); with the demand along the dependent combinations removed it is consistent
// and solved to round-off, while independent rows and contacts keep their q to the bit.
#include <coulomb/solvers/RedundantRows.hpp>
#include <coulomb/solvers/Residual.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>

#include <gtest/gtest.h>

#include <Eigen/Dense>

namespace coulomb::solvers {
namespace {

// Equality rows J (rows x 6) on one body with unit mass matrix: W = J J', q = J v + bias.
ContactProblem equalityProblem(const Eigen::MatrixXd& J, const Eigen::VectorXd& q) {
  ContactProblem p;
  p.W = DelassusOperator::dense(J * J.transpose());
  p.q = q;
  p.blocks.assign(J.rows(), ConstraintBlock::equality());
  return p;
}

// Three rows of a planar loop: the third is the sum of the first two turned by a drift angle,
// so W has one eigenvalue ~ drift^2 against ~1, and a bias that asks for velocity along that
// combination needs impulses ~ 1 / drift^2.
Eigen::MatrixXd nearlyDependentRows(double drift) {
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3, 6);
  J(0, 0) = 1.0;
  J(1, 1) = 1.0;
  J(2, 0) = 1.0;
  J(2, 1) = 1.0;
  J(2, 2) = drift;  // out of the plane
  return J;
}

TEST(RedundantRows, ADemandAlongRowsDependentUpToDriftIsRemovedAndTheProblemSolves) {
  const Eigen::MatrixXd J = nearlyDependentRows(1e-5);
  const Eigen::VectorXd q = Eigen::Vector3d(0.1, -0.2, 0.05);  // row 3 asks for 0.15 more
  const SolverRegistry registry = SolverRegistry::builtIn();
  SolverOptions options;
  options.tolerance = 1e-10;

  const ContactProblem raw = equalityProblem(J, q);
  const SolveOutcome before = registry.create("ac_newton")->solve(raw, options);
  EXPECT_GT(before.report.residual, 1e-8);  // the floor: no bounded answer

  ContactProblem cleaned = raw;
  RedundantRowsWorkspace work;
  const RedundantDemand removed = removeRedundantDemands(cleaned, work);
  EXPECT_EQ(removed.combinations, 1);
  // The demand removed is q's part along (1, 1, -1) / sqrt(3): (0.1 - 0.2 - 0.05) / sqrt(3).
  EXPECT_NEAR(removed.removed, 0.15 / std::sqrt(3.0), 1e-9);
  const Eigen::Vector3d c = Eigen::Vector3d(1.0, 1.0, -1.0).normalized();
  EXPECT_NEAR(c.dot(cleaned.q), 0.0, 1e-12);

  const SolveOutcome after = registry.create("ac_newton")->solve(cleaned, options);
  EXPECT_EQ(after.report.status, SolverStatus::Converged);
  EXPECT_LT(after.report.residual, 1e-10);
  EXPECT_LT(after.impulses.norm(), 1.0);  // bounded: the load, not 1 / drift^2
}

TEST(RedundantRows, IndependentRowsAndContactsKeepTheirDemandToTheBit) {
  // Equality rows that are independent (the drift is the rows' own scale), and a contact.
  Eigen::MatrixXd J = nearlyDependentRows(0.5);
  ContactProblem p;
  Eigen::MatrixXd W = Eigen::MatrixXd::Identity(6, 6);
  W.topLeftCorner(3, 3) = J * J.transpose();
  p.W = DelassusOperator::dense(W);
  p.q = (Eigen::VectorXd(6) << 0.1, -0.2, 0.05, -1.0, 0.3, 0.2).finished();
  p.blocks = {ConstraintBlock::equality(), ConstraintBlock::equality(), ConstraintBlock::equality(),
              ConstraintBlock::contact(0.5)};
  const Eigen::VectorXd q = p.q;
  RedundantRowsWorkspace work;
  EXPECT_EQ(removeRedundantDemands(p, work).combinations, 0);
  EXPECT_EQ(p.q, q);

  // Now dependent: only the equality rows' q changes; the contact's rows keep theirs.
  W.topLeftCorner(3, 3) = nearlyDependentRows(0.0) * nearlyDependentRows(0.0).transpose();
  p.W = DelassusOperator::dense(W);
  EXPECT_EQ(removeRedundantDemands(p, work).combinations, 1);
  EXPECT_NE(p.q.head<3>(), q.head<3>());
  EXPECT_EQ(p.q.tail<3>(), q.tail<3>());
}

TEST(RedundantRows, FewerThanTwoEqualityRowsOrAMatrixFreeWAreLeftAlone) {
  ContactProblem one = equalityProblem(Eigen::MatrixXd::Identity(1, 6), Eigen::VectorXd::Ones(1));
  RedundantRowsWorkspace work;
  EXPECT_EQ(removeRedundantDemands(one, work).combinations, 0);
  ContactProblem free;
  free.blocks.assign(2, ConstraintBlock::equality());
  free.q = Eigen::Vector2d(1.0, 2.0);
  free.W = DelassusOperator::matrixFree(2, [](const Eigen::VectorXd& x, Eigen::VectorXd& y) {
    y = Eigen::Vector2d(x.sum(), x.sum());
  });
  EXPECT_EQ(removeRedundantDemands(free, work).combinations, 0);
  EXPECT_EQ(free.q, Eigen::Vector2d(1.0, 2.0));
}

}  // namespace
}  // namespace coulomb::solvers
