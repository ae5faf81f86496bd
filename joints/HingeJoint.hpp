#pragma once
// Hinge (revolute) joint: the anchors coincide (3 rows) and axis_B stays parallel to axis_A:
// C_3 = normal_A . axis_B = 0, C_4 = binormal_A . axis_B = 0 (JointPrimitives "dot"; survey
// sec. 2.1.3: a hinge needs five holonomic constraints). One rotation about axis_A stays free.
// Coordinate: the angle of normal_B about axis_A measured from normal_A,
//   theta = atan2(axis_A . (normal_A x normal_B), normal_A . normal_B),
// whose rate where C = 0 is axis_A . (omega_B - omega_A): row [0, -axis_A | 0, axis_A].
#include <coulomb/joints/JointPrimitives.hpp>

namespace coulomb::joints {

ConstraintEval hingeJointConstraint(const JointFrame& frameA, const JointFrame& frameB,
                                    const geometry::Pose& poseA, const geometry::Pose& poseB);

JointCoordinate hingeAngle(const JointFrame& frameA, const JointFrame& frameB,
                           const geometry::Pose& poseA, const geometry::Pose& poseB);

}  // namespace coulomb::joints
