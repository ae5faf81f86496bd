// BlockLu against a dense LU: non-symmetric matrices on symmetric patterns of 3 x 3 blocks (a
// chain's Newton matrix B of the joint correction, a branching mechanism with a loop, pairs in both
// orientations) and of scalar entries, the analysis reused with new values, x aliasing b, and a
// singular or non-finite pivot block reported.
#include <coulomb/solvers/direct/BlockLu.hpp>

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

namespace coulomb::solvers {
namespace {

using Pairs = std::vector<std::pair<int, int>>;

template <int N>
struct Values {
  std::vector<typename BlockLuOf<N>::Block> diagonal, coupling, mirrored;
  Eigen::MatrixXd dense;
};

// A random matrix on the pattern whose symmetric part is positive definite (the diagonal blocks
// dominate), with independent blocks A(row, col) and A(col, row).
template <int N>
Values<N> randomMatrix(int n, const Pairs& pairs, std::mt19937& rng) {
  using B = typename BlockLuOf<N>::Block;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto random = [&] {
    B b;
    for (int i = 0; i < N * N; ++i) b.data()[i] = u(rng);
    return b;
  };
  Values<N> v;
  v.dense = Eigen::MatrixXd::Zero(N * n, N * n);
  for (const auto& [row, col] : pairs) {
    v.coupling.push_back(random());
    v.mirrored.push_back(random());
    v.dense.template block<N, N>(N * row, N * col) += v.coupling.back();
    v.dense.template block<N, N>(N * col, N * row) += v.mirrored.back();
  }
  for (int i = 0; i < n; ++i) {
    B d = random();
    const double rowSum = v.dense.middleRows(N * i, N).cwiseAbs().rowwise().sum().maxCoeff();
    const double colSum = v.dense.middleCols(N * i, N).cwiseAbs().colwise().sum().maxCoeff();
    d.diagonal().array() += rowSum + colSum + N + std::abs(u(rng));
    v.diagonal.push_back(d);
    v.dense.template block<N, N>(N * i, N * i) = d;
  }
  return v;
}

template <int N>
void expectSolves(int n, const Pairs& pairs, int trials) {
  std::mt19937 rng(13);
  BlockLuOf<N> lu;
  for (int t = 0; t < trials; ++t) {
    const Values<N> v = randomMatrix<N>(n, pairs, rng);
    if (!lu.analyzed(n, pairs)) lu.analyze(n, pairs);
    ASSERT_TRUE(lu.factorize(v.diagonal, v.coupling, v.mirrored));
    const Eigen::VectorXd b = Eigen::VectorXd::Random(N * n);
    Eigen::VectorXd x;
    lu.solve(b, x);
    const Eigen::VectorXd expected = v.dense.partialPivLu().solve(b);
    EXPECT_LT((x - expected).norm(), 1e-12 * (1.0 + expected.norm())) << "trial " << t;
    EXPECT_LT((v.dense * x - b).norm(), 1e-12 * (1.0 + b.norm())) << "trial " << t;
    Eigen::VectorXd aliased = b;
    lu.solve(aliased, aliased);
    EXPECT_EQ(aliased, x);
  }
}

Pairs chain(int n) {  // joint i shares a link with joint i - 1
  Pairs p;
  for (int i = 1; i < n; ++i) p.push_back({i, i - 1});
  return p;
}

// Joints sharing bodies in a tree that branches (a ragdoll's torso with limbs), pairs in both
// orientations, and a loop closed across two branches (fill).
const Pairs kBranching = {{1, 0}, {2, 0}, {3, 0}, {0, 4}, {5, 1},
                          {6, 5}, {2, 7}, {8, 7}, {9, 3}, {9, 8}};

TEST(BlockLu, SolvesAChainsNewtonMatrixByThreeByThreeBlocks) {
  expectSolves<3>(50, chain(50), 3);
}

TEST(BlockLu, SolvesABranchingMechanismWithALoop) {
  expectSolves<3>(10, kBranching, 4);
  expectSolves<1>(10, kBranching, 4);
}

TEST(BlockLu, SolvesScalarEntries) {
  Pairs dense;  // every entry coupled: a full matrix, the worst fill
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < i; ++j) dense.push_back({j, i});
  expectSolves<1>(12, dense, 3);
  expectSolves<1>(40, chain(40), 2);
}

TEST(BlockLu, ReportsASingularOrNonFinitePivotAndRecovers) {
  std::mt19937 rng(5);
  const Values<3> v = randomMatrix<3>(10, kBranching, rng);
  BlockLuOf<3> lu;
  lu.analyze(10, kBranching);
  Values<3> singular = v;  // block row and column 4 zero: A is singular
  singular.diagonal[4].setZero();
  singular.coupling[3].setZero();
  singular.mirrored[3].setZero();
  EXPECT_FALSE(lu.factorize(singular.diagonal, singular.coupling, singular.mirrored));
  Values<3> nan = v;
  nan.mirrored[6](1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(lu.factorize(nan.diagonal, nan.coupling, nan.mirrored));
  EXPECT_TRUE(lu.factorize(v.diagonal, v.coupling, v.mirrored));  // usable after a failure
}

TEST(BlockLu, RejectsAPatternOrValuesThatDoNotMatch) {
  BlockLuOf<3> lu;
  EXPECT_THROW(lu.analyze(3, {{3, 0}}), std::invalid_argument);
  EXPECT_THROW(lu.analyze(3, {{1, 1}}), std::invalid_argument);
  lu.analyze(3, {{1, 0}});
  using Block = BlockLuOf<3>::Block;
  std::vector<Block> diagonal(3, Block::Identity()), coupling(1, Block::Zero()), mirrored;
  EXPECT_THROW(lu.factorize(diagonal, coupling, mirrored), std::invalid_argument);
}

}  // namespace
}  // namespace coulomb::solvers
