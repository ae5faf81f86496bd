#include <coulomb/solvers/direct/SymbolicLdlt.hpp>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

#include <algorithm>
#include <stdexcept>

namespace coulomb::solvers {

void amdOrdering(int n, const std::vector<std::pair<int, int>>& entries, std::vector<int>& perm) {
  std::vector<Eigen::Triplet<double>> full;
  full.reserve(2 * entries.size() + static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) full.emplace_back(i, i, 1.0);
  for (const auto& [row, col] : entries) {
    full.emplace_back(row, col, 1.0);
    full.emplace_back(col, row, 1.0);
  }
  Eigen::SparseMatrix<double> pattern(n, n);
  pattern.setFromTriplets(full.begin(), full.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
  Eigen::AMDOrdering<int>()(pattern, inverse);  // inverse.indices()[new] = original
  perm.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) perm[inverse.indices()[k]] = k;
}

void eliminationTree(int n, const std::vector<int>& ap, const std::vector<int>& ai,
                     std::vector<int>& parent, std::vector<int>& lnz, std::vector<int>& flag) {
  parent.assign(n, -1);
  lnz.assign(n, 0);
  flag.assign(n, 0);
  for (int k = 0; k < n; ++k) {
    flag[k] = k;
    for (int p = ap[k]; p < ap[k + 1]; ++p)
      for (int i = ai[p]; i < k && flag[i] != k; i = parent[i]) {
        if (parent[i] == -1) parent[i] = k;
        ++lnz[i];
        flag[i] = k;
      }
  }
}

void BlockElimination::analyze(int blocks, const std::vector<std::pair<int, int>>& coupled) {
  if (blocks < 0) throw std::invalid_argument("block factorization: negative block count");
  for (const auto& [row, col] : coupled)
    if (row < 0 || col < 0 || row >= blocks || col >= blocks || row == col)
      throw std::invalid_argument("block factorization: a pair outside the matrix or diagonal");
  n = blocks;
  pairs = coupled;
  amdOrdering(n, pairs, perm);
  inverse.resize(n);
  for (int i = 0; i < n; ++i) inverse[perm[i]] = i;

  ep.assign(n + 1, 0);
  for (const auto& [row, col] : pairs) ++ep[std::max(perm[row], perm[col]) + 1];
  for (int k = 0; k < n; ++k) ep[k + 1] += ep[k];
  entries.resize(pairs.size());
  std::vector<int> next(ep.begin(), ep.end() - 1);
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const int a = perm[pairs[p].first], b = perm[pairs[p].second];
    entries[next[std::max(a, b)]++] = {std::min(a, b), static_cast<int>(p), a > b};
  }

  std::vector<int> rowsAbove(entries.size()), counts, flag;
  for (std::size_t e = 0; e < entries.size(); ++e) rowsAbove[e] = entries[e].i;
  eliminationTree(n, ep, rowsAbove, parent, counts, flag);
  lp.assign(n + 1, 0);
  for (int k = 0; k < n; ++k) lp[k + 1] = lp[k] + counts[k];
}

int BlockElimination::reach(int k, std::vector<int>& flag, std::vector<int>& pattern) const {
  int top = n;
  flag[k] = k;
  for (int e = ep[k]; e < ep[k + 1]; ++e) {
    int length = 0;
    for (int i = entries[e].i; flag[i] != k; i = parent[i]) {
      pattern[length++] = i;
      flag[i] = k;
    }
    while (length > 0) pattern[--top] = pattern[--length];
  }
  return top;
}

}  // namespace coulomb::solvers
