// Articulation construction: indices, sizes, and loud failures that name the link or joint.
#include <gtest/gtest.h>
#include <coulomb/joints/tree/Articulation.hpp>
#include <coulomb/joints/tree/TreeDynamics.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

using namespace coulomb::joints::tree;
using coulomb::geometry::Pose;
using coulomb::geometry::SpatialInertia;

namespace {
SpatialInertia unitBody() {
  return {1.0, Eigen::Vector3d::Zero(), 0.1 * Eigen::Matrix3d::Identity()};
}

void expectErrorMentioning(const std::vector<TreeLink>& links, const std::string& word) {
  try {
    const Articulation tree(links);
    FAIL() << "expected std::invalid_argument mentioning " << word;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(Articulation, IndicesFollowLinkOrder) {
  const Articulation tree(
      {{"base", -1, TreeJoint::floating("free"), unitBody()},
       {"ball", 0, TreeJoint::spherical("shoulder", {}), unitBody()},
       {"tool", 1, TreeJoint::fixed("flange", Pose::translation({0, 0, 1})), unitBody()},
       {"slider", 0, TreeJoint::prismatic("rail", {}, Eigen::Vector3d::UnitY()), unitBody()}});
  EXPECT_EQ(tree.nq(), 7 + 4 + 0 + 1);
  EXPECT_EQ(tree.nv(), 6 + 3 + 0 + 1);
  EXPECT_EQ(tree.qIndex(3), 11);
  EXPECT_EQ(tree.vIndex(3), 9);
  EXPECT_TRUE(tree.hasFloatingBase());
  EXPECT_EQ(tree.findLink("tool"), 2);
  EXPECT_EQ(tree.findLink("nothing"), -1);
  const Eigen::VectorXd q = tree.neutralConfiguration();
  EXPECT_EQ(q(3), 1.0);  // floating quaternion w
  EXPECT_EQ(q(7), 1.0);  // spherical quaternion w
  EXPECT_EQ(q.sum(), 2.0);
}

TEST(Articulation, BadModelsFailWithTheLinkOrJointName) {
  expectErrorMentioning(
      {{"arm", -1, TreeJoint::revolute("elbow", {}, Eigen::Vector3d(1, 1, 0)), unitBody()}},
      "elbow");
  expectErrorMentioning(
      {{"a", -1, TreeJoint::revolute("j", {}, Eigen::Vector3d::UnitZ()), unitBody()},
       {"late", 2, TreeJoint::revolute("k", {}, Eigen::Vector3d::UnitZ()), unitBody()},
       {"b", 0, TreeJoint::revolute("m", {}, Eigen::Vector3d::UnitZ()), unitBody()}},
      "late");
  SpatialInertia saddle = unitBody();
  saddle.inertiaAboutCom = Eigen::Vector3d(0.1, -0.1, 0.5).asDiagonal();  // not semidefinite
  expectErrorMentioning(
      {{"saddle", -1, TreeJoint::revolute("j", {}, Eigen::Vector3d::UnitZ()), saddle}},
      "positive semidefinite");
  SpatialInertia negative = unitBody();
  negative.mass = -1.0;
  expectErrorMentioning({{"antimatter", -1, TreeJoint::fixed("j", {}), negative}}, "antimatter");
  SpatialInertia nan = unitBody();
  nan.centerOfMass.x() = std::nan("");
  expectErrorMentioning({{"ghost", -1, TreeJoint::fixed("j", {}), nan}}, "ghost");
  Pose broken;
  broken.position.y() = std::nan("");
  expectErrorMentioning({{"l", -1, TreeJoint::fixed("mount", broken), unitBody()}}, "mount");
  TreeJoint damped = TreeJoint::revolute("damper", {}, Eigen::Vector3d::UnitZ());
  damped.damping = -1.0;
  expectErrorMentioning({{"l", -1, damped, unitBody()}}, "damper");
}

TEST(Articulation, TensorsBreakingTheTriangleInequalityAreAllowed) {
  // Positive definite but I1 + I2 < I3: no mass distribution has these moments, yet ABA needs
  // only definiteness (docs/articulations.md); CAD-exported URDFs are full of them.
  SpatialInertia flat = unitBody();
  flat.inertiaAboutCom = Eigen::Vector3d(0.1, 0.1, 0.5).asDiagonal();
  const Articulation tree(
      {{"plate", -1, TreeJoint::revolute("j", {}, Eigen::Vector3d::UnitZ()), flat}},
      Eigen::Vector3d::Zero());
  // About z through the COM: qdd = tau / Izz, the file's 0.5 and not a "repaired" moment.
  EXPECT_DOUBLE_EQ(forwardDynamics(tree, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1),
                                   Eigen::VectorXd::Ones(1))[0],
                   2.0);
}

TEST(Articulation, MasslessFramesAreAllowed) {
  const Articulation tree(
      {{"frame", -1, TreeJoint::fixed("weld", {}), SpatialInertia{}},
       {"arm", 0, TreeJoint::revolute("j", {}, Eigen::Vector3d::UnitZ()), unitBody()}});
  EXPECT_EQ(tree.nv(), 1);
}
