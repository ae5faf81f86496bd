#include <gtest/gtest.h>
#include <coulomb/solvers/BodySpaceDelassus.hpp>
#include <coulomb/solvers/PreparedProblem.hpp>
#include <coulomb/solvers/Residual.hpp>

#include <cstdlib>
#include <memory>
#include <thread>
#include <vector>

using namespace coulomb::solvers;

TEST(PreparedProblem, AnisotropicContactsBecomeIsotropic) {
  ContactProblem p;
  p.blocks = {ConstraintBlock::anisotropicContact(0.2, 0.8), ConstraintBlock::unilateral()};
  Eigen::MatrixXd W = Eigen::MatrixXd::Identity(4, 4) * 2.0;
  W(0, 3) = W(3, 0) = 0.5;
  p.W = DelassusOperator::dense(W);
  p.q = Eigen::Vector4d(-1, 2, 3, -1);
  const PreparedProblem pp = PreparedProblem::from(p);
  EXPECT_FALSE(pp.blocks[0].anisotropic);
  EXPECT_DOUBLE_EQ(pp.blocks[0].mu, 1.0);
  EXPECT_DOUBLE_EQ(pp.W().toDense()(1, 1), 2.0 * 0.2 * 0.2);
  EXPECT_DOUBLE_EQ(pp.q[2], 3.0 * 0.8);
  const Eigen::VectorXd r = Eigen::Vector4d(1, 0.1, -0.3, 2);
  EXPECT_LT((pp.toOriginal(pp.fromOriginal(r)) - r).norm(), 1e-15);
  // Same feasibility: projected prepared iterates are feasible for the elliptic cone.
  Eigen::VectorXd x = Eigen::Vector4d(1, 5, 5, -1);
  pp.project(x);
  const Eigen::VectorXd xo = pp.toOriginal(x);
  EXPECT_LE(std::hypot(xo[1] / 0.2, xo[2] / 0.8), xo[0] + 1e-14);
  EXPECT_DOUBLE_EQ(x[3], 0.0);
  EXPECT_DOUBLE_EQ(pp.maxDiagonal, 2.0);
}

TEST(PreparedProblem, ResidualEqualsCommonResidualWhenIsotropic) {
  const ContactProblem p = ContactProblem::contacts(
      DelassusOperator::dense(Eigen::MatrixXd::Identity(3, 3)), Eigen::Vector3d(-1, 3, 4), {0.5});
  const PreparedProblem pp = PreparedProblem::from(p);
  Eigen::VectorXd u;
  const Eigen::VectorXd r = Eigen::Vector3d(0.5, 0.1, 0.2);
  EXPECT_DOUBLE_EQ(pp.residual(r, u), commonResidual(p, r).relative);
}

TEST(SolveContext, TimeLimitAndHistory) {
  SolverOptions o;
  o.timeLimitSeconds = 1e-3;
  o.recordHistory = true;
  const SolveContext c(o, SolveContext::Clock::now());
  SolverReport r;
  std::this_thread::sleep_for(std::chrono::milliseconds(3));
  EXPECT_TRUE(c.timeUp(r));
  EXPECT_TRUE(r.timeLimitReached);
  c.record(r, 1, 0.5);
  ASSERT_EQ(r.history.size(), 1u);
  EXPECT_EQ(c.maxIterations(7), 7);
}

// ContactSolver keeps a body-space W factored until a solver needs W itself: forming it then
// gives what forming it up front does, entry for entry, with the same largest diagonal.
TEST(PreparedProblem, WFormedOnDemandEqualsWFormedUpFront) {
  auto factors = std::make_shared<BodySpaceDelassus>(2, std::vector<int>{3, 3, 1});
  std::srand(7);
  const Eigen::Matrix<double, 6, 6> inverseMass =
      Eigen::Matrix<double, 6, 1>(0.5, 0.5, 0.5, 2.0, 3.0, 4.0).asDiagonal();
  for (int block = 0; block < 3; ++block) {
    const int rows = block < 2 ? 3 : 1;
    for (int side = 0; side < 2; ++side) {
      const Eigen::MatrixXd J = Eigen::MatrixXd::Random(rows, 6);
      factors->setSide(block, side, side, J, inverseMass * J.transpose());
    }
  }
  ContactProblem p;
  p.blocks = {ConstraintBlock::contact(0.5), ConstraintBlock::contact(0.3),
              ConstraintBlock::unilateral()};
  p.W = DelassusOperator::bodySpace(factors);
  p.q = Eigen::VectorXd::LinSpaced(7, -1.0, 0.5);
  PreparedProblem upFront, onDemand;
  upFront.assign(p, /*keepBodySpace=*/false);
  onDemand.assign(p, /*keepBodySpace=*/true);
  ASSERT_NE(onDemand.bodySpace, nullptr);
  EXPECT_EQ(onDemand.maxDiagonal, upFront.maxDiagonal);
  onDemand.formExplicitW(p);
  EXPECT_EQ(onDemand.bodySpace, nullptr);
  EXPECT_EQ(onDemand.W().toDense(), upFront.W().toDense());
  EXPECT_EQ(onDemand.maxDiagonal, upFront.maxDiagonal);
  EXPECT_GT(upFront.maxDiagonal, 0.0);
}

// An isotropic problem with a block-sparse W is read in place (no copy of W per solve); writing
// into W (a proximal subproblem's shift) copies it first and leaves the problem's W as it was.
TEST(PreparedProblem, BlockSparseWIsSharedUntilWrittenInto) {
  Eigen::MatrixXd dense = Eigen::MatrixXd::Identity(6, 6) * 2.0;
  dense(0, 3) = dense(3, 0) = 0.5;
  auto sparse = std::make_shared<BlockSparseMatrix>();
  sparse->assignFromDense(dense, {3, 3});
  ContactProblem p;
  p.blocks = {ConstraintBlock::contact(0.5), ConstraintBlock::contact(0.5)};
  p.W = DelassusOperator::blockSparse(sparse);
  p.q = Eigen::VectorXd::LinSpaced(6, -1.0, 1.0);
  PreparedProblem prepared;
  prepared.assign(p);
  EXPECT_EQ(&prepared.W(), sparse.get());
  PreparedProblem shifted = prepared;  // as ac_newton's proximal loop copies it
  shifted.writableW().assignShiftedDiagonal(prepared.W(), 0.25);
  EXPECT_NE(&shifted.W(), sparse.get());
  EXPECT_EQ(shifted.W().toDense(), dense + 0.25 * Eigen::MatrixXd::Identity(6, 6));
  EXPECT_EQ(sparse->toDense(), dense);  // the problem's W is untouched
  // Another partition than the problem's blocks (or anisotropic contacts) gets its own copy.
  ContactProblem anisotropic = p;
  anisotropic.blocks[0] = ConstraintBlock::anisotropicContact(0.2, 0.8);
  prepared.assign(anisotropic);
  EXPECT_NE(&prepared.W(), sparse.get());
}
