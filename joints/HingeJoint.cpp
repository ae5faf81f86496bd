#include <coulomb/joints/HingeJoint.hpp>

#include <cmath>

namespace coulomb::joints {

ConstraintEval hingeJointConstraint(const JointFrame& frameA, const JointFrame& frameB,
                                    const geometry::Pose& poseA, const geometry::Pose& poseB) {
  const WorldFrame a = toWorld(frameA, poseA), b = toWorld(frameB, poseB);
  ConstraintEval out(5);
  setPointRows(out, 0, a, b);
  setDotRow(out, 3, a.normal, b.axis);
  setDotRow(out, 4, a.binormal, b.axis);
  return out;
}

JointCoordinate hingeAngle(const JointFrame& frameA, const JointFrame& frameB,
                           const geometry::Pose& poseA, const geometry::Pose& poseB) {
  const WorldFrame a = toWorld(frameA, poseA), b = toWorld(frameB, poseB);
  JointCoordinate c;
  c.value = std::atan2(a.axis.dot(a.normal.cross(b.normal)), a.normal.dot(b.normal));
  c.jacobianA << 0.0, 0.0, 0.0, -a.axis.transpose();
  c.jacobianB << 0.0, 0.0, 0.0, a.axis.transpose();
  return c;
}

}  // namespace coulomb::joints
