// SparseLdlt against a dense factorization: symmetric positive definite matrices with the
// patterns of joint islands (a chain, a branching tree, a loop), the analysis reused with new
// values, zero fill on trees, and a zero pivot reported.
#include <coulomb/solvers/direct/SparseLdlt.hpp>

#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include <random>
#include <utility>
#include <vector>

namespace coulomb::solvers {
namespace {

struct Pattern {
  int n = 0;
  std::vector<std::pair<int, int>> offDiagonal;  // (row > col)
};

Pattern chain(int n) {
  Pattern p{n, {}};
  for (int i = 1; i < n; ++i) p.offDiagonal.push_back({i, i - 1});
  return p;
}

// A random SPD matrix on the pattern (diagonally dominant), in the entry order of `rows/cols`.
Eigen::MatrixXd randomSpd(const Pattern& p, std::mt19937& rng, std::vector<int>& rows,
                          std::vector<int>& cols, std::vector<double>& values) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(p.n, p.n);
  rows.clear();
  cols.clear();
  values.clear();
  for (const auto& [i, j] : p.offDiagonal) {
    const double v = u(rng);
    A(i, j) = A(j, i) = v;
    rows.push_back(i);
    cols.push_back(j);
    values.push_back(v);
  }
  for (int i = 0; i < p.n; ++i) {
    A(i, i) = A.row(i).cwiseAbs().sum() + 0.5 + std::abs(u(rng));
    rows.push_back(i);
    cols.push_back(i);
    values.push_back(A(i, i));
  }
  return A;
}

void expectSolves(const Pattern& pattern, int trials) {
  std::mt19937 rng(7);
  std::vector<int> rows, cols;
  std::vector<double> values;
  SparseLdlt ldlt;
  for (int t = 0; t < trials; ++t) {
    const Eigen::MatrixXd A = randomSpd(pattern, rng, rows, cols, values);
    if (!ldlt.analyzed(pattern.n, rows, cols)) ldlt.analyze(pattern.n, rows, cols);
    ASSERT_TRUE(ldlt.factorize(values));
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(pattern.n, -1.0, 2.0);
    Eigen::VectorXd x;
    ldlt.solve(b, x);
    const Eigen::VectorXd reference = A.ldlt().solve(b);
    EXPECT_LT((x - reference).norm(), 1e-12 * reference.norm()) << "trial " << t;
    EXPECT_LT((A * x - b).norm(), 1e-12 * b.norm()) << "trial " << t;
  }
}

TEST(SparseLdlt, ChainSolvesWithoutFill) {
  const Pattern p = chain(60);
  expectSolves(p, 3);
  std::vector<int> rows, cols;
  for (const auto& [i, j] : p.offDiagonal) rows.push_back(i), cols.push_back(j);
  SparseLdlt ldlt;
  ldlt.analyze(p.n, rows, cols);
  EXPECT_EQ(ldlt.factorNonZeros(), static_cast<int>(p.offDiagonal.size()));  // a tree: no fill
}

TEST(SparseLdlt, BranchingTreeAndLoopAndDenseBlocks) {
  Pattern tree{31, {}};
  for (int i = 1; i < 31; ++i) tree.offDiagonal.push_back({i, (i - 1) / 2});  // binary tree
  expectSolves(tree, 3);
  Pattern loop = chain(20);
  loop.offDiagonal.push_back({19, 0});  // closes the chain into a ring: some fill
  expectSolves(loop, 3);
  Pattern blocks{12, {}};  // 3x3 blocks of ball joints sharing bodies
  for (int b = 0; b < 4; ++b)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < i; ++j) blocks.offDiagonal.push_back({3 * b + i, 3 * b + j});
  for (int b = 1; b < 4; ++b)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) blocks.offDiagonal.push_back({3 * b + i, 3 * (b - 1) + j});
  expectSolves(blocks, 3);
}

