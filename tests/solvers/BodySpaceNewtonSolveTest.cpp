// The Newton step solved in body space (BodySpaceNewtonSolve, docs/solvers.md "The Newton step in
// body space"): J_s = A (W + s I) + B through the Woodbury identity on W's factors. Checked against
// the same system formed from W's entries and solved by a full-pivoting LU, and in the Newton loop
// against the contact-space LU on a tower whose contact rows (120) outnumber its velocities (60).
#include <gtest/gtest.h>
#include <coulomb/solvers/PreparedProblem.hpp>
#include <coulomb/solvers/newton/AcNewtonSolver.hpp>
#include <coulomb/solvers/newton/BodySpaceNewtonSolve.hpp>
#include <coulomb/solvers/newton/NonsmoothNewton.hpp>

#include "TowerProblems.hpp"

#include <Eigen/Dense>

#include <random>

using namespace coulomb::solvers;

namespace {

// A and B of the three kinds of Alart-Curnier blocks (docs/solver-derivations.md (5.5)): open (A =
// 0, B = I), sticking (A = rho I, B = 0) and sliding (B = I - P in the tangent plane, coupled to
// r_N; A = rho P), by block number.
std::vector<NewtonBlockJacobian> mixedBlocks(int blocks, double rho) {
  std::vector<NewtonBlockJacobian> jac(blocks);
  for (int b = 0; b < blocks; ++b) {
    NewtonBlockJacobian& j = jac[b];
    switch (b % 3) {
      case 0:
        j.B.setIdentity();
        break;
      case 1:
        j.A = rho * Eigen::Matrix3d::Identity();
        break;
      default: {
        const Eigen::Vector2d n(0.6, 0.8);  // the slip direction
        const double ratio = 0.7;           // radius / |y_T|
        const Eigen::Matrix2d P = ratio * (Eigen::Matrix2d::Identity() - n * n.transpose());
        j.A(0, 0) = rho;
        j.A.bottomRightCorner<2, 2>() = rho * P;
        j.A.block<2, 1>(1, 0) = 0.5 * rho * n;
        j.B.bottomRightCorner<2, 2>() = Eigen::Matrix2d::Identity() - P;
        j.B.block<2, 1>(1, 0) = -0.5 * n;
      }
    }
  }
  return jac;
}

Eigen::MatrixXd denseJacobian(const Eigen::MatrixXd& W, const std::vector<NewtonBlockJacobian>& jac,
                              double shift) {
  const int n = static_cast<int>(W.rows());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n), B = Eigen::MatrixXd::Zero(n, n);
  for (int b = 0; 3 * b < n; ++b) {
    A.block<3, 3>(3 * b, 3 * b) = jac[b].A;
    B.block<3, 3>(3 * b, 3 * b) = jac[b].B;
  }
  return A * (W + shift * Eigen::MatrixXd::Identity(n, n)) + B;
}

}  // namespace

// Every kind of block, shifts from 1e-2 to 1e-8 of max W_ii: the body-space answer, after the four
// steps of iterative refinement the Newton loop allows at most, solves the system formed from W's
// entries to the loop's check, 1e-8 of the right-hand side (measured 1.5e-9 at a shift of 1e-8,
// the floor of J x - b in double there), and agrees with a full-pivoting LU of that system.
// Unrefined it is within 1e-9 down to a shift of 1e-4 (measured: 2e-10 at 1e-4, 2e-6 at 1e-6,
// 2e-2 at 1e-8: the block LU pivots inside its diagonal blocks only, and cond(K) ~ 1 / shift).
TEST(BodySpaceNewtonSolve, SolvesTheSystemFormedFromWsEntries) {
  const ContactProblem problem = coulomb::solvers::testing::tower(10, 0.5, 0.3);
  const BodySpaceDelassus& factors = *problem.W.bodySpaceOperator();
  const PreparedProblem prepared = PreparedProblem::from(problem);
  const Eigen::MatrixXd W = prepared.W().toDense();
  const int n = prepared.size();
  ASSERT_EQ(n, 120);
  ASSERT_EQ(6 * factors.bodyCount(), 60);
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = normal(random);
  const std::vector<NewtonBlockJacobian> jac = mixedBlocks(factors.blockCount(), 1.0 / W(0, 0));
  BodySpaceNewtonSolve solve;
  for (const double relative : {1e-2, 1e-4, 1e-6, 1e-8}) {
    const double shift = relative * prepared.maxDiagonal;
    ASSERT_TRUE(solve.factor(factors, prepared.offset, jac, shift)) << relative;
    Eigen::VectorXd x, correction;
    solve.solve(b, x);
    const Eigen::MatrixXd J = denseJacobian(W, jac, shift);
    if (relative >= 1e-4) {
      EXPECT_LE((J * x - b).norm(), 1e-9 * b.norm()) << relative;
    }
    for (int refinement = 0; refinement < 4; ++refinement) {
      solve.solve(b - J * x, correction);
      x += correction;
    }
    EXPECT_LE((J * x - b).norm(), 1e-8 * b.norm()) << relative;
    const Eigen::VectorXd reference = J.fullPivLu().solve(b);
    EXPECT_LE((x - reference).norm(), 1e-6 * reference.norm()) << relative;
  }
}

