#include <gtest/gtest.h>
#include <coulomb/integrators/FreeMotion.hpp>

using namespace coulomb;
using geometry::MotionType;

TEST(FreeMotion, GravityAndForceChangeOnlyDynamicVelocities) {
  geometry::BodyState state;
  const Eigen::Matrix3d inertia = Eigen::Vector3d(2.0, 2.0, 4.0).asDiagonal();
  state.assign(0, MotionType::Dynamic, {}, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d::Zero(), 2.0,
               inertia);
  state.assign(1, MotionType::Kinematic, {}, Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 1),
               0.0, Eigen::Matrix3d::Zero());
  state.assign(2, MotionType::Static, {}, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 0.0,
               Eigen::Matrix3d::Zero());
  state.forces[0] = Eigen::Vector3d(4.0, 0.0, 0.0);
  state.torques[0] = Eigen::Vector3d(0.0, 0.0, 8.0);
  state.forces[1] = Eigen::Vector3d(100.0, 0.0, 0.0);
  const Eigen::Vector3d g(0.0, 0.0, -10.0);
  integrators::predictFreeVelocities(state, g, 0.1);
  // v* = v + h (g + F/m) = (1 + 0.1 * 2, 0, -1)
  EXPECT_TRUE(state.linearVelocities[0].isApprox(Eigen::Vector3d(1.2, 0.0, -1.0)));
  // omega* = h I^-1 tau = 0.1 * 8 / 4
  EXPECT_TRUE(state.angularVelocities[0].isApprox(Eigen::Vector3d(0.0, 0.0, 0.2)));
  EXPECT_EQ(state.linearVelocities[1], Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(state.linearVelocities[2], Eigen::Vector3d::Zero());
}
