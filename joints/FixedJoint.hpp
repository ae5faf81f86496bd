#pragma once
// Fixed (weld) joint: anchors and orientations coincide (6 rows): the point rows
// C_0..2 = p_B - p_A and three perpendicularity rows between the frame axes,
// C_3 = axis_A . normal_B, C_4 = normal_A . binormal_B, C_5 = binormal_A . axis_B, which vanish
// when the frames are aligned and whose angular Jacobians there are the three frame axes
// (JointPrimitives "dot"; survey sec. 2.1.3: any smooth C with full-rank dC/dx will do).
#include <coulomb/joints/JointPrimitives.hpp>

namespace coulomb::joints {

ConstraintEval fixedJointConstraint(const JointFrame& frameA, const JointFrame& frameB,
                                    const geometry::Pose& poseA, const geometry::Pose& poseB);

}  // namespace coulomb::joints
