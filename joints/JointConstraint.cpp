#include <coulomb/joints/BallJoint.hpp>
#include <coulomb/joints/FixedJoint.hpp>
#include <coulomb/joints/HingeJoint.hpp>
#include <coulomb/joints/JointConstraint.hpp>
#include <coulomb/joints/PrismaticJoint.hpp>
#include <coulomb/joints/UniversalJoint.hpp>

#include <algorithm>
#include <cmath>

namespace coulomb::joints {

ConstraintEval evaluateJoint(const JointDef& def, const geometry::Pose& poseA,
                             const geometry::Pose& poseB) {
  switch (def.type) {
    case JointType::Ball:
      return ballJointConstraint(def.frameA, def.frameB, poseA, poseB);
    case JointType::Hinge:
      return hingeJointConstraint(def.frameA, def.frameB, poseA, poseB);
    case JointType::Prismatic:
      return prismaticJointConstraint(def.frameA, def.frameB, poseA, poseB);
    case JointType::Fixed:
      return fixedJointConstraint(def.frameA, def.frameB, poseA, poseB);
    case JointType::Universal:
      return universalJointConstraint(def.frameA, def.frameB, poseA, poseB);
  }
  return ConstraintEval(0);
}

void evaluateJoint(const JointDef& def, const geometry::Pose& poseA, const geometry::Pose& poseB,
                   ConstraintEval& out) {
  if (def.type != JointType::Ball) {
    out = evaluateJoint(def, poseA, poseB);
    return;
  }
  // As toWorld, the anchors and arms only (setPointRows writes every entry of the 3 rows).
  WorldFrame a, b;
  a.arm = poseA.rotation * def.frameA.anchor;
  a.anchor = poseA.position + a.arm;
  b.arm = poseB.rotation * def.frameB.anchor;
  b.anchor = poseB.position + b.arm;
  out.error.resize(3);
  out.jacobianA.resize(3, 6);
  out.jacobianB.resize(3, 6);
  setPointRows(out, 0, a, b);
}

std::optional<JointCoordinate> jointCoordinate(const JointDef& def, const geometry::Pose& poseA,
                                               const geometry::Pose& poseB) {
  if (def.type == JointType::Hinge) return hingeAngle(def.frameA, def.frameB, poseA, poseB);
  if (def.type == JointType::Prismatic)
    return prismaticDisplacement(def.frameA, def.frameB, poseA, poseB);
  return std::nullopt;
}

JointError jointError(const JointDef& def, const ConstraintEval& eval) {
  // Linear rows: the first three (point rows) except for sliders, whose first two are "along".
  const int linearRows = def.type == JointType::Prismatic ? 2 : std::min(3, eval.rows());
  JointError e;
  for (int i = 0; i < eval.rows(); ++i) {
    double& target = i < linearRows ? e.linear : e.angular;
    target = std::max(target, std::abs(eval.error[i]));
  }
  return e;
}

}  // namespace coulomb::joints
