// BlockLdlt against a dense factorization: symmetric positive definite matrices of 6 x 6 blocks
// with the patterns of contact graphs (a tower, a pyramid's layers, a ring, pairs given in both
// orientations), the analysis reused with new values, zero fill on trees, x aliasing b, and a
// singular or non-finite pivot block reported; and of 3 x 3 blocks (BlockLdltOf<3>) with the
// patterns of a ball-joint chain's and a branching mechanism's normal matrix (a band of width 2).
#include <coulomb/solvers/direct/BlockLdlt.hpp>

#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

namespace coulomb::solvers {
namespace {

using Block = BlockLdlt::Block;
using Pairs = std::vector<std::pair<int, int>>;

template <int N>
struct Values {
  std::vector<typename BlockLdltOf<N>::Block> diagonal, coupling;
  Eigen::MatrixXd dense;
};

// A random SPD matrix on the pattern: random couplings, diagonal blocks made dominant.
template <int N = 6>
Values<N> randomSpd(int n, const Pairs& pairs, std::mt19937& rng) {
  using B = typename BlockLdltOf<N>::Block;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Values<N> v;
  v.dense = Eigen::MatrixXd::Zero(N * n, N * n);
  for (const auto& [row, col] : pairs) {
    B c;
    for (int i = 0; i < N * N; ++i) c.data()[i] = u(rng);
    v.coupling.push_back(c);
    v.dense.template block<N, N>(N * row, N * col) += c;
    v.dense.template block<N, N>(N * col, N * row) += c.transpose();
  }
  for (int i = 0; i < n; ++i) {
    B s;
    for (int k = 0; k < N * N; ++k) s.data()[k] = u(rng);
    B d = 0.5 * (s + s.transpose());
    const double offRows = v.dense.middleRows(N * i, N).cwiseAbs().rowwise().sum().maxCoeff();
    d.diagonal().array() += offRows + N + std::abs(u(rng));
    v.diagonal.push_back(d);
    v.dense.template block<N, N>(N * i, N * i) = d;
  }
  return v;
}

template <int N = 6>
void expectSolves(int n, const Pairs& pairs, int trials) {
  std::mt19937 rng(11);
  BlockLdltOf<N> ldlt;
  for (int t = 0; t < trials; ++t) {
    const Values<N> v = randomSpd<N>(n, pairs, rng);
    if (!ldlt.analyzed(n, pairs)) ldlt.analyze(n, pairs);
    ASSERT_TRUE(ldlt.factorize(v.diagonal, v.coupling));
    const Eigen::VectorXd b = Eigen::VectorXd::Random(N * n);
    Eigen::VectorXd x;
    ldlt.solve(b, x);
    const Eigen::VectorXd expected = v.dense.ldlt().solve(b);
    EXPECT_LT((x - expected).norm(), 1e-12 * (1.0 + expected.norm())) << "trial " << t;
    EXPECT_LT((v.dense * x - b).norm(), 1e-12 * (1.0 + b.norm())) << "trial " << t;
  }
}

Pairs tower(int n) {  // body i rests on body i - 1
  Pairs p;
  for (int i = 1; i < n; ++i) p.push_back({i, i - 1});
  return p;
}

TEST(BlockLdlt, SolvesATowerWithoutFill) {
  const Pairs pairs = tower(12);
  expectSolves(12, pairs, 3);
  BlockLdlt ldlt;
  ldlt.analyze(12, pairs);
  EXPECT_EQ(ldlt.factorBlocks(), 11);  // a tree: L has A's pattern
}

TEST(BlockLdlt, SolvesAPyramidsLayersWithFill) {
  // Rows of a 2D pyramid: box (r, i) rests on (r - 1, i) and (r - 1, i + 1); pairs in both
  // orientations, as a contact graph lists them.
  Pairs pairs;
  std::vector<int> first{0};
  const int base = 6;
  for (int r = 0; r < base; ++r) first.push_back(first.back() + base - r);
  for (int r = 1; r < base; ++r)
    for (int i = 0; i < base - r; ++i) {
      const int box = first[r] + i;
      pairs.push_back({box, first[r - 1] + i});
      pairs.push_back({first[r - 1] + i + 1, box});
    }
  expectSolves(first.back(), pairs, 3);
}

TEST(BlockLdlt, SolvesARingAndReusesItsAnalysis) {
  Pairs pairs = tower(9);
  pairs.push_back({8, 0});  // a loop: one fill chain
  expectSolves(9, pairs, 5);
}

TEST(BlockLdlt, SolvesIsolatedBlocksAndAliasedVectors) {
  std::mt19937 rng(3);
  const Values<6> v = randomSpd(4, {}, rng);
  BlockLdlt ldlt;
  ldlt.analyze(4, {});
  ASSERT_TRUE(ldlt.factorize(v.diagonal, v.coupling));
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(24, -1.0, 2.0);
  const Eigen::VectorXd expected = v.dense.ldlt().solve(x);
  ldlt.solve(x, x);
  EXPECT_LT((x - expected).norm(), 1e-13);
}

TEST(BlockLdlt, ReportsASingularOrNonFinitePivot) {
  const Pairs pairs = tower(3);
  std::mt19937 rng(5);
  Values<6> v = randomSpd(3, pairs, rng);
  BlockLdlt ldlt;
  ldlt.analyze(3, pairs);
  Values<6> singular = v;
  singular.diagonal[1].setZero();
  singular.coupling[0].setZero();
  singular.coupling[1].setZero();
  EXPECT_FALSE(ldlt.factorize(singular.diagonal, singular.coupling));
  Values<6> nan = v;
  nan.coupling[1](2, 3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(ldlt.factorize(nan.diagonal, nan.coupling));
  EXPECT_TRUE(ldlt.factorize(v.diagonal, v.coupling));  // usable again after a failure
}

TEST(BlockLdlt, SolvesAChainsCorrectionMatrixByThreeByThreeBlocks) {
  // A normal matrix of a chain of ball joints: joint i couples with i - 1 and i - 2 (a
  // pentadiagonal band).
  Pairs pairs;
  for (int i = 1; i < 50; ++i) {
    pairs.push_back({i, i - 1});
    if (i > 1) pairs.push_back({i, i - 2});
  }
  expectSolves<3>(50, pairs, 3);
}

TEST(BlockLdlt, SolvesABranchingMechanismByThreeByThreeBlocks) {
  // Joints sharing bodies in a tree that branches (a ragdoll's torso with limbs), pairs in both
  // orientations, and a loop closed across two branches.
  Pairs pairs = {{1, 0}, {2, 0}, {3, 0}, {0, 4}, {5, 1}, {6, 5}, {2, 7}, {8, 7}, {9, 3}, {9, 8}};
  expectSolves<3>(10, pairs, 4);
  std::mt19937 rng(7);
  Values<3> singular = randomSpd<3>(10, pairs, rng);
  singular.diagonal[4].setZero();
  singular.coupling[3].setZero();
  BlockLdltOf<3> ldlt;
  ldlt.analyze(10, pairs);
  EXPECT_FALSE(ldlt.factorize(singular.diagonal, singular.coupling));
}

TEST(BlockLdlt, RejectsAPatternOutsideTheMatrix) {
  BlockLdlt ldlt;
  EXPECT_THROW(ldlt.analyze(3, {{3, 0}}), std::invalid_argument);
  EXPECT_THROW(ldlt.analyze(3, {{1, 1}}), std::invalid_argument);
  ldlt.analyze(3, {{1, 0}});
  std::vector<Block> diagonal(2, Block::Identity()), coupling(1, Block::Zero());
  EXPECT_THROW(ldlt.factorize(diagonal, coupling), std::invalid_argument);
}

}  // namespace
}  // namespace coulomb::solvers
