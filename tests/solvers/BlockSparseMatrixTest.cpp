#include <gtest/gtest.h>
#include <coulomb/solvers/BlockSparseMatrix.hpp>

#include <stdexcept>

using namespace coulomb::solvers;

namespace {
BlockSparseMatrix mixed() {  // blocks: contact (3), scalar (1)
  std::vector<MatrixBlockEntry> e;
  e.push_back({0, 0, {4, 1, 0, 1, 3, 0, 0, 0, 2}});
  e.push_back({0, 1, {1, 0, 2}});
  e.push_back({1, 0, {1, 0, 2}});
  e.push_back({1, 1, {5}});
  e.push_back({1, 1, {1}});  // duplicate: summed
  return BlockSparseMatrix({3, 1}, e);
}
}  // namespace

TEST(BlockSparseMatrix, LayoutAndDuplicates) {
  const BlockSparseMatrix A = mixed();
  EXPECT_EQ(A.size(), 4);
  EXPECT_EQ(A.blockCount(), 2);
  EXPECT_EQ(A.nonZeroBlocks(), 4);
  EXPECT_EQ(A.blockOffset(1), 3);
  ASSERT_GE(A.diagonalBlock(1), 0);
  EXPECT_DOUBLE_EQ(A.blockValues(A.diagonalBlock(1))[0], 6.0);
}

TEST(BlockSparseMatrix, ProductsMatchDense) {
  const BlockSparseMatrix A = mixed();
  const Eigen::MatrixXd D = A.toDense();
  EXPECT_TRUE(D.isApprox(Eigen::MatrixXd(A.toSparse())));
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(4, -1, 2);
  Eigen::VectorXd y;
  A.multiply(x, y);
  EXPECT_LT((y - D * x).norm(), 1e-14);
  Eigen::VectorXd z = Eigen::VectorXd::Ones(4);
  A.multiplyTransposeAdd(x, z);
  EXPECT_LT((z - Eigen::VectorXd::Ones(4) - D.transpose() * x).norm(), 1e-14);
  const Eigen::VectorXd s = Eigen::Vector4d(1, 2, 3, 4);
  EXPECT_LT((A.scaledSymmetric(s).toDense() - s.asDiagonal() * D * s.asDiagonal()).norm(), 1e-13);
  BlockSparseMatrix B = A;
  B.addToDiagonal(0.5);
  EXPECT_LT((B.toDense() - D - 0.5 * Eigen::MatrixXd::Identity(4, 4)).norm(), 1e-15);
}

TEST(BlockSparseMatrix, RejectsBadBlocks) {
  EXPECT_THROW(BlockSparseMatrix({3, 4}, {}), std::invalid_argument);
  EXPECT_THROW(BlockSparseMatrix({3}, {{0, 1, std::vector<double>(9, 0.0)}}),
               std::invalid_argument);
  EXPECT_THROW(BlockSparseMatrix({3}, {{0, 0, std::vector<double>(4, 0.0)}}),
               std::invalid_argument);
}

TEST(BlockSparseMatrix, FromBlockCsrEqualsTheEntryConstructor) {
  const BlockSparseMatrix A = mixed();
  const BlockSparseMatrix B = BlockSparseMatrix::fromBlockCsr(
      {3, 1}, {0, 2, 4}, {0, 1, 0, 1}, {4, 1, 0, 1, 3, 0, 0, 0, 2, 1, 0, 2, 1, 0, 2, 6});
  EXPECT_EQ(B.nonZeroBlocks(), A.nonZeroBlocks());
  EXPECT_EQ(B.diagonalBlock(0), A.diagonalBlock(0));
  EXPECT_EQ(B.diagonalBlock(1), A.diagonalBlock(1));
  EXPECT_EQ(B.values(), A.values());
  EXPECT_EQ(B.toDense(), A.toDense());
}

