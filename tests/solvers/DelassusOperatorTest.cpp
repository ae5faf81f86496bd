#include <gtest/gtest.h>
#include <coulomb/solvers/DelassusOperator.hpp>

#include <Eigen/Dense>

using namespace coulomb::solvers;

TEST(DelassusOperator, ThreeStoragesAgree) {
  Eigen::MatrixXd W(6, 6);
  W.setRandom();
  W = W * W.transpose() + Eigen::MatrixXd::Identity(6, 6);
  W.block<3, 3>(0, 3).setZero();
  W.block<3, 3>(3, 0).setZero();
  const DelassusOperator dense = DelassusOperator::dense(W);
  const BlockSparseMatrix bs = dense.toBlockSparse({3, 3});
  EXPECT_EQ(bs.nonZeroBlocks(), 2);  // zero off-diagonal blocks dropped
  const DelassusOperator sparse = DelassusOperator::blockSparse(bs);
  const DelassusOperator free = DelassusOperator::matrixFree(
      6, [W](const Eigen::VectorXd& x, Eigen::VectorXd& y) { y = W * x; });
  EXPECT_EQ(free.storage(), DelassusOperator::Storage::MatrixFree);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(6, -2, 3), q = Eigen::VectorXd::Ones(6);
  Eigen::VectorXd u1, u2, u3;
  dense.velocity(x, q, u1);
  sparse.velocity(x, q, u2);
  free.velocity(x, q, u3);
  EXPECT_LT((u1 - u2).norm(), 1e-13);
  EXPECT_LT((u1 - u3).norm(), 1e-13);
  EXPECT_LT((free.toBlockSparse({3, 3}).toDense() - W).norm(), 1e-13);
  EXPECT_LT((sparse.toBlockSparse({3, 1, 1, 1}).toDense() - W).norm(), 1e-13);
  EXPECT_LT((sparse.column(4) - W.col(4)).norm(), 1e-13);
}

TEST(DelassusOperator, EmptyAndInvalid) {
  const DelassusOperator empty;
  EXPECT_EQ(empty.rows(), 0);
  EXPECT_THROW(DelassusOperator::matrixFree(3, nullptr), std::invalid_argument);
  EXPECT_THROW(DelassusOperator::dense(Eigen::MatrixXd::Identity(3, 3)).toBlockSparse({3, 3}),
               std::invalid_argument);
}
