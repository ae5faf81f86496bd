#pragma once
// Prismatic (slider) joint: the orientations coincide (3 "dot" rows, as FixedJoint) and anchor B
// stays on the line through anchor A along axis_A: C = normal_A . d = 0, binormal_A . d = 0 with
// d = p_B - p_A (JointPrimitives "along"; 5 rows in all). Coordinate: s = axis_A . d [m], whose
// exact rate row is the "along" row of axis_A.
#include <coulomb/joints/JointPrimitives.hpp>

namespace coulomb::joints {

ConstraintEval prismaticJointConstraint(const JointFrame& frameA, const JointFrame& frameB,
                                        const geometry::Pose& poseA, const geometry::Pose& poseB);

JointCoordinate prismaticDisplacement(const JointFrame& frameA, const JointFrame& frameB,
                                      const geometry::Pose& poseA, const geometry::Pose& poseB);

}  // namespace coulomb::joints
