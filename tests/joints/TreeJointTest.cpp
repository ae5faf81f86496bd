// Joint models: coordinate counts, neutral configurations, joint motions and subspaces.
#include <gtest/gtest.h>
#include <coulomb/joints/tree/TreeJoint.hpp>

#include <array>
#include <stdexcept>

using namespace coulomb::joints::tree;

TEST(TreeJoint, CountsAndNeutralConfigurations) {
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  EXPECT_EQ(TreeJoint::revolute("r", {}, z).nv(), 1);
  EXPECT_EQ(TreeJoint::prismatic("p", {}, z).nq(), 1);
  EXPECT_EQ(TreeJoint::fixed("f", {}).nv(), 0);
  EXPECT_EQ(TreeJoint::spherical("s", {}).nq(), 4);
  EXPECT_EQ(TreeJoint::spherical("s", {}).nv(), 3);
  EXPECT_EQ(TreeJoint::floating("x").nq(), 7);
  EXPECT_EQ(TreeJoint::floating("x").nv(), 6);
  EXPECT_EQ(TreeJoint::floating("x").neutralConfiguration()(3), 1.0);
}

TEST(TreeJoint, MotionsFollowTheAxis) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, 2) / 3.0;
  const coulomb::geometry::Pose turn =
      TreeJoint::revolute("r", {}, axis).jointMotion(std::array{0.3}.data());
  EXPECT_NEAR(Eigen::AngleAxisd(turn.rotation).angle(), 0.3, 1e-15);
  EXPECT_LE((Eigen::AngleAxisd(turn.rotation).axis() - axis).norm(), 1e-15);
  const coulomb::geometry::Pose slide =
      TreeJoint::prismatic("p", {}, axis).jointMotion(std::array{1.5}.data());
  EXPECT_LE((slide.position - 1.5 * axis).norm(), 1e-15);
  // A drifted quaternion is normalised.
  const std::array<double, 7> free{1, 2, 3, 2.0, 0.0, 0.0, 0.0};
  const coulomb::geometry::Pose pose = TreeJoint::floating("x").jointMotion(free.data());
  EXPECT_NEAR(pose.rotation.norm(), 1.0, 1e-15);
  EXPECT_EQ(pose.position, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(TreeJoint::prismatic("p", {}, axis).motionSubspace().col(0).tail<3>(), axis);
}

TEST(TreeJoint, ValidationNamesTheJoint) {
  try {
    TreeJoint::prismatic("rail", {}, Eigen::Vector3d(0, 0, 2)).validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rail"), std::string::npos);
  }
  TreeJoint limited = TreeJoint::revolute("knee", {}, Eigen::Vector3d::UnitX());
  limited.lower = 1.0;
  limited.upper = -1.0;
  EXPECT_THROW(limited.validate(), std::invalid_argument);
}
