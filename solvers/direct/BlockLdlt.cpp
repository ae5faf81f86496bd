#include <coulomb/solvers/direct/BlockLdlt.hpp>

#include <coulomb/solvers/direct/BlockTriangularSolve.hpp>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <stdexcept>

namespace coulomb::solvers {

template <int N>
void BlockLdltOf<N>::analyze(int blocks, const std::vector<std::pair<int, int>>& pairs) {
  symbolic_.analyze(blocks, pairs);
  const int n = blocks;
  li_.assign(symbolic_.lp[n], 0);
  lx_.assign(symbolic_.lp[n], Block::Zero());
  lnz_.assign(n, 0);
  flag_.assign(n, 0);
  dInverse_.assign(n, Block::Zero());
  y_.assign(n, Block::Zero());
  pattern_.assign(n, 0);
  work_.resize(N * static_cast<Eigen::Index>(n));
}

template <int N>
bool BlockLdltOf<N>::factorize(const std::vector<Block>& diagonal,
                               const std::vector<Block>& coupling) {
  const BlockElimination& s = symbolic_;
  const int n = s.n;
  if (n < 0 || diagonal.size() != static_cast<std::size_t>(n) || coupling.size() != s.pairs.size())
    throw std::invalid_argument("BlockLdlt::factorize: values do not match the pattern");
  // Row k of L by a block triangular solve along the elimination tree (Davis's ldl_numeric with
  // N x N blocks): Y_i = D_i L_ki^T, Y_r -= L_ri Y_i, L_ki = (D_i^-1 Y_i)^T, D_k -= L_ki Y_i.
  for (int k = 0; k < n; ++k) {
    Block d = diagonal[s.inverse[k]];
    lnz_[k] = 0;
    for (int e = s.ep[k]; e < s.ep[k + 1]; ++e) {
      const BlockElimination::Entry& entry = s.entries[e];
      if (entry.transposed)
        y_[entry.i] += coupling[entry.pair].transpose();
      else
        y_[entry.i] += coupling[entry.pair];
    }
    for (int top = s.reach(k, flag_, pattern_); top < n; ++top) {
      const int i = pattern_[top];
      const Block yi = y_[i];
      y_[i].setZero();
      const int end = s.lp[i] + lnz_[i];
      for (int p = s.lp[i]; p < end; ++p) y_[li_[p]].noalias() -= lx_[p] * yi;
      const Block lki = (dInverse_[i] * yi).transpose();
      d.noalias() -= lki * yi;
      li_[end] = k;
      lx_[end] = lki;
      ++lnz_[i];
    }
    if (!d.allFinite()) return false;
    if constexpr (N <= 4) {
      // Eigen's closed-form (cofactor) inverse: a 3 x 3 pivot by a pivoted LDL^T and N
      // solves cost half of the whole factorization of a chain's correction matrix.
      bool invertible = false;
      d.computeInverseWithCheck(dInverse_[k], invertible, 0.0);
      if (!invertible) return false;
    } else {
      const Eigen::LDLT<Block> pivot(d);
      if (pivot.info() != Eigen::Success || (pivot.vectorD().array() == 0.0).any()) return false;
      dInverse_[k] = pivot.solve(Block::Identity());
    }
    if (!dInverse_[k].allFinite()) return false;
  }
  return true;
}

template <int N>
void BlockLdltOf<N>::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  detail::solveByBlocks<N>(
      symbolic_, li_, lx_, [&](int p) { return lx_[p].transpose(); }, dInverse_, work_, b, x);
}

template class BlockLdltOf<3>;
template class BlockLdltOf<6>;

}  // namespace coulomb::solvers
