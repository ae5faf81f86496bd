#pragma once
// The all-sticking start of a body-space problem (docs/solvers.md "Sticking start"): the impulses
// that stop every active contact (touching, approaching or loaded in the last step) and satisfy
// every equality, bounded and active unilateral row, u = W r + q = 0 on those rows, as if every
// such contact stuck. On a resting stack that is the exact answer, which Gauss-Seidel reaches only
// after hundreds of sweeps from r = 0 (the load must travel through every layer) and Newton
// after tens of iterations (pyramid_10's first step: 0 sweeps instead of 200 bgs_nncg sweeps and
// a Newton fallback). Elsewhere it is one more start candidate: the solver projects it onto the
// cones and keeps it only if its residual beats the warm start's and r = 0's.
//
// W = J M^-1 J^T has rank at most 6 x bodies while it has 3 x contacts rows (four coplanar points
// per face): the rows are solved in body space, never in W's size. With P = J^T J and
// Q = M^-1 J^T J M^-1 (both 6 x 6 blocks on bodies that share a row, from the factors J and
// G = M^-1 J^T the operator already holds):
//   f = -Q^-1 (M^-1 J^T q)     the bodies' impulses that make J dv = -q (least squares),
//   r =  J P^-1 f              the row impulses of least norm with J^T r = f,
// so that dv = M^-1 J^T r gives u = q + J dv = 0 when the rows can all be met; redundant rows share
// the load evenly (least norm). This is exact when every body of the island is held in all six
// directions by the stopped rows (stacks, pyramids and piles at rest); a body left free in some
// direction (a ball on a plane) gets a least-squares approximation, which the residual test may
// reject. Both matrices get the same small multiple of the identity (kRegularization of their
// mean diagonal), and one step of iterative refinement with the same factors removes what that
// costs in accuracy. Two factorizations of one pattern by 6 x 6 blocks (BlockLdlt, analysed once
// per contact graph), O(bodies) on a stack (pyramid_20's 211 boxes: docs/benchmarks.md).
#include <coulomb/solvers/BodySpaceDelassus.hpp>
#include <coulomb/solvers/ContactProblem.hpp>
#include <coulomb/solvers/direct/BlockLdlt.hpp>

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace coulomb::solvers {

class StickingStart {
 public:
  // [-] Added to P and Q's diagonals, relative to their mean diagonal. The start from the
  // regularized factors misses the rows' stop by about 1e3 times this on a resting stack (P's
  // conditioning grows with the stack's height: 1e-9 to 2e-7 on the towers and pyramids), and
  // compute() takes it to round-off by one step of iterative refinement with the same factors;
  // 1e-10 left 2e-7 to 7e-7 before the refinement, 1e-14 round-off in the free directions.
  static constexpr double kRegularization = 1e-12;

  /// The start r (start(), W.size() entries) from W's factors, q and the blocks (W's partition).
  /// The rows stopped are the active ones of the chooser (docs/solvers.md): equality and bounded
  /// rows, and contacts and unilateral rows that approach or rest (q_N <= 0) or carried load
  /// (`warmStart`, may be null: r_N > 0; the last step's impulses, or the iterate of a solve that
  /// restarts from it; a resting contact's q_N flickers around 0 by round-off and drift). The
  /// others get 0; r is not projected onto the cones. False when no row is selected or a
  /// factorization fails (r is then unusable).
  /// With `stepQ` (or null), the same rows' start for it as well, from the same factorizations:
  /// stepStart() (a solve's q - J v_k, ContactProblem::arrival).
  bool compute(const BodySpaceDelassus& W, const Eigen::VectorXd& q,
               const std::vector<ConstraintBlock>& blocks, const Eigen::VectorXd* warmStart,
               const Eigen::VectorXd* stepQ = nullptr);
  /// The last computed start (kept here, so that a solve that takes it allocates nothing).
  [[nodiscard]] const Eigen::VectorXd& start() const { return start_; }
  /// The last start for stepQ, when hasStepStart() (compute() had a stepQ and succeeded).
  [[nodiscard]] const Eigen::VectorXd& stepStart() const { return stepStart_; }
  [[nodiscard]] bool hasStepStart() const { return hasStepStart_; }

 private:
  // Whether block b is stopped, and its body pair's index in pairs_ (-1: one side or one body).
  // Computed when asked, not stored per block: a steady step allocates nothing even when a new
  // manifold point makes the island one block larger than ever before.
  [[nodiscard]] bool selected(const BodySpaceDelassus& W, int b) const;
  [[nodiscard]] int pairOf(const BodySpaceDelassus& W, int b) const;
  void buildPattern(const BodySpaceDelassus& W);
  // P (J's rows) or Q (M^-1 J^T's) into diagonal_ and coupling_, regularized.
  void accumulate(const BodySpaceDelassus& W, bool inverseMassWeighted);
  // Adds to `out` the start for the row velocities `velocities`, from Q's and P's factors.
  void startFor(const BodySpaceDelassus& W, const Eigen::VectorXd& velocities,
                Eigen::VectorXd& out);

  const Eigen::VectorXd* q_ = nullptr;  // the problem being started (during compute only)
  const std::vector<ConstraintBlock>* blocks_ = nullptr;
  const Eigen::VectorXd* warmStart_ = nullptr;
  std::vector<long long> pairs_;              // (higher body, lower body) of coupled bodies, sorted
  std::vector<std::pair<int, int>> pattern_;  // pairs_ as (higher, lower): P and Q's pattern
  std::vector<BlockLdlt::Block> diagonal_, coupling_;  // per body, per pair
  BlockLdlt ldltQ_, ldltP_;
  Eigen::VectorXd rhs_, f_, x_, start_, stepStart_;
  Eigen::VectorXd u_;  // the refinement's W r + q
  bool hasStepStart_ = false;
  int bodies_ = 0;
};

}  // namespace coulomb::solvers
