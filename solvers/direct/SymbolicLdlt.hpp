#pragma once
// The symbolic part shared by the sparse factorizations (SparseLdlt on scalar entries, BlockLdlt
// and BlockLu on N x N blocks): the fill-reducing ordering and the elimination tree of a symmetric
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

/// The analysis of a pattern of N x N blocks (any N) that BlockLdlt and BlockLu share: `blocks`
/// block rows and the coupled pairs (row, col), row != col, each standing for A(row, col) and
/// A(col, row). The blocks are ordered (AMD), each pair is filed above the diagonal of the later of
/// its two columns, and the elimination tree gives the block count of every column of L.
struct BlockElimination {
  struct Entry {  // A(i, k) (or A(k, i)) of `pair`, above the diagonal of column k
    int i, pair;
    bool transposed;  // the pair's row is k: its block is A(k, i)
  };
  int n = -1;
  std::vector<std::pair<int, int>> pairs;  // the analyzed pattern, as given
  std::vector<int> perm, inverse;          // perm[original] = position; inverse[position]
  std::vector<int> ep;                     // column k's entries: entries[ep[k] .. ep[k + 1])
  std::vector<Entry> entries;
  std::vector<int> lp, parent;  // L's column starts (by blocks) and the elimination tree

  /// Throws std::invalid_argument on a negative count, an index out of range or row == col.
  void analyze(int blocks, const std::vector<std::pair<int, int>>& coupled);
  /// The columns i < k of row k of L that can be nonzero, in an order that eliminates each after
  /// those it depends on: pattern[top .. n) with top returned (Davis's ereach). `flag` and
  /// `pattern` have n entries; flag[k] is set to k.
  int reach(int k, std::vector<int>& flag, std::vector<int>& pattern) const;
  [[nodiscard]] bool analyzed(int blocks, const std::vector<std::pair<int, int>>& coupled) const {
    return blocks == n && coupled == pairs;
  }
};

}  // namespace coulomb::solvers
