// The second half of the symmetric step (PredictedStateCorrection.hpp, projectJointVelocities).
#include <coulomb/integrators/JointRowSystem.hpp>
#include <coulomb/integrators/PredictedStateCorrection.hpp>

namespace coulomb::integrators {

using namespace joint_rows;

void projectJointVelocities(geometry::BodyState& state,
                            std::span<const joints::JointDef* const> joints,
                            PredictedStateWorkspace& w, PredictedStateResult& result) {
  const double compliance = resetAtCurrentPoses(state, joints, w, result, true);
  if (compliance <= 0.0) return;
  const auto jointCount = static_cast<int>(joints.size());
  // -J v: the bodies that are not touched (the world, static bodies) do not move.
  w.target.setZero(w.offset[jointCount]);
  for (const Workspace::Touch& t : w.touches) {
    const joints::RowJacobian& J = side(w.start, t);
    w.target.segment(w.offset[t.joint], J.rows()) -=
        J.leftCols<3>() * state.linearVelocities[t.body] +
        J.rightCols<3>() * state.angularVelocities[t.body];
  }
  result.initialError = w.target.cwiseAbs().maxCoeff();
  assemble(w.start, compliance, w);
  if (!solveSymmetric(w, w.p) || !w.p.allFinite()) {
    result.converged = false;
    result.finalError = result.initialError;
    return;
  }
  applyRowImpulses(state, w.start, w.p, w);
  result.iterations = 1;
  for (int j = 0; j < jointCount; ++j) {
    result.impulses[j] = w.p.segment(w.offset[j], w.start[j].rows());
    result.impulsesOnB[j] = w.start[j].jacobianB.transpose() * result.impulses[j];
  }
}

}  // namespace coulomb::integrators
