#include <coulomb/solvers/direct/BlockLdlt.hpp>

#include <coulomb/solvers/direct/SymbolicLdlt.hpp>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <algorithm>
#include <stdexcept>

namespace coulomb::solvers {

template <int N>
void BlockLdltOf<N>::analyze(int blocks, const std::vector<std::pair<int, int>>& pairs) {
  if (blocks < 0) throw std::invalid_argument("BlockLdlt::analyze: negative block count");
  for (const auto& [row, col] : pairs)
    if (row < 0 || col < 0 || row >= blocks || col >= blocks || row == col)
      throw std::invalid_argument("BlockLdlt::analyze: a pair outside the matrix or diagonal");
  const int n = blocks;
  n_ = n;
  pairs_ = pairs;

  // Fill-reducing ordering of the bodies' graph.
  amdOrdering(n, pairs, perm_);
  inverse_.resize(n);
  for (int i = 0; i < n; ++i) inverse_[perm_[i]] = i;

  // Each pair above the diagonal of the later of its two columns (Davis's upper triangle).
  ep_.assign(n + 1, 0);
  for (const auto& [row, col] : pairs) ++ep_[std::max(perm_[row], perm_[col]) + 1];
  for (int k = 0; k < n; ++k) ep_[k + 1] += ep_[k];
  entries_.resize(pairs.size());
  {
    std::vector<int> next(ep_.begin(), ep_.end() - 1);
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      const int a = perm_[pairs[p].first], b = perm_[pairs[p].second];
      // A(a, b) = coupling[p]; above the diagonal of column max(a, b) it is A(min, max).
      entries_[next[std::max(a, b)]++] = {std::min(a, b), static_cast<int>(p), a > b};
    }
  }

  // The elimination tree of the blocks and the block counts of L's columns.
  {
    std::vector<int> rowsAbove(entries_.size());
    for (std::size_t e = 0; e < entries_.size(); ++e) rowsAbove[e] = entries_[e].i;
    eliminationTree(n, ep_, rowsAbove, parent_, lnz_, flag_);
  }
  lp_.assign(n + 1, 0);
  for (int k = 0; k < n; ++k) lp_[k + 1] = lp_[k] + lnz_[k];
  li_.assign(lp_[n], 0);
  lx_.assign(lp_[n], Block::Zero());
  dInverse_.assign(n, Block::Zero());
  y_.assign(n, Block::Zero());
  pattern_.assign(n, 0);
  work_.resize(N * static_cast<Eigen::Index>(n));
}

template <int N>
bool BlockLdltOf<N>::analyzed(int blocks, const std::vector<std::pair<int, int>>& pairs) const {
  return blocks == n_ && pairs == pairs_;
}

template <int N>
bool BlockLdltOf<N>::factorize(const std::vector<Block>& diagonal,
                               const std::vector<Block>& coupling) {
  const int n = n_;
  if (n < 0 || diagonal.size() != static_cast<std::size_t>(n) || coupling.size() != pairs_.size())
    throw std::invalid_argument("BlockLdlt::factorize: values do not match the pattern");
  // Row k of L by a block triangular solve along the elimination tree (Davis's ldl_numeric with
  // N x N blocks): Y_i = D_i L_ki^T, Y_r -= L_ri Y_i, L_ki = (D_i^-1 Y_i)^T, D_k -= L_ki Y_i.
  for (int k = 0; k < n; ++k) {
    Block d = diagonal[inverse_[k]];
    int top = n;
    flag_[k] = k;
    lnz_[k] = 0;
    for (int e = ep_[k]; e < ep_[k + 1]; ++e) {
      const Entry& entry = entries_[e];
      if (entry.transposed)
        y_[entry.i] += coupling[entry.pair].transpose();
      else
        y_[entry.i] += coupling[entry.pair];
      int length = 0;
      for (int i = entry.i; flag_[i] != k; i = parent_[i]) {
        pattern_[length++] = i;
        flag_[i] = k;
      }
      while (length > 0) pattern_[--top] = pattern_[--length];
    }
    for (; top < n; ++top) {
      const int i = pattern_[top];
      const Block yi = y_[i];
      y_[i].setZero();
      const int end = lp_[i] + lnz_[i];
      for (int p = lp_[i]; p < end; ++p) y_[li_[p]].noalias() -= lx_[p] * yi;
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
  const int n = n_;
  using Segment = Eigen::Matrix<double, N, 1>;
  auto w = [&](int j) { return work_.segment<N>(N * static_cast<Eigen::Index>(j)); };
  for (int i = 0; i < n; ++i) w(perm_[i]) = b.segment<N>(N * static_cast<Eigen::Index>(i));
  for (int j = 0; j < n; ++j) {  // L y = P b
    const Segment wj = w(j);
    for (int p = lp_[j]; p < lp_[j + 1]; ++p) w(li_[p]).noalias() -= lx_[p] * wj;
  }
  for (int j = 0; j < n; ++j) w(j) = (dInverse_[j] * w(j)).eval();
  for (int j = n - 1; j >= 0; --j) {  // L^T z = D^-1 y
    Segment wj = w(j);
    for (int p = lp_[j]; p < lp_[j + 1]; ++p) wj.noalias() -= lx_[p].transpose() * w(li_[p]);
    w(j) = wj;
  }
  x.resize(N * static_cast<Eigen::Index>(n));
  for (int i = 0; i < n; ++i) x.segment<N>(N * static_cast<Eigen::Index>(i)) = w(perm_[i]);
}

template class BlockLdltOf<3>;
template class BlockLdltOf<6>;

}  // namespace coulomb::solvers
