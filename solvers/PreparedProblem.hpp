#pragma once
// The form every solver works on, built once per solve by ContactSolver::solve from a validated
// ContactProblem: W as a block-sparse matrix over the problem's blocks, q, block offsets and the
// per-block data the inner loops need. Anisotropic contacts are mapped to isotropic ones with
// mu = 1 by the change of variables r = S r~, S = diag(1, mu1, mu2): then u~ = S u = (S W S) r~ + S
// q and ||M^-1 r_T|| <= r_N becomes ||r~_T|| <= r~_N, with the De Saxce shift u~_N + ||u~_T|| = u_N
// + ||M u_T||: the same law, so every solver only ever sees isotropic cones.
#include <coulomb/solvers/BlockSparseMatrix.hpp>
#include <coulomb/solvers/ContactProblem.hpp>
#include <coulomb/solvers/SolverOptions.hpp>
#include <coulomb/solvers/SolverReport.hpp>

#include <Eigen/Core>

#include <chrono>
#include <memory>
#include <vector>

namespace coulomb::solvers {

struct PreparedProblem {
  // W's entries (empty when bodySpace is set): the problem's own block-sparse W, read in place
  // when the solve can take it as it is, else `ownW`, formed (from the factors), scaled
  // (anisotropic contacts) or shifted (a proximal subproblem) here.
  [[nodiscard]] const BlockSparseMatrix& W() const { return sharedW ? *sharedW : ownW; }
  // ownW to write into, holding W's current entries (a copy of the problem's when it was shared).
  BlockSparseMatrix& writableW();
  std::shared_ptr<const BlockSparseMatrix> sharedW;  // released with bodySpace when the solve ends
  BlockSparseMatrix ownW;
  // Set instead of W when the problem's W is body-space and isotropic (assign with keepBodySpace):
  // solvers that work on the factors (Gauss-Seidel, see BodySpaceDelassus) never form W; for the
  // others ContactSolver calls formExplicitW only once they iterate (the starts are evaluated on
  // the factors).
  std::shared_ptr<const BodySpaceDelassus> bodySpace;
  // With bodySpace: W_bb row-major at 9 b, the factors' own cache (BodySpaceDelassus::
  // diagonalBlocks, valid while bodySpace is held: the factors are never changed once shared).
  const double* diagonalBlocks = nullptr;
  // The factors of W (J M^-1 J^T) when the problem came with them and is isotropic, kept after
  // formExplicitW: a Newton step may solve its system in body space (BodySpaceNewtonSolve, when
  // that system is the smaller). W = factors + factorsShift I (a proximal subproblem adds its
  // shift to W and to factorsShift). Released with bodySpace when the solve ends.
  std::shared_ptr<const BodySpaceDelassus> factors;
  double factorsShift = 0.0;
  Eigen::VectorXd q;
  std::vector<ConstraintBlock> blocks;  // isotropic (anisotropic ones mapped, see above)
  std::vector<int> offset;              // blocks.size() + 1 entries
  std::vector<int> sizes;               // blocks[b].size()
  Eigen::VectorXd scale;                // r_original = scale .* r; empty = identity
  double qNorm = 0.0;                   // plainNorm(q)
  double maxDiagonal = 0.0;             // max_i W_ii

  // A residual already evaluated (residual() below) with what it computed: u = W r + q, in body
  // space dv = M^-1 J^T r, the relative and absolute residuals, and whether W was the body-space
  // factors then (formExplicitW changes the rounding of W r). Reading it instead of evaluating
  // again gives the same bits.
  // A copy of a PreparedProblem does not inherit one: composite solvers copy the problem to change
  // its W or q (ac_newton's proximal subproblems), for which these values would be wrong.
  struct KnownEvaluation {
    KnownEvaluation() = default;
    KnownEvaluation(const KnownEvaluation& /*other*/) {}
    KnownEvaluation(KnownEvaluation&&) = default;
    KnownEvaluation& operator=(const KnownEvaluation& other) {
      if (this != &other) *this = KnownEvaluation();
      return *this;
    }
    KnownEvaluation& operator=(KnownEvaluation&&) = default;
    ~KnownEvaluation() = default;
    // True when known and made for r, bit for bit.
    [[nodiscard]] bool isOf(const Eigen::VectorXd& r) const;
    bool known = false;
    Eigen::VectorXd r, u, dv;  // dv: body space only
    double residual = 0.0, absolute = 0.0;
    bool inBodySpace = false;
  };
  // The start ContactSolver::solve hands to the solver: a solver starting from this very r
  // (startIs) reads its residual, u and dv instead of computing them a second time.
  KnownEvaluation start;
  // The solver's answer, when its last act was evaluating it (recordEnd): ContactSolver reads the
  // common residual from it. Mutable: solvers see the problem as const.
  mutable KnownEvaluation end;

