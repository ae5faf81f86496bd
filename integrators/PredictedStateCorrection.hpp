#pragma once
// Impulse-based predicted-state correction of joint drift (Bender, Finkenzeller, Schmitt 2005;
// survey: Bender, Erleben, Trinkle 2014, sec. 4.4.1, Fig. 11 and the system J M^-1 J^T p = dv).
// After the velocity solve, for every joint with this policy:
//   1. predict the poses at t+h that integratePositions would produce from the current
//      velocities (x + h v; the torque-free DLM rotation for dynamic bodies);
//   2. evaluate each joint's C at the predicted poses: the drift d(t+h) the step would leave;
//   3. take a Newton step on p -> C(t+h; p): B p = -d/h with B = J_pred M^-1 J^T (the impulse
//      along the start-of-step rows J, the error measured along the rows at the predicted state),
//      B carrying a tiny compliance eps I (eps = 1e-10 max diag(J M^-1 J^T)) so redundant rows,
//      e.g. a closed loop of hinges, stay solvable (docs/solver-derivations.md sec. 10); B
//      factorized by a sparse LU analysed once per joint structure (solvers/direct/BlockLu: by
//      3 x 3 blocks when every joint has 3 rows, else entry by entry), and dv = M^-1 J^T p applied;
//   4. repeat until every |C(t+h)| <= tolerance or the iteration cap;
//   5. if a pass stalls (|C| not halved or not reduced: SHAKE has no root near, e.g. a whip or
//      a heavy load on light links), the remaining passes project along the rows at the
//      predicted state instead.
// The converged velocity moves the bodies exactly onto the constraint manifold. With the
// velocity-level impulse of the solve along the same J^T, the whole step is the SHAKE
// discretisation (Ryckaert, Ciccotti, Berendsen 1977), which is symplectic: joint drift is
// removed without the energy Baumgarte's bias pumps in or out. Steps that needed the projection
// of 5. are not SHAKE (the force direction is taken at t+h, which also damps the fast modes).
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/joints/JointDef.hpp>
#include <coulomb/joints/JointPrimitives.hpp>
#include <coulomb/joints/RowBlock.hpp>
#include <coulomb/joints/Stabilization.hpp>
#include <coulomb/solvers/direct/BlockLdlt.hpp>
#include <coulomb/solvers/direct/BlockLu.hpp>
#include <coulomb/solvers/direct/SparseLdlt.hpp>

