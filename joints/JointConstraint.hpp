#pragma once
// Dispatch over the joint types: the equality constraint C(x) with its Jacobian, and the scalar
// coordinate of hinges and sliders. Every caller (row emission, predicted-state correction, drift
// reports, tests) goes through these two functions, so a joint's rows and its drift always agree.
#include <coulomb/joints/JointDef.hpp>
#include <coulomb/joints/JointPrimitives.hpp>

#include <optional>

namespace coulomb::joints {

/// C(x) and its Jacobian for `def` with the bodies at `poseA`, `poseB` (COM poses in world;
/// identity for the world).
ConstraintEval evaluateJoint(const JointDef& def, const geometry::Pose& poseA,
                             const geometry::Pose& poseB);
/// The same into `out`, reusing its storage: the iterations that re-evaluate every joint per
/// pass (the predicted-state correction) neither zero nor copy k x 6 matrices, and a ball joint
/// computes only its anchors.
void evaluateJoint(const JointDef& def, const geometry::Pose& poseA, const geometry::Pose& poseB,
                   ConstraintEval& out);

/// Hinge angle or slider displacement; nullopt for types without a coordinate.
std::optional<JointCoordinate> jointCoordinate(const JointDef& def, const geometry::Pose& poseA,
                                               const geometry::Pose& poseB);

/// Largest |C| of the point/along rows [m] and of the dot rows [-, ~rad] of an evaluation.
struct JointError {
  double linear = 0.0;
  double angular = 0.0;
};
JointError jointError(const JointDef& def, const ConstraintEval& eval);

}  // namespace coulomb::joints
