#include <gtest/gtest.h>
#include <coulomb/geometry/Quaternion.hpp>
#include <coulomb/integrators/FreeMotion.hpp>
#include <coulomb/integrators/PositionUpdate.hpp>

#include <cmath>
#include <numbers>

using namespace coulomb;
using geometry::MotionType;

TEST(PositionUpdate, KinematicBodyFollowsItsVelocityByTheExpMap) {
  geometry::BodyState state;
  state.assign(0, MotionType::Kinematic, {}, Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0, 0, 1),
               0.0, Eigen::Matrix3d::Zero());
  for (int i = 0; i < 100; ++i) integrators::integratePositions(state, 0.01);
  EXPECT_TRUE(state.poses[0].position.isApprox(Eigen::Vector3d(1, 2, 3), 1e-12));
  EXPECT_TRUE(state.poses[0].rotation.isApprox(geometry::axisRotation(2, 1.0), 1e-12));
  EXPECT_EQ(state.angularVelocities[0], Eigen::Vector3d(0, 0, 1));
}

TEST(PositionUpdate, StaticBodyNeverMoves) {
  geometry::BodyState state;
  geometry::Pose pose = geometry::Pose::translation(Eigen::Vector3d(1, 1, 1));
  state.assign(0, MotionType::Static, pose, Eigen::Vector3d(5, 5, 5), Eigen::Vector3d(1, 1, 1), 0,
               Eigen::Matrix3d::Zero());
  integrators::integratePositions(state, 0.1);
  EXPECT_EQ(state.poses[0].position, pose.position);
}

TEST(PositionUpdate, ProjectileMatchesClosedFormToRoundOff) {
  // Semi-implicit Euler: x_n = x0 + v0 t + g h^2 n(n+1)/2, i.e. the closed form shifted by
  // g h t / 2 (its first-order error, known exactly).
  geometry::BodyState state;
  const Eigen::Vector3d v0(3.0, 0.0, 4.0), g(0.0, 0.0, -9.81);
  state.assign(0, MotionType::Dynamic, {}, v0, Eigen::Vector3d::Zero(), 1.0,
               Eigen::Matrix3d::Identity());
  const double h = 0.01;
  const int n = 80;
  for (int i = 0; i < n; ++i) {
    integrators::predictFreeVelocities(state, g, h);
    integrators::integratePositions(state, h);
  }
  const double t = n * h;
  const Eigen::Vector3d exact = v0 * t + 0.5 * g * t * t;
  const Eigen::Vector3d expected = exact + 0.5 * g * h * t;
  EXPECT_LT((state.poses[0].position - expected).norm(), 1e-12);
  EXPECT_TRUE(state.linearVelocities[0].isApprox(v0 + g * t, 1e-12));
}

TEST(PositionUpdate, ABodyWithThreeEqualMomentsTurnsAboutItsConstantAngularVelocity) {
  // A spinning cube (three equal moments, tilted start): the torque-free flow keeps w and L = I w,
  // and after t the orientation is exp(t w) q0. A body with unequal moments (the same w) takes
  // the general path and must not keep w (the test can tell the two apart).
  const Eigen::Vector3d w(3.0, -1.0, 2.0);
  const Eigen::Quaterniond q0 = geometry::axisRotation(0, 0.3) * geometry::axisRotation(2, 1.1);
  geometry::BodyState state;
  state.assign(0, MotionType::Dynamic, geometry::Pose{q0, Eigen::Vector3d::Zero()},
               Eigen::Vector3d::Zero(), w, 2.0, (1.0 / 600.0) * Eigen::Matrix3d::Identity());
  state.assign(1, MotionType::Dynamic, geometry::Pose{q0, Eigen::Vector3d::Zero()},
               Eigen::Vector3d::Zero(), w, 2.0, Eigen::Vector3d(1.0, 2.0, 3.0).asDiagonal());
  const Eigen::Vector3d momentum1 = state.angularMomentum(1);
  const double h = 0.01;
  const int n = 250;
  for (int i = 0; i < n; ++i) integrators::integratePositions(state, h);
  EXPECT_EQ(state.angularVelocities[0], w);
  const Eigen::Quaterniond exact = geometry::quaternionExp(n * h * w) * q0;
  EXPECT_LT(state.poses[0].rotation.angularDistance(exact), 1e-12);
  const Eigen::Matrix3d r = state.poses[0].rotationMatrix();
  EXPECT_TRUE((r * state.bodyInverseInertias[0] * r.transpose())
                  .isApprox(state.worldInverseInertias[0], 1e-12));
  EXPECT_GT((state.angularVelocities[1] - w).norm(), 1e-3);
  EXPECT_LT((state.angularMomentum(1) - momentum1).norm(), 1e-12 * momentum1.norm());
}
