#pragma once
// Ball (spherical) joint: the anchors coincide, C = p_B - p_A = 0 (3 rows), leaving the three
// relative rotations free. Survey (Bender, Erleben, Trinkle 2014) sec. 4.4.1, Fig. 11 (the
// ball joint of the impulse-based correction); rows and Jacobian: JointPrimitives "point".
#include <coulomb/joints/JointPrimitives.hpp>

namespace coulomb::joints {

ConstraintEval ballJointConstraint(const JointFrame& frameA, const JointFrame& frameB,
                                   const geometry::Pose& poseA, const geometry::Pose& poseB);

}  // namespace coulomb::joints
