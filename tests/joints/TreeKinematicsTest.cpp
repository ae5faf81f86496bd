// Forward kinematics, link velocities and Jacobians of trees, against finite differences of the
// link poses along a joint-space motion.
#include <gtest/gtest.h>
#include <coulomb/geometry/Quaternion.hpp>
#include <coulomb/joints/tree/TreeKinematics.hpp>

#include "RandomTrees.hpp"

#include <cmath>

using namespace coulomb::joints::tree;
using randomtree::RandomSource;

namespace {
/// q moved by eps * qd along each joint's manifold (body-frame velocities for quaternions).
Eigen::VectorXd displaced(const Articulation& tree, Eigen::VectorXd q, const Eigen::VectorXd& qd,
                          double eps) {
  for (int i = 0; i < tree.linkCount(); ++i) {
    const int iq = tree.qIndex(i), iv = tree.vIndex(i);
    const TreeJointType type = tree.link(i).joint.type;
    if (type == TreeJointType::Spherical || type == TreeJointType::Floating) {
      const int o = type == TreeJointType::Floating ? 3 : 0;
      const Eigen::Quaterniond r(q(iq + o), q(iq + o + 1), q(iq + o + 2), q(iq + o + 3));
      const Eigen::Quaterniond moved =
          r * coulomb::geometry::quaternionExp(eps * qd.segment<3>(iv));
      if (o == 3) q.segment<3>(iq) += eps * (r * qd.segment<3>(iv + 3));  // first order is enough
      q.segment<4>(iq + o) << moved.w(), moved.x(), moved.y(), moved.z();
    } else if (tree.link(i).joint.nv() == 1) {
      q(iq) += eps * qd(iv);
    }
  }
  return q;
}
}  // namespace

TEST(TreeKinematics, TwoLinkChainPoses) {
  coulomb::geometry::SpatialInertia unit{1.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()};
  const Articulation arm(
      {{"upper", -1, TreeJoint::revolute("shoulder", {}, Eigen::Vector3d::UnitZ()), unit},
       {"lower", 0,
        TreeJoint::prismatic("slide", coulomb::geometry::Pose::translation({1, 0, 0}),
                             Eigen::Vector3d::UnitX()),
        unit}});
  const TreeKinematics kin = forwardKinematics(arm, Eigen::Vector2d(M_PI / 2, 0.5));
  EXPECT_LE((kin.worldPoses[1].position - Eigen::Vector3d(0, 1.5, 0)).norm(), 1e-15);
  EXPECT_LE(
      (kin.worldPoses[1].rotation * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(),
      1e-15);
}

TEST(TreeKinematics, JacobiansMatchFiniteDifferencesOfPoses) {
  for (unsigned seed = 1; seed <= 12; ++seed) {
    RandomSource random(seed);
    const Articulation tree = randomtree::randomTree(random, {9, seed % 2 == 0, false});
    const Eigen::VectorXd q = randomtree::randomConfiguration(tree, random);
    const Eigen::VectorXd qd = randomtree::randomVector(tree.nv(), random, 1.0);
    const TreeKinematics kin = forwardKinematics(tree, q);
    const double eps = 1e-6;
    const TreeKinematics ahead = forwardKinematics(tree, displaced(tree, q, qd, eps));
    const TreeKinematics behind = forwardKinematics(tree, displaced(tree, q, qd, -eps));
    const std::vector<coulomb::geometry::Vector6d> v = linkVelocities(tree, kin, qd);
    for (int link = 0; link < tree.linkCount(); ++link) {
      const Eigen::Vector3d local = random.vector(0.5);
      const Eigen::Vector3d point = kin.worldPoses[link].apply(local);
      const Eigen::Vector3d numeric =
          (ahead.worldPoses[link].apply(local) - behind.worldPoses[link].apply(local)) / (2 * eps);
      const Eigen::Matrix<double, 6, Eigen::Dynamic> j = twistJacobian(tree, kin, link, point);
      EXPECT_LE((j.topRows<3>() * qd - numeric).norm(), 1e-7)
          << "seed " << seed << " link " << link;
      EXPECT_LE((pointVelocity(tree, kin, qd, link, point) - numeric).norm(), 1e-7);
      // Angular velocity: R(t + e) R(t - e)^T ~ exp(2 e [omega]x).
      const Eigen::Vector3d omegaNumeric =
          coulomb::geometry::quaternionLog(ahead.worldPoses[link].rotation *
                                           behind.worldPoses[link].rotation.conjugate()) /
          (2 * eps);
      EXPECT_LE((j.bottomRows<3>() * qd - omegaNumeric).norm(), 1e-7);
      // linkVelocities is the same motion in link coordinates.
      EXPECT_LE((kin.worldPoses[link].rotation * v[link].head<3>() - j.bottomRows<3>() * qd).norm(),
                1e-12);
    }
  }
}

TEST(TreeKinematics, ColumnsOfNonAncestorJointsAreZero) {
  coulomb::geometry::SpatialInertia unit{1.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()};
  const Articulation fork(
      {{"root", -1, TreeJoint::revolute("a", {}, Eigen::Vector3d::UnitZ()), unit},
       {"left", 0, TreeJoint::revolute("b", {}, Eigen::Vector3d::UnitX()), unit},
       {"right", 0, TreeJoint::revolute("c", {}, Eigen::Vector3d::UnitY()), unit}});
  const TreeKinematics kin = forwardKinematics(fork, Eigen::Vector3d(0.1, 0.2, 0.3));
  const auto j = pointJacobian(fork, kin, 1, Eigen::Vector3d(1, 1, 1));
  EXPECT_EQ(j.col(2).norm(), 0.0);
  EXPECT_GT(j.col(1).norm(), 0.0);
}
