#include <coulomb/joints/PrismaticJoint.hpp>

namespace coulomb::joints {

ConstraintEval prismaticJointConstraint(const JointFrame& frameA, const JointFrame& frameB,
                                        const geometry::Pose& poseA, const geometry::Pose& poseB) {
  const WorldFrame a = toWorld(frameA, poseA), b = toWorld(frameB, poseB);
  ConstraintEval out(5);
  setAlongRow(out, 0, a.normal, a, b);
  setAlongRow(out, 1, a.binormal, a, b);
  setOrientationRows(out, 2, a, b);
  return out;
}

JointCoordinate prismaticDisplacement(const JointFrame& frameA, const JointFrame& frameB,
                                      const geometry::Pose& poseA, const geometry::Pose& poseB) {
  const WorldFrame a = toWorld(frameA, poseA), b = toWorld(frameB, poseB);
  ConstraintEval along(1);
  setAlongRow(along, 0, a.axis, a, b);
  JointCoordinate c;
  c.value = along.error[0];
  c.jacobianA = along.jacobianA.row(0);
  c.jacobianB = along.jacobianB.row(0);
  return c;
}

}  // namespace coulomb::joints
