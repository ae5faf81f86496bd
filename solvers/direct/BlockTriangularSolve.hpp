#pragma once
// x = A^-1 b from a factorization A = P^T L D U P by N x N blocks (BlockLdlt: U = L^T; BlockLu),
// L unit lower triangular stored by columns (column j's blocks L(li[p], j) at lx[p], p in
// [lp[j], lp[j+1])) and row j of U at the same positions. Internal to BlockLdlt.cpp and
// BlockLu.cpp.
#include <coulomb/solvers/direct/SymbolicLdlt.hpp>

#include <Eigen/Core>

#include <vector>

namespace coulomb::solvers::detail {

/// `upper(p)` is U(j, li[p]) for an index p of column j. x may alias b; `work` has N n entries.
template <int N, class Upper>
void solveByBlocks(const BlockElimination& s, const std::vector<int>& li,
                   const std::vector<Eigen::Matrix<double, N, N>>& lx, Upper upper,
                   const std::vector<Eigen::Matrix<double, N, N>>& dInverse, Eigen::VectorXd& work,
                   const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const int n = s.n;
  using Segment = Eigen::Matrix<double, N, 1>;
  auto w = [&](int j) { return work.segment<N>(N * static_cast<Eigen::Index>(j)); };
  for (int i = 0; i < n; ++i) w(s.perm[i]) = b.segment<N>(N * static_cast<Eigen::Index>(i));
  for (int j = 0; j < n; ++j) {  // L y = P b
    const Segment wj = w(j);
    for (int p = s.lp[j]; p < s.lp[j + 1]; ++p) w(li[p]).noalias() -= lx[p] * wj;
  }
  for (int j = 0; j < n; ++j) w(j) = (dInverse[j] * w(j)).eval();
  for (int j = n - 1; j >= 0; --j) {  // U z = D^-1 y
    Segment wj = w(j);
    for (int p = s.lp[j]; p < s.lp[j + 1]; ++p) wj.noalias() -= upper(p) * w(li[p]);
    w(j) = wj;
  }
  x.resize(N * static_cast<Eigen::Index>(n));
  for (int i = 0; i < n; ++i) x.segment<N>(N * static_cast<Eigen::Index>(i)) = w(s.perm[i]);
}

}  // namespace coulomb::solvers::detail
