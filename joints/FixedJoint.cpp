#include <coulomb/joints/FixedJoint.hpp>

namespace coulomb::joints {

ConstraintEval fixedJointConstraint(const JointFrame& frameA, const JointFrame& frameB,
                                    const geometry::Pose& poseA, const geometry::Pose& poseB) {
  const WorldFrame a = toWorld(frameA, poseA), b = toWorld(frameB, poseB);
  ConstraintEval out(6);
  setPointRows(out, 0, a, b);
  setOrientationRows(out, 3, a, b);
  return out;
}

}  // namespace coulomb::joints
