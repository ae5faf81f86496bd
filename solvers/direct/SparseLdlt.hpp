#pragma once
// Sparse LDL^T of a symmetric matrix whose pattern repeats from solve to solve (a joint island's
// W, the joint correction's normal matrix): the symbolic part (fill-reducing AMD ordering,
// elimination tree, column counts, storage of L) is done once per pattern by analyze(); every
// later factorize() and solve() works in that storage and allocates nothing. The numeric part is
// the up-looking LDL^T of Davis (2005), "Algorithm 849: A concise sparse Cholesky factorization
// package", ACM TOMS 31(4): row k of L from a sparse triangular solve along the elimination tree.
// No pivoting: for a symmetric positive (semi)definite W a zero pivot is reported, a tiny one is
// left to the caller's residual check (redundant rows of a loop).
// On a tree-structured W (a chain or a branching mechanism of joints) the AMD ordering follows the
// tree and L has no fill: linear time (Baraff 1996, section 7).
#include <Eigen/Core>

#include <vector>

namespace coulomb::solvers {

class SparseLdlt {
 public:
  /// The pattern of the lower triangle (row >= col) of an n x n symmetric matrix, as parallel
  /// lists of entries in any order (duplicates are summed by factorize). Orders it, builds the
  /// elimination tree and sizes L.
  void analyze(int n, const std::vector<int>& rows, const std::vector<int>& cols);
  /// True when analyze() was given exactly this pattern (same n, same entries in the same order).
  [[nodiscard]] bool analyzed(int n, const std::vector<int>& rows,
                              const std::vector<int>& cols) const;
  /// Numeric factorization with the values of the analyzed entries, in their order. False (and
  /// the factorization unusable) when a pivot is exactly zero or not finite.
  bool factorize(const std::vector<double>& values);
  /// The same, revealing dependent rows (a loop's redundant joint rows): a pivot at or below
  /// `pivotFloor` marks its row (the ordered index is appended to `dependent`) and is replaced by
  /// the floor, so that the factors are those of A + D_f, D_f diagonal with entries of at most
  /// the floor on the dependent rows: solve() is then one step of inverse iteration towards A's
  /// near-null space (docs/solver-derivations.md (10.3)). False only for a non-finite pivot.
  bool factorizeRevealing(const std::vector<double>& values, double pivotFloor,
                          std::vector<int>& dependent);
  /// For a dependent row k (ordered index, from factorizeRevealing): n = P^T L^-T e_k in the
  /// original order. The factors are of A + D_f, so (A + D_f) n = d_k L e_k with d_k the floored
  /// pivot: A n is of the size of the floor, n a vector of A's (near) null space.
  void nullVector(int k, Eigen::VectorXd& n);
  /// x = A^-1 b with the last successful factorization (x may alias b).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);

  [[nodiscard]] int size() const { return n_; }
  [[nodiscard]] int factorNonZeros() const { return lp_.empty() ? 0 : lp_.back(); }

 private:
  bool factorizeWith(const std::vector<double>& values, double pivotFloor,
                     std::vector<int>* dependent);
  int n_ = -1;
  std::vector<int> rows_, cols_;  // the analyzed pattern, as given
  std::vector<int> perm_;         // perm_[original] = position in the ordered matrix
  std::vector<int> ap_, ai_;      // ordered upper triangle, compressed by column
  std::vector<int> slotOf_;       // entry e of the pattern -> its position in ax_
  std::vector<double> ax_;
  std::vector<int> lp_, li_, parent_, lnz_, flag_, pattern_;  // L and the workspaces of Davis
  std::vector<double> lx_, d_, y_;
  Eigen::VectorXd work_;
};

}  // namespace coulomb::solvers