TEST(BlockSparseMatrix, FromBlockCsrRejectsInconsistentArrays) {
  const std::vector<double> nine(9, 1.0);
  EXPECT_THROW(BlockSparseMatrix::fromBlockCsr({3}, {0, 1}, {0}, {1.0}), std::invalid_argument);
  EXPECT_THROW(BlockSparseMatrix::fromBlockCsr({3}, {0, 2}, {0}, nine), std::invalid_argument);
  EXPECT_THROW(BlockSparseMatrix::fromBlockCsr({1, 1}, {0, 2, 2}, {1, 0}, {1.0, 1.0}),
               std::invalid_argument);  // columns not increasing
  EXPECT_THROW(BlockSparseMatrix::fromBlockCsr({3}, {0, 1}, {1}, nine), std::invalid_argument);
}

// The proximal loop's W + s I written over a copy of W: the same numbers as a fresh copy with
// addToDiagonal, for every shift in turn; a matrix of another structure is refused.
TEST(BlockSparseMatrix, ShiftedDiagonalOverACopyEqualsANewShiftedCopy) {
  const BlockSparseMatrix base = mixed();
  BlockSparseMatrix shifted = base;
  for (const double s : {1.5, 1e-3, 0.0, 7.25}) {
    shifted.assignShiftedDiagonal(base, s);
    BlockSparseMatrix fresh = base;
    fresh.addToDiagonal(s);
    EXPECT_EQ(shifted.toDense(), fresh.toDense()) << s;
  }
  const BlockSparseMatrix other({3}, {{0, 0, {1, 0, 0, 0, 1, 0, 0, 0, 1}}});
  EXPECT_THROW(shifted.assignShiftedDiagonal(other, 1.0), std::logic_error);
}

// adoptBlockCsr keeps the index of a pattern it already holds (an island refilled step after
// step): the new values are used, a changed pattern is indexed anew, and a rejected pattern is
// rejected again when it comes back (nothing of it is taken as indexed).
TEST(BlockSparseMatrix, AdoptingTheHeldPatternUsesTheNewValues) {
  const std::vector<int> sizes{3, 1}, rowStart{0, 2, 4}, columns{0, 1, 0, 1};
  std::vector<double> values{4, 1, 0, 1, 3, 0, 0, 0, 2, 1, 0, 2, 1, 0, 2, 6};
  BlockSparseMatrix A;
  A.adoptBlockCsr(sizes, rowStart, columns, values);
  const Eigen::MatrixXd first = A.toDense();
  std::vector<double> doubled{8, 2, 0, 2, 6, 0, 0, 0, 4, 2, 0, 4, 2, 0, 4, 12};
  A.adoptBlockCsr(sizes, rowStart, columns, doubled);
  EXPECT_EQ((A.toDense() - 2.0 * first).norm(), 0.0);
  const Eigen::VectorXd x = Eigen::Vector4d(1, -2, 3, 0.5);
  Eigen::VectorXd y;
  A.multiply(x, y);
  EXPECT_LT((y - 2.0 * first * x).norm(), 1e-14);

  // Another pattern: the off-diagonal blocks dropped.
  std::vector<double> diagonalOnly{4, 1, 0, 1, 3, 0, 0, 0, 2, 6};
  A.adoptBlockCsr(sizes, {0, 1, 2}, {0, 1}, diagonalOnly);
  EXPECT_EQ(A.nonZeroBlocks(), 2);
  EXPECT_EQ(A.diagonalBlock(1), 1);
  EXPECT_DOUBLE_EQ(A.toDense()(3, 0), 0.0);
  EXPECT_DOUBLE_EQ(A.toDense()(3, 3), 6.0);

  // A pattern with too few values is rejected, and again the second time.
  BlockSparseMatrix B;
  std::vector<double> few(9, 1.0);
  EXPECT_THROW(B.adoptBlockCsr(sizes, rowStart, columns, few), std::invalid_argument);
  std::vector<double> fewAgain(9, 1.0);
  EXPECT_THROW(B.adoptBlockCsr(sizes, rowStart, columns, fewAgain), std::invalid_argument);
}
