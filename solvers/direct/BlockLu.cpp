#include <coulomb/solvers/direct/BlockLu.hpp>

#include <coulomb/solvers/direct/BlockTriangularSolve.hpp>

#include <Eigen/LU>

#include <stdexcept>

namespace coulomb::solvers {

template <int N>
void BlockLuOf<N>::analyze(int blocks, const std::vector<std::pair<int, int>>& pairs) {
  symbolic_.analyze(blocks, pairs);
  const int n = blocks;
  li_.assign(symbolic_.lp[n], 0);
  lx_.assign(symbolic_.lp[n], Block::Zero());
  ux_.assign(symbolic_.lp[n], Block::Zero());
  lnz_.assign(n, 0);
  flag_.assign(n, 0);
  pattern_.assign(n, 0);
  dInverse_.assign(n, Block::Zero());
  y_.assign(n, Block::Zero());
  z_.assign(n, Block::Zero());
  work_.resize(N * static_cast<Eigen::Index>(n));
}

template <int N>
bool BlockLuOf<N>::factorize(const std::vector<Block>& diagonal, const std::vector<Block>& coupling,
                             const std::vector<Block>& mirrored) {
  const BlockElimination& s = symbolic_;
  const int n = s.n;
  if (n < 0 || diagonal.size() != static_cast<std::size_t>(n) ||
      coupling.size() != s.pairs.size() || mirrored.size() != s.pairs.size())
    throw std::invalid_argument("BlockLu::factorize: values do not match the pattern");
  // Step k: column k of U above the diagonal from L y = A(0:k, k), y_i = D_i U(i, k); row k of L
  // from U^T z = A(k, 0:k)^T, z_i = D_i^T L(k, i)^T; then D_k = A(k, k) - sum L(k, i) D_i U(i, k).
  // Both solves visit the same blocks: the reach of column k in the elimination tree.
  for (int k = 0; k < n; ++k) {
    Block d = diagonal[s.inverse[k]];
    lnz_[k] = 0;
    for (int e = s.ep[k]; e < s.ep[k + 1]; ++e) {
      const BlockElimination::Entry& entry = s.entries[e];
      // Not transposed: the pair's row is i, coupling = A(i, k) and mirrored = A(k, i).
      const Block& upper = entry.transposed ? mirrored[entry.pair] : coupling[entry.pair];
      const Block& lower = entry.transposed ? coupling[entry.pair] : mirrored[entry.pair];
      y_[entry.i] += upper;
      z_[entry.i] += lower.transpose();
    }
    for (int top = s.reach(k, flag_, pattern_); top < n; ++top) {
      const int i = pattern_[top];
      const Block yi = y_[i], zi = z_[i];
      y_[i].setZero();
      z_[i].setZero();
      const int end = s.lp[i] + lnz_[i];
      for (int p = s.lp[i]; p < end; ++p) {
        y_[li_[p]].noalias() -= lx_[p] * yi;
        z_[li_[p]].noalias() -= ux_[p].transpose() * zi;
      }
      const Block lki = zi.transpose() * dInverse_[i];
      d.noalias() -= lki * yi;
      li_[end] = k;
      lx_[end] = lki;
      ux_[end] = dInverse_[i] * yi;
      ++lnz_[i];
    }
    if (!d.allFinite()) return false;
    bool invertible = false;
    d.computeInverseWithCheck(dInverse_[k], invertible, 0.0);  // closed form for N <= 4
    if (!invertible || !dInverse_[k].allFinite()) return false;
  }
  return true;
}

template <int N>
void BlockLuOf<N>::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  detail::solveByBlocks<N>(
      symbolic_, li_, lx_, [&](int p) -> const Block& { return ux_[p]; }, dInverse_, work_, b, x);
}

template class BlockLuOf<1>;
template class BlockLuOf<3>;

}  // namespace coulomb::solvers