  static PreparedProblem from(const ContactProblem& problem, bool keepBodySpace = false);
  // The same into this object, reusing its storage (ContactSolver's workspace).
  void assign(const ContactProblem& problem, bool keepBodySpace = false);
  // W formed from the body-space factors kept by assign (a no-op without them): ContactSolver
  // keeps the factors while it only evaluates starts, and forms W only for a solver that iterates
  // on it, so that a warm start that already converges never pays for W.
  void formExplicitW(const ContactProblem& problem);

  [[nodiscard]] int size() const { return static_cast<int>(q.size()); }
  [[nodiscard]] int blockCount() const { return static_cast<int>(blocks.size()); }
  [[nodiscard]] Eigen::Matrix3d contactBlock(int b) const;  // W_bb of a contact block
  [[nodiscard]] double diagonal(int row) const;             // W_ii
  [[nodiscard]] const double* diagonalBlock(int b) const;   // W_bb, row-major
  [[nodiscard]] double largestDiagonal() const;             // max_i W_ii

  void velocity(const Eigen::VectorXd& r, Eigen::VectorXd& u) const;  // u = W r + q
  // e_rel of (1.8) in this problem's variables; computes u. With `absolute`, also the unscaled
  // ||F(r)||.
  double residual(const Eigen::VectorXd& r, Eigen::VectorXd& u, double* absolute = nullptr) const;
  // The same (bit for bit) that also keeps dv = M^-1 J^T r in body space (dv untouched otherwise).
  double residual(const Eigen::VectorXd& r, Eigen::VectorXd& u, Eigen::VectorXd& dv,
                  double* absolute = nullptr) const;
  // True when `start` is known and r is bitwise the same vector.
  [[nodiscard]] bool startIs(const Eigen::VectorXd& r) const;
  // With `absolute`, also the unscaled ||F(r)|| (the common residual's absolute value).
  [[nodiscard]] double residualFromVelocity(const Eigen::VectorXd& r, const Eigen::VectorXd& u,
                                            double* absolute = nullptr) const;
  // True when `start` is known for r and was evaluated on W as it is now (u reusable).
  [[nodiscard]] bool startEvaluatedAs(const Eigen::VectorXd& r) const;
  // Records r (the solver's answer) with u = W r + q and its residual (relative, absolute: what
  // residual() gave for them) as `end`.
  void recordEnd(const Eigen::VectorXd& r, const Eigen::VectorXd& u, double residual,
                 double absolute) const;
  // Projection onto the constraint set: cones, bounds, [0, inf); equality rows untouched.
  void project(Eigen::VectorXd& r) const;
  [[nodiscard]] Eigen::VectorXd toOriginal(const Eigen::VectorXd& r) const;
  [[nodiscard]] Eigen::VectorXd fromOriginal(const Eigen::VectorXd& r) const;
  // The same into `out` (may not alias r).
  void toOriginal(const Eigen::VectorXd& r, Eigen::VectorXd& out) const;
  void fromOriginal(const Eigen::VectorXd& r, Eigen::VectorXd& out) const;
};

// Per-solve services: clock, time limit, iteration budget, history.
class SolveContext {
 public:
  using Clock = std::chrono::steady_clock;
  SolveContext(const SolverOptions& options, Clock::time_point start);

  [[nodiscard]] const SolverOptions& options() const { return options_; }
  [[nodiscard]] double tolerance() const { return options_.tolerance; }
  [[nodiscard]] int maxIterations(int solverDefault) const {
    return options_.maxIterations > 0 ? options_.maxIterations : solverDefault;
  }
  [[nodiscard]] double elapsed() const;
  // True once the time limit has passed (and marks the report).
  bool timeUp(SolverReport& report) const;
  // Appends to report.history when the options ask for it.
  void record(SolverReport& report, int iteration, double residual) const;
  // A context with the same clock and limit but other options (inner solves of composite solvers).
  [[nodiscard]] SolveContext withOptions(const SolverOptions& options) const;

 private:
  SolverOptions options_;
  Clock::time_point start_;
};

}  // namespace coulomb::solvers
