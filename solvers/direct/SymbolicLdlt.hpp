#pragma once
// The symbolic part shared by the sparse LDL^T factorizations (SparseLdlt on scalar entries,
// BlockLdlt on 6 x 6 blocks): the fill-reducing ordering and the elimination tree of a symmetric
// pattern. Davis (2005), "Algorithm 849: A concise sparse Cholesky factorization package", ACM
// TOMS 31(4): ldl_symbolic.
#include <utility>
#include <vector>

namespace coulomb::solvers {

/// AMD ordering (Eigen's, as its SimplicialLDLT) of the n x n symmetric pattern with the given
/// off-diagonal entries (either triangle, duplicates allowed; the diagonal is implied):
/// perm[original] = position.
void amdOrdering(int n, const std::vector<std::pair<int, int>>& entries, std::vector<int>& perm);

/// The elimination tree (parent[k], -1 at a root) and the entries of each column of L (lnz[k])
/// of the ordered pattern given as its upper triangle by columns: column k's rows are
/// ai[ap[k] .. ap[k + 1]); rows >= k are skipped. `flag` is workspace (n entries).
void eliminationTree(int n, const std::vector<int>& ap, const std::vector<int>& ai,
                     std::vector<int>& parent, std::vector<int>& lnz, std::vector<int>& flag);

}  // namespace coulomb::solvers
