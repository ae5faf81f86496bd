#pragma once
// Impulse-based predicted-state correction of joint drift (Bender, Finkenzeller, Schmitt 2005;
// survey: Bender, Erleben, Trinkle 2014, sec. 4.4.1, Fig. 11 and the system J M^-1 J^T p = dv).
// After the velocity solve, for every joint with this policy:
//   1. predict the poses at t+h that integratePositions would produce from the current
//      velocities (x + h v; the torque-free DLM rotation for dynamic bodies);
//   2. evaluate each joint's C at the predicted poses: the drift d(t+h) the step would leave;
//   3. solve A p = -d/h with A = J M^-1 J^T (J at the start of the step, factored once:
//      sparse LDL^T, plus a tiny compliance eps I with eps = 1e-10 max diag(A) so redundant
//      rows, e.g. a closed loop of hinges, stay solvable; SOLVERS.md sec. 10) and apply
//      dv = M^-1 J^T p to the velocities;
//   4. repeat until every |C(t+h)| <= tolerance or the iteration cap;
//   5. if a pass stalls (|C| not halved: SHAKE has no root near, e.g. a heavy load on light
//      links), the remaining passes project along the rows at the predicted state instead.
// The converged velocity moves the bodies exactly onto the constraint manifold. With the
// velocity-level impulse of the solve along the same J^T, the whole step is the SHAKE
// discretisation (Ryckaert, Ciccotti, Berendsen 1977), which is symplectic: joint drift is
// removed without the energy Baumgarte's bias pumps in or out. Steps that needed the projection
// of 5. are not SHAKE (the force direction is taken at t+h, which also damps the fast modes).
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/joints/JointDef.hpp>
#include <coulomb/joints/RowBlock.hpp>
#include <coulomb/joints/Stabilization.hpp>

#include <span>
#include <vector>

namespace coulomb::integrators {

struct PredictedStateResult {
  int iterations = 0;         // correction solves performed
  double initialError = 0.0;  // [m or rad] largest predicted |C| before any correction
  double finalError = 0.0;    // [m or rad] largest predicted |C| after the last one
  bool converged = false;     // finalError <= tolerance
  std::vector<joints::RowVector> impulses;  // per joint: accumulated p on its equality rows [N s]
};

/// The pose body i reaches when integratePositions(state, h) runs with its current velocities
/// (static bodies and the world do not move). Does not modify `state`.
geometry::Pose predictPose(const geometry::BodyState& state, std::size_t i, double h);

/// Corrects the velocities of the dynamic bodies of `joints` (bodies index `state`; an invalid
/// id is the world). The joints must be valid (validateJointDef) and name live bodies.
PredictedStateResult correctPredictedState(geometry::BodyState& state,
                                           std::span<const joints::JointDef* const> joints,
                                           const joints::PredictedStateSettings& settings,
                                           double h);

}  // namespace coulomb::integrators
