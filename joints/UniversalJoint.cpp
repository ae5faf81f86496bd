#include <coulomb/joints/UniversalJoint.hpp>

namespace coulomb::joints {

ConstraintEval universalJointConstraint(const JointFrame& frameA, const JointFrame& frameB,
                                        const geometry::Pose& poseA, const geometry::Pose& poseB) {
  const WorldFrame a = toWorld(frameA, poseA), b = toWorld(frameB, poseB);
  ConstraintEval out(4);
  setPointRows(out, 0, a, b);
  setDotRow(out, 3, a.axis, b.normal);
  return out;
}

}  // namespace coulomb::joints
