#pragma once
// Universal (Cardan) joint: the anchors coincide (3 rows) and the cross keeps the arm axis_A of
// body A perpendicular to the arm normal_B of body B: C_3 = axis_A . normal_B = 0 (JointPrimitives
// "dot"). Two relative rotations stay free (about axis_A and about normal_B). Set the frames so
// that axis_A . normal_B = 0 at creation (e.g. identical frames: x . y = 0).
#include <coulomb/joints/JointPrimitives.hpp>

namespace coulomb::joints {

ConstraintEval universalJointConstraint(const JointFrame& frameA, const JointFrame& frameB,
                                        const geometry::Pose& poseA, const geometry::Pose& poseB);

}  // namespace coulomb::joints
