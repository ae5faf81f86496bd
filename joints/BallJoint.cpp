#include <coulomb/joints/BallJoint.hpp>

namespace coulomb::joints {

ConstraintEval ballJointConstraint(const JointFrame& frameA, const JointFrame& frameB,
                                   const geometry::Pose& poseA, const geometry::Pose& poseB) {
  ConstraintEval out(3);
  setPointRows(out, 0, toWorld(frameA, poseA), toWorld(frameB, poseB));
  return out;
}

}  // namespace coulomb::joints
