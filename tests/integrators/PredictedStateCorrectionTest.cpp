// Bender's predicted-state correction (survey sec. 4.4.1): the corrected velocities move the
// bodies onto the joint manifold at t+h, by impulses along the start-of-step Jacobian only.
#include <gtest/gtest.h>
#include <coulomb/integrators/PositionUpdate.hpp>
#include <coulomb/integrators/PredictedStateCorrection.hpp>
#include <coulomb/joints/JointConstraint.hpp>

using namespace coulomb;
using geometry::MotionType;

namespace {

joints::JointDef ballToWorld(geometry::BodyId body, const Eigen::Vector3d& bodyAnchor) {
  joints::JointDef def;
  def.type = joints::JointType::Ball;
  def.bodyB = body;
  def.frameB.anchor = bodyAnchor;
  return def;
}

}  // namespace

TEST(PredictedStateCorrection, PendulumLandsOnItsCircle) {
  // Bob 1 m from the pivot swinging at 3 rad/s about y: x + h v and the rotation by 0.03 rad
  // leave the anchor 1 - cos(0.03) = 4.5e-4 m off the pivot; the correction pulls it back.
  geometry::BodyState state;
  state.assign(0, MotionType::Dynamic, geometry::Pose::translation({1, 0, 0}),
               Eigen::Vector3d(0, 0, -3), Eigen::Vector3d(0, 3, 0), 1.0,
               Eigen::Matrix3d::Identity() * 0.001);
  const joints::JointDef joint = ballToWorld({0, 0}, {-1, 0, 0});
  const joints::JointDef* list[] = {&joint};
  joints::PredictedStateSettings settings;
  settings.tolerance = 1e-12;
  const auto result = integrators::correctPredictedState(state, list, settings, 0.01);
  EXPECT_NEAR(result.initialError, 1 - std::cos(0.03), 1e-12);
  EXPECT_TRUE(result.converged);
  EXPECT_LE(result.finalError, 1e-12);
  EXPECT_GE(result.iterations, 1);
  EXPECT_LE(result.iterations, 10);
  integrators::integratePositions(state, 0.01);
  const Eigen::Vector3d anchor = state.poses[0].apply(Eigen::Vector3d(-1, 0, 0));
  EXPECT_LT(anchor.norm(), 1e-12);
  // The impulse acts along the start-of-step joint rows, i.e. on the bob's anchor along -x.
  EXPECT_GT(result.impulses[0].norm(), 0.0);
}

TEST(PredictedStateCorrection, ChainOfTwoClosesBothJointsAndKeepsMomentumFreeDirections) {
  // Two free links joined by a ball joint, no world: the correction impulses are internal, so
  // the total linear momentum is unchanged.
  geometry::BodyState state;
  const Eigen::Matrix3d inertia = Eigen::Vector3d(1e-3, 2e-3, 3e-3).asDiagonal();
  state.assign(0, MotionType::Dynamic, geometry::Pose::translation({0, 0, 0}),
               Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 5), 0.5, inertia);
  state.assign(1, MotionType::Dynamic, geometry::Pose::translation({1, 0, 0}),
               Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(1, 0, -4), 0.7, inertia);
  joints::JointDef joint;
  joint.bodyA = {0, 0};
  joint.bodyB = {1, 0};
  joint.frameA.anchor = {0.5, 0, 0};
  joint.frameB.anchor = {-0.5, 0, 0};
  const joints::JointDef* list[] = {&joint};
  const Eigen::Vector3d momentum =
      0.5 * state.linearVelocities[0] + 0.7 * state.linearVelocities[1];
  const auto result = integrators::correctPredictedState(state, list, {}, 0.01);
  EXPECT_TRUE(result.converged) << result.finalError;
  EXPECT_TRUE((0.5 * state.linearVelocities[0] + 0.7 * state.linearVelocities[1])
                  .isApprox(momentum, 1e-12));
  integrators::integratePositions(state, 0.01);
  EXPECT_LT(joints::evaluateJoint(joint, state.poses[0], state.poses[1]).error.norm(), 1e-10);
}

TEST(PredictedStateCorrection, StaticEndsAndNoJointsAreHarmless) {
  geometry::BodyState state;
  state.assign(0, MotionType::Static, {}, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 0.0,
               Eigen::Matrix3d::Zero());
  EXPECT_EQ(integrators::correctPredictedState(state, {}, {}, 0.01).iterations, 0);
  joints::JointDef joint = ballToWorld({0, 0}, {1, 0, 0});
  const joints::JointDef* list[] = {&joint};
  const auto result = integrators::correctPredictedState(state, list, {}, 0.01);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_TRUE(state.poses[0].position.isZero());
}

TEST(PredictedStateCorrection, PredictPoseMatchesIntegratePositions) {
  geometry::BodyState state;
  state.assign(0, MotionType::Dynamic, geometry::Pose::translation({1, 2, 3}),
               Eigen::Vector3d(0.3, -1, 2), Eigen::Vector3d(3, -2, 7), 2.0,
               Eigen::Vector3d(0.1, 0.2, 0.25).asDiagonal());
  const geometry::Pose predicted = integrators::predictPose(state, 0, 0.01);
  integrators::integratePositions(state, 0.01);
  EXPECT_EQ(predicted.position, state.poses[0].position);
  EXPECT_EQ(predicted.rotation.coeffs(), state.poses[0].rotation.coeffs());
}
