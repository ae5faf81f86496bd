#pragma once
// Sparse LU (A = L D U, L unit lower and U unit upper triangular by blocks, D block diagonal) of a
// square matrix of N x N blocks whose pattern is symmetric but whose values are not: the Newton
// matrix B = J_pred M^-1 J_start^T of the joint correction (integrators/PredictedStateCorrection),
// with one block row per joint. It is BlockLdlt's up-looking algorithm run on both triangles: row
// k of L and column k of U are two sparse triangular solves along the same elimination tree
// (Davis 2006, "Direct Methods for Sparse Linear Systems", sec. 4.1 and 6.1), so the ordering
// (AMD) and the storage of L are analysed once per pattern and U shares L's pattern. There is no
// pivoting between blocks: this suits matrices whose symmetric part is positive definite (B near
// J M^-1 J^T); a singular or non-finite pivot block is reported, never used. Instantiated for
// N = 1 (scalar entries) and N = 3 (ball joints) in BlockLu.cpp.
#include <coulomb/solvers/direct/SymbolicLdlt.hpp>

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace coulomb::solvers {

template <int N>
class BlockLuOf {
 public:
  using Block = Eigen::Matrix<double, N, N>;

  /// The pattern: `blocks` block rows and the coupled pairs (row, col), row != col, each standing
  /// for both A(row, col) and A(col, row); the diagonal is always present. Throws
  /// std::invalid_argument on an index out of range or row == col.
  void analyze(int blocks, const std::vector<std::pair<int, int>>& pairs);
  [[nodiscard]] bool analyzed(int blocks, const std::vector<std::pair<int, int>>& pairs) const {
    return symbolic_.analyzed(blocks, pairs);
  }
  /// Numeric factorization: `diagonal[i]` = A(i, i), `coupling[p]` = A(row, col) and
  /// `mirrored[p]` = A(col, row) of pair p. False (and the factorization unusable) when a pivot
  /// block is singular or not finite.
  bool factorize(const std::vector<Block>& diagonal, const std::vector<Block>& coupling,
                 const std::vector<Block>& mirrored);
  /// x = A^-1 b with the last successful factorization (x may alias b).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);

  [[nodiscard]] int blockCount() const { return symbolic_.n; }

 private:
  BlockElimination symbolic_;
  std::vector<int> li_, lnz_, flag_, pattern_;  // rows of L's columns (= columns of U's rows)
  std::vector<Block> lx_, ux_;                  // L(li, i) and U(i, li) at the same positions
  std::vector<Block> dInverse_, y_, z_;
  Eigen::VectorXd work_;
};

extern template class BlockLuOf<1>;
extern template class BlockLuOf<3>;

}  // namespace coulomb::solvers