#include <Eigen/Core>

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace coulomb::integrators {

struct PredictedStateResult {
  int iterations = 0;         // correction solves performed
  double initialError = 0.0;  // [m or rad] largest predicted |C| before any correction
  double finalError = 0.0;    // [m or rad] largest predicted |C| after the last one
  bool converged = false;     // finalError <= tolerance
  std::vector<joints::RowVector> impulses;  // per joint: accumulated p on its equality rows [N s]
  // Per joint: J_B^T p, the impulse on body B along the start-of-step rows the correction acted on
  // (linear [N s], then angular [N m s], world axes).
  std::vector<Eigen::Matrix<double, 6, 1>> impulsesOnB;
};

/// The pose body i reaches when integratePositions(state, h) runs with its current velocities
/// (static bodies and the world do not move). Does not modify `state`.
geometry::Pose predictPose(const geometry::BodyState& state, std::size_t i, double h);

/// What the correction keeps between steps: the structure of its matrices (which joints share a
/// body, the pattern of B, its LU and LDL^T analyses), rebuilt only when the joints, their row
/// counts or which of their bodies are dynamic change, and every vector of the iteration. With it
/// a steady step's correction allocates nothing.
struct PredictedStateWorkspace {
  struct Touch {  // a joint's side on a dynamic body; sorted by body, then joint, then side
    std::uint32_t body = 0;
    int joint = 0;
    bool sideB = false;
  };
  struct Term {  // block `pair` += rows of touch `row` times M^-1 (rows of touch `column`)^T
    int row = 0, column = 0, pair = 0;
  };
  std::vector<int> key, keyScratch;  // rows and dynamic bodies per joint (structure's identity)
  std::vector<int> offset;
  std::vector<Touch> touches;
  std::vector<std::uint32_t> bodies;       // the touched bodies, ascending
  std::vector<int> sideBody;               // per joint side: its index in `bodies`, or -1
  std::vector<std::pair<int, int>> pairs;  // (a, b): joints sharing a body (and every (a, a))
  std::vector<int> pairValues;             // start of block (a, b) in `b`, rows(a) x rows(b)
  std::vector<int> diagonalPair;           // (a, a) per joint
  std::vector<Term> terms;
  // Every joint with 3 rows (ball joints: chains, ropes, ragdoll shoulders): B is factorized by
  // 3 x 3 blocks (solvers/direct/BlockLu) and the projection's J M^-1 J^T likewise (BlockLdlt),
  // several times cheaper than entry by entry. The pattern's pairs are the blocks (a, b), a > b,
  // of `pairs`; their indices in `pairs`, and those of the mirrored blocks (b, a).
  bool byBlocks = false;
  std::vector<std::pair<int, int>> blockPairs;
  std::vector<int> blockSource, blockMirrorSource;
  solvers::BlockLuOf<3> newtonBlockLu;
  solvers::BlockLdltOf<3> symmetricBlockLdlt;
  std::vector<solvers::BlockLdltOf<3>::Block> blockDiagonal, blockCoupling, blockMirrored;
  // Otherwise entry by entry: the off-diagonal entries (r, c), r > c, of the pattern, the
  // positions in `b` of B(r, c), B(c, r) and of the diagonal; and the lower triangle of the
  // symmetric J M^-1 J^T (diagonal included) as (row, column, position in `b`).
  std::vector<std::pair<int, int>> scalarPairs;
  std::vector<int> scalarSource, scalarMirrorSource, scalarDiagonalSource;
  solvers::BlockLuOf<1> newtonLu;
  std::vector<solvers::BlockLuOf<1>::Block> scalarDiagonal, scalarCoupling, scalarMirrored;
  std::vector<int> symmetricRows, symmetricCols, symmetricSource;
  solvers::SparseLdlt symmetricLdlt;
  // The iteration.
  std::vector<joints::ConstraintEval> start, predicted, predictedBefore, along;
  std::vector<Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>> minvJt;  // per touch
  std::vector<double> b, entries;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> saved;
  std::vector<geometry::Pose> predictedPoses;  // per touched body (as `bodies`), per pass
  Eigen::VectorXd drift, driftBefore, total, p, target;
};

/// Corrects the velocities of the dynamic bodies of `joints` (bodies index `state`; an invalid
/// id is the world). The joints must be valid (validateJointDef) and name live bodies.
PredictedStateResult correctPredictedState(geometry::BodyState& state,
                                           std::span<const joints::JointDef* const> joints,
                                           const joints::PredictedStateSettings& settings,
                                           double h);
/// The same with the caller's workspace and result (reused: the World's joint stage).
void correctPredictedState(geometry::BodyState& state,
                           std::span<const joints::JointDef* const> joints,
                           const joints::PredictedStateSettings& settings, double h,
                           PredictedStateWorkspace& workspace, PredictedStateResult& result);

/// The second half of the symmetric (RATTLE) step of an island of ideal joints (Andersen 1983;
/// Hairer, Lubich, Wanner, "Geometric Numerical Integration", sec. VII.1.4; docs/tuning.md,
/// "Chains keep their energy"): the velocities of the joints' dynamic bodies projected onto
/// J(x) v = 0 at their current poses in the kinetic metric, (J M^-1 J^T + eps I) p = -J v and
/// v += M^-1 J^T p (eps as in the correction). One linear solve: J is fixed. `result` gets the
/// impulses p, `initialError` the largest |J v| before [m/s or rad/s], `converged` false only when
/// the factorization fails (the velocities are then unchanged).
void projectJointVelocities(geometry::BodyState& state,
                            std::span<const joints::JointDef* const> joints,
                            PredictedStateWorkspace& workspace, PredictedStateResult& result);

}  // namespace coulomb::integrators
