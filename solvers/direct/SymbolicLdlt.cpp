#include <coulomb/solvers/direct/SymbolicLdlt.hpp>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

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

}  // namespace coulomb::solvers
