#include <gtest/gtest.h>
#include <coulomb/geometry/BodyState.hpp>

using namespace coulomb::geometry;

TEST(BodyState, AssignComputesInverseMassAndWorldInertia) {
  BodyState state;
  Pose pose;
  pose.rotation = Eigen::AngleAxisd(EIGEN_PI / 2, Eigen::Vector3d::UnitZ());
  state.assign(0, MotionType::Dynamic, pose, Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0, 0), 2.0,
               Eigen::Vector3d(1, 2, 3).asDiagonal());
  EXPECT_DOUBLE_EQ(state.inverseMasses[0], 0.5);
  // Body x (moment 1) now points along world y.
  EXPECT_NEAR(state.worldInverseInertias[0](1, 1), 1.0, 1e-12);
  EXPECT_NEAR(state.worldInverseInertias[0](0, 0), 0.5, 1e-12);
  // omega along world x = body -y: L = 2 omega.
  EXPECT_TRUE(state.angularMomentum(0).isApprox(Eigen::Vector3d(2, 0, 0), 1e-12));
  EXPECT_NEAR(state.kineticEnergy(0), 1.0, 1e-12);
}

TEST(BodyState, NonDynamicBodiesHaveInfiniteMass) {
  BodyState state;
  state.assign(3, MotionType::Kinematic, {}, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d::Zero(), 5.0,
               Eigen::Matrix3d::Identity());
  ASSERT_EQ(state.size(), 4u);
  EXPECT_EQ(state.inverseMasses[3], 0.0);
  EXPECT_EQ(state.alive[0], 0);  // gap slots stay free
  EXPECT_FALSE(state.isDynamic(3));
  EXPECT_EQ(state.kineticEnergy(3), 0.0);
}

TEST(BodyState, HashSeesEveryBitAndSkipsFreeSlots) {
  BodyState a;
  a.assign(0, MotionType::Dynamic, {}, Eigen::Vector3d(1, 2, 3), Eigen::Vector3d::Zero(), 1.0,
           Eigen::Matrix3d::Identity());
  BodyState b = a;
  EXPECT_EQ(stateHash(a), stateHash(b));
  b.linearVelocities[0].x() = std::nextafter(1.0, 2.0);
  EXPECT_NE(stateHash(a), stateHash(b));
  BodyState c = a;
  c.assign(1, MotionType::Dynamic, {}, Eigen::Vector3d(1, 2, 3), Eigen::Vector3d::Zero(), 1.0,
           Eigen::Matrix3d::Identity());
  c.clear(1);
  EXPECT_EQ(stateHash(a), stateHash(c));
}