TEST(SparseLdlt, ReanalysesOnlyForANewPattern) {
  const Pattern p = chain(5);
  std::vector<int> rows{1, 2, 3, 4, 0, 1, 2, 3, 4}, cols{0, 1, 2, 3, 0, 1, 2, 3, 4};
  SparseLdlt ldlt;
  EXPECT_FALSE(ldlt.analyzed(p.n, rows, cols));
  ldlt.analyze(p.n, rows, cols);
  EXPECT_TRUE(ldlt.analyzed(p.n, rows, cols));
  rows[0] = 2;  // another pattern
  EXPECT_FALSE(ldlt.analyzed(p.n, rows, cols));
}

TEST(SparseLdlt, DuplicateEntriesAreSummed) {
  SparseLdlt ldlt;
  ldlt.analyze(2, {0, 1, 1, 1}, {0, 0, 1, 1});
  ASSERT_TRUE(ldlt.factorize({4.0, 1.0, 1.5, 1.5}));  // A = [4 1; 1 3]
  Eigen::VectorXd x;
  ldlt.solve(Eigen::Vector2d(5.0, 4.0), x);
  EXPECT_NEAR(x[0], 1.0, 1e-15);
  EXPECT_NEAR(x[1], 1.0, 1e-15);
}

TEST(SparseLdlt, ZeroPivotIsReported) {
  SparseLdlt ldlt;
  ldlt.analyze(2, {0, 1, 1}, {0, 0, 1});
  EXPECT_FALSE(ldlt.factorize({1.0, 1.0, 1.0}));                   // [1 1; 1 1] is singular
  EXPECT_THROW(ldlt.analyze(2, {0}, {1}), std::invalid_argument);  // upper-triangle entry
}

// A = B B' of rank 3 on 6 rows (a loop's joint rows: three are combinations of the others): the
// revealing factorization marks three rows, each null vector n has A n ~ 0, and solve() with the
// floored pivots amplifies A's null space (one step of inverse iteration).
TEST(SparseLdlt, RevealingFactorizationFindsDependentRowsAndTheirNullVectors) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd B(6, 3);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 3; ++j) B(i, j) = u(rng);
  const Eigen::MatrixXd A = B * B.transpose();
  std::vector<int> rows, cols;
  std::vector<double> values;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j <= i; ++j) {
      rows.push_back(i);
      cols.push_back(j);
      values.push_back(A(i, j));
    }
  SparseLdlt ldlt;
  ldlt.analyze(6, rows, cols);
  const double floor = 1e-8 * A.diagonal().maxCoeff();
  std::vector<int> dependent;
  ASSERT_TRUE(ldlt.factorizeRevealing(values, floor, dependent));
  ASSERT_EQ(dependent.size(), 3U);
  Eigen::VectorXd n;
  for (const int k : dependent) {
    ldlt.nullVector(k, n);
    EXPECT_GE(n.norm(), 1.0);  // a unit entry at row k
    EXPECT_LT((A * n).norm(), 1e-12 * A.norm() * n.norm()) << "row " << k;
  }
  // The plain factorization of the same values reports the zero (or round-off) pivots as unusable
  // or leaves them to the caller; the revealing one never fails on them.
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(6);
  Eigen::VectorXd x;
  ldlt.solve(b, x);
  ASSERT_TRUE(x.allFinite());
  // Its direction is almost entirely in A's null space (x' A x / x' x at the floor's scale).
  EXPECT_LT(x.dot(A * x) / x.squaredNorm(), 10 * floor);
}

// Full rank: nothing is marked and the answer is the plain factorization's, to the bit.
TEST(SparseLdlt, RevealingFactorizationOfAFullRankMatrixIsThePlainOne) {
  SparseLdlt plain, revealing;
  plain.analyze(2, {0, 1, 1}, {0, 0, 1});
  revealing.analyze(2, {0, 1, 1}, {0, 0, 1});
  ASSERT_TRUE(plain.factorize({4.0, 1.0, 3.0}));
  std::vector<int> dependent;
  ASSERT_TRUE(revealing.factorizeRevealing({4.0, 1.0, 3.0}, 1e-8 * 4.0, dependent));
  EXPECT_TRUE(dependent.empty());
  Eigen::VectorXd x, y;
  plain.solve(Eigen::Vector2d(5.0, 4.0), x);
  revealing.solve(Eigen::Vector2d(5.0, 4.0), y);
  EXPECT_EQ(x, y);
}

}  // namespace
}  // namespace coulomb::solvers
