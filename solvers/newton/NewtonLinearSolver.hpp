#pragma once
// The linear solve of one nonsmooth Newton step (docs/solver-derivations.md (5.7)-(5.8)): J_RR x =
// rhs with J = A (W + sigma I) + B restricted to the rows R that are not unit rows (the eliminated
// ones). J_RR has W's block sparsity (a tower is block-tridiagonal in body order), so above
// `denseThreshold` kept rows, when W is not nearly dense, it is assembled straight into a
// compressed sparse matrix and factorized by a sparse LU (below). The pattern of J_RR depends only
// on W's block structure and on R: it is built, and the sparse LU's symbolic analysis (ordering,
// block triangular form) is done, once per (structure, R) and reused by every later solve with the
// same pair (the Newton steps of one solve mostly keep R, the proximal subproblems (5.9) keep W's
// structure); only the numeric factorization is redone, on the last one's pivot order while that
// stays accurate (the solve's residual check), else with a fresh pivot search. The sparse LU is
// SuiteSparse's KLU (Davis and Palamadai Natarajan 2010: AMD ordering of the diagonal blocks of a
// block triangular form, left-looking LU with threshold partial pivoting, refactorization): on a
// 441-contact sphere packing's Newton solve the same iterates as Eigen's supernodal SparseLU in
// half the time (docs/benchmarks.md "KLU for the sparse Newton step").
// Measured crossovers (docs/benchmarks.md, "Newton linear solve"): on a tower's pattern the
// sparse LU wins from ~100 kept rows (4x at 240); on a dense W it is 1.2-1.6x slower than the
// dense LU at any size, hence the density bound.
#include <coulomb/solvers/BlockSparseMatrix.hpp>

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/SparseCore>

#include <memory>
#include <vector>

namespace coulomb::solvers {

// The generalized Jacobian blocks of one constraint block: dPhi_b = A_b du_b + B_b dr_b (only the
// leading blockSize x blockSize part is used for scalar rows).
struct NewtonBlockJacobian {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero(), B = Eigen::Matrix3d::Zero();
};

struct NewtonLinearStats {
  int denseSolves = 0;             // dense partial-pivoting LU solves
  int sparseSolves = 0;            // sparse LU solves (numeric factorizations)
  int refactorFallbacks = 0;       // refactorizations on the kept pivots that missed the check
  int patternAnalyses = 0;         // sparse patterns built + symbolic analyses (a new R)
  bool lastReusedPattern = false;  // the last sparse solve reused the cached pattern
};

class NewtonLinearSolver {
 public:
  // Dense LU when at most `denseThreshold` rows are kept or when W stores more than
  // `maxSparseDensity` n^2 entries; else sparse LU (pattern and analysis cached).
  explicit NewtonLinearSolver(int denseThreshold, double maxSparseDensity = 0.5);
  ~NewtonLinearSolver();
  NewtonLinearSolver(NewtonLinearSolver&&) noexcept;
  NewtonLinearSolver& operator=(NewtonLinearSolver&&) noexcept;

  // Solves J_RR x = rhs (rhs and x: |R| entries; x is resized to |R|). `kept` lists the rows of
  // R in increasing order, `index[i]` is the position of row i in `kept` or -1; `offset` the
  // block offsets of W (blockCount + 1 entries), `jac` the blocks A_b, B_b. False when the
  // factorization fails or the solution is not accurate (||J_RR x - rhs|| > 1e-8 ||rhs||).
  bool solve(const BlockSparseMatrix& W, const std::vector<int>& offset,
             const std::vector<NewtonBlockJacobian>& jac, const std::vector<int>& kept,
             const std::vector<int>& index, double sigma, const Eigen::VectorXd& rhs,
             Eigen::VectorXd& x);
  // The same on the leading |R| entries of rhs and x, both at least |R| long and never resized:
  // the Newton loop keeps them at the problem's size, so a changing |R| reallocates nothing.
  bool solveLeading(const BlockSparseMatrix& W, const std::vector<int>& offset,
                    const std::vector<NewtonBlockJacobian>& jac, const std::vector<int>& kept,
                    const std::vector<int>& index, double sigma, const Eigen::VectorXd& rhs,
                    Eigen::VectorXd& x);

  // J_RR x = rhs with the factors of the last successful solveLeading (no new factorization), on
  // the leading |R| entries as there; false when there are none or x is not accurate. For a
  // second right-hand side of the same Jacobian (NewtonWorkspace::factoredFor).
  bool solveAgain(const Eigen::VectorXd& rhs, Eigen::VectorXd& x);

  [[nodiscard]] const NewtonLinearStats& stats() const { return stats_; }
  [[nodiscard]] int denseThreshold() const { return denseThreshold_; }

 private:
  void buildPattern(const BlockSparseMatrix& W, const std::vector<int>& offset,
                    const std::vector<int>& kept, const std::vector<int>& index);
  void fillSparse(const BlockSparseMatrix& W, const std::vector<int>& offset,
                  const std::vector<NewtonBlockJacobian>& jac, const std::vector<int>& index,
                  double sigma);

  int denseThreshold_;
  double maxSparseDensity_;
  NewtonLinearStats stats_;
  [[nodiscard]] bool samePattern(const BlockSparseMatrix& W, const std::vector<int>& kept) const;

  // Cached pattern: key (W's block structure, R) and the matrix with, for every entry in assembly
  // order, its position in the compressed storage.
  std::vector<int> patternSizes_, patternRowStart_, patternColumns_, patternKept_;
  std::vector<int> slots_;
  Eigen::SparseMatrix<double> J_;
  struct SparseFactor;  // the sparse LU and its symbolic analysis (KLU: in the .cpp only)
  std::unique_ptr<SparseFactor> lu_;
  bool analyzed_ = false;
  // Dense path: J_RR and its LU factors in the leading m x m block of storage sized to the
  // largest m met (Eigen's blocked partial-pivoting LU run in place, with the leading dimension
  // of the storage), the row transpositions, so that a new |R| reallocates nothing.
  Eigen::MatrixXd dense_, denseLu_;
  std::vector<int> transpositions_;
  // What the last successful solveLeading factored: |R| and the path (0: none).
  enum class Factored { None, Dense, Sparse };
  Factored factored_ = Factored::None;
  int factoredRows_ = 0;
  Eigen::VectorXd check_;  // J_RR x - rhs
};

}  // namespace coulomb::solvers
