#pragma once
// Sparse LDL^T of a symmetric positive definite matrix made of N x N blocks: 6 x 6 with one block
// row per rigid body (the body-space normal matrices J^T J and M^-1 J^T J M^-1 of the sticking
// start, StickingStart.hpp), 3 x 3 with one block row per ball joint (the normal matrix of the
// joint correction, integrators/PredictedStateCorrection). L is unit lower triangular by blocks
// and D block diagonal. Instantiated for N = 3 and 6 only (BlockLdlt.cpp).
// The algorithm is the up-looking LDL^T of Davis (2005), "Algorithm 849: A concise sparse
// Cholesky factorization package", ACM TOMS 31(4), carried out on the graph of the bodies instead
// of the scalar entries: the ordering (AMD), the elimination tree and the storage of L are built
// once per pattern by analyze(), and every numeric operation is a fixed-size N x N product that
// the compiler vectorizes. On the 211 boxes of pyramid_20 this is several times faster than the
// scalar SparseLdlt on the same matrix (docs/benchmarks.md "Sticking start"), which spends its time
// walking the same block pattern one entry at a time.
#include <coulomb/solvers/direct/SymbolicLdlt.hpp>

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace coulomb::solvers {

template <int N>
class BlockLdltOf {
 public:
  using Block = Eigen::Matrix<double, N, N>;

  /// The pattern: `blocks` block rows and the coupled pairs, each (row, col) with row != col and
  /// both in [0, blocks); a pair's block is A(row, col), its transpose A(col, row) implied. The
  /// diagonal is always present. Orders the blocks (AMD), builds the elimination tree and sizes L.
  /// Throws std::invalid_argument on an index out of range or row == col.
  void analyze(int blocks, const std::vector<std::pair<int, int>>& pairs);
  /// True when analyze() was given exactly this pattern (same count, same pairs in the same order).
  [[nodiscard]] bool analyzed(int blocks, const std::vector<std::pair<int, int>>& pairs) const {
    return symbolic_.analyzed(blocks, pairs);
  }
  /// Numeric factorization: `diagonal[i]` = A(i, i) (symmetric), `coupling[p]` = A(row, col) of
  /// pair p. False (and the factorization unusable) when a pivot block is singular or not finite.
  bool factorize(const std::vector<Block>& diagonal, const std::vector<Block>& coupling);
  /// x = A^-1 b with the last successful factorization (x may alias b).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);

  [[nodiscard]] int blockCount() const { return symbolic_.n; }
  [[nodiscard]] int factorBlocks() const { return symbolic_.lp.empty() ? 0 : symbolic_.lp.back(); }

 private:
  BlockElimination symbolic_;
  std::vector<int> li_, lnz_, flag_, pattern_;  // L's rows and the workspaces of Davis
  std::vector<Block> lx_, dInverse_, y_;
  Eigen::VectorXd work_;
};

extern template class BlockLdltOf<3>;
extern template class BlockLdltOf<6>;
using BlockLdlt = BlockLdltOf<6>;

}  // namespace coulomb::solvers