// A sticking block has D = B + s A = s rho I: without a shift it is singular and the body-space
// path refuses (the contact-space LU takes the step).
TEST(BodySpaceNewtonSolve, RefusesAZeroShift) {
  const ContactProblem problem = coulomb::solvers::testing::tower(3, 0.5);
  const PreparedProblem prepared = PreparedProblem::from(problem);
  BodySpaceNewtonSolve solve;
  const std::vector<NewtonBlockJacobian> jac = mixedBlocks(12, 1.0);
  EXPECT_FALSE(solve.factor(*problem.W.bodySpaceOperator(), prepared.offset, jac, 0.0));
  EXPECT_TRUE(solve.factor(*problem.W.bodySpaceOperator(), prepared.offset, jac, 1e-6));
}

// The cost rule: 60 velocities against 120 sticking contact rows takes body space, and so does
// the same tower with every contact slipping; one box on the ground (6 velocities, 12 rows)
// slipping keeps the contact-space LU, whose 12 x 12 factorization is cheaper than forming K.
// Open contacts add nothing to K.
TEST(BodySpaceNewtonSolve, TakesBodySpaceWhenItHasFewerUnknownsAndEnoughBlocks) {
  const auto cost = [](int boxes, const NewtonBlockJacobian& each) {
    const ContactProblem problem = coulomb::solvers::testing::tower(boxes, 0.5);
    const BodySpaceDelassus& W = *problem.W.bodySpaceOperator();
    BodySpaceNewtonSolve solve;
    const std::vector<NewtonBlockJacobian> jac(static_cast<std::size_t>(W.blockCount()), each);
    return solve.bodySpaceCost(W, jac, solve.eliminationFlops(W));
  };
  NewtonBlockJacobian sticking, slipping, open;
  sticking.A = Eigen::Vector3d(2.0, 3.0, 3.0).asDiagonal();
  sticking.B.setZero();
  slipping.A << 2.0, 0.0, 0.0, 0.1, 0.5, 0.2, 0.1, 0.2, 0.5;
  slipping.B << 0.0, 0.0, 0.0, -0.1, 0.6, 0.1, -0.1, 0.1, 0.6;
  open.A.setZero();
  open.B.setIdentity();
  EXPECT_LT(cost(10, sticking), BodySpaceNewtonSolve::contactSpaceCost(120));
  EXPECT_LT(cost(10, slipping), BodySpaceNewtonSolve::contactSpaceCost(120));
  EXPECT_LT(cost(10, sticking), cost(10, slipping));
  EXPECT_GT(cost(1, slipping), BodySpaceNewtonSolve::contactSpaceCost(12));
  BodySpaceNewtonSolve solve;
  const ContactProblem column = coulomb::solvers::testing::tower(10, 0.5);
  const double elimination = solve.eliminationFlops(*column.W.bodySpaceOperator());
  EXPECT_NEAR(elimination, 10 * (144.0 + 432.0 + 432.0) - 432.0 - 432.0, 1e-9);  // tridiagonal
  const std::vector<NewtonBlockJacobian> allOpen(
      static_cast<std::size_t>(column.W.bodySpaceOperator()->blockCount()), open);
  EXPECT_EQ(solve.bodySpaceCost(*column.W.bodySpaceOperator(), allOpen, elimination), elimination);
}

// In the Newton loop: a 10-box tower pushed sideways at the top (its contacts stick, slide and
// open) is solved to 1e-10 with the steps in body space and with the contact-space LU alone;
// both converge. Four points per face leave the impulses undetermined (the two answers differ by
// half their norm), the velocities they give agree. The body-space path is taken.
TEST(BodySpaceNewtonSolve, NewtonConvergesAsWithTheContactSpaceLu) {
  const ContactProblem problem = coulomb::solvers::testing::tower(10, 0.3, 2.0);
  const PreparedProblem p = PreparedProblem::from(problem);
  ASSERT_NE(p.factors, nullptr);
  SolverOptions o;
  o.tolerance = 1e-10;
  const SolveContext context(o, SolveContext::Clock::now());
  Eigen::VectorXd velocities[2];
  for (const bool body : {true, false}) {
    NewtonSettings settings;
    settings.bodySpaceSolve = body;
    NewtonWorkspace work(settings);
    SolverReport report;
    Eigen::VectorXd r = Eigen::VectorXd::Zero(p.size());
    runNonsmoothNewton(p, AlartCurnierFunction{}, settings, context, 200, r, report, &work);
    EXPECT_EQ(report.status, SolverStatus::Converged) << body << " " << report.message;
    Eigen::VectorXd& u = velocities[body ? 0 : 1];
    EXPECT_LE(p.residual(r, u), 1e-10) << body;
    if (body) {
      EXPECT_GT(work.bodySpaceSolves, 0);
    } else {
      EXPECT_EQ(work.bodySpaceSolves, 0);
    }
  }
  EXPECT_LE((velocities[0] - velocities[1]).norm(), 1e-8 * p.q.norm());
}
