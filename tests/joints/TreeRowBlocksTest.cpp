// The rows of a tree's constraints (joints/tree/TreeRowBlocks) mapped into joint space the way the
// assembler maps them (J_side * twistJacobian(link, proxy origin), summed over the sides): a joint
// rate row is exactly sign * e_v, a coupling's given row is qd_f - m qd_l, and a loop closure's
// row is the relative point velocity (finite differences of the anchor positions).
#include <gtest/gtest.h>
#include <coulomb/joints/tree/TreeKinematics.hpp>
#include <coulomb/joints/tree/TreeRowBlocks.hpp>

#include "RandomTrees.hpp"

#include <vector>

using namespace coulomb::joints::tree;
using coulomb::geometry::BodyId;
using coulomb::joints::RowBlock;
using coulomb::joints::RowKind;
using randomtree::RandomSource;

namespace {

struct Proxies {
  std::vector<BodyId> bodies;  // proxy of link i is body i
  TreeKinematics kinematics;
};

Proxies proxiesOf(const Articulation& tree, const Eigen::VectorXd& q) {
  Proxies p;
  for (int i = 0; i < tree.linkCount(); ++i)
    p.bodies.push_back(BodyId{static_cast<std::uint32_t>(i), 0});
  p.kinematics = forwardKinematics(tree, q);
  return p;
}

// The block's joint-space rows: each side through the twist Jacobian of its link about the
// proxy's origin (the link frame, ArticulationStage::updateProxies).
Eigen::MatrixXd jointSpace(const Articulation& tree, const Proxies& p, const RowBlock& block) {
  Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(block.rows(), tree.nv());
  for (const bool sideB : {false, true}) {
    const BodyId& body = sideB ? block.bodyB : block.bodyA;
    if (!body.valid()) continue;
    const int link = static_cast<int>(body.index);
    const auto& jac = sideB ? block.jacobianB : block.jacobianA;
    rows += jac * twistJacobian(tree, p.kinematics, link, p.kinematics.worldPoses[link].position);
  }
  return rows;
}

bool oneDof(const Articulation& tree, int link) {
  const TreeJointType type = tree.link(link).joint.type;
  return type == TreeJointType::Revolute || type == TreeJointType::Continuous ||
         type == TreeJointType::Prismatic;
}

}  // namespace

TEST(TreeRowBlocks, JointRateRowIsTheJointVelocity) {
  int checked = 0, prismatic = 0;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    RandomSource random(seed);
    const Articulation tree = randomtree::randomTree(random, {8, seed % 2 == 0, false});
    const Eigen::VectorXd q = randomtree::randomConfiguration(tree, random);
    const Eigen::VectorXd qd = randomtree::randomVector(tree.nv(), random, 1.0);
    const Proxies p = proxiesOf(tree, q);
    const TreeRowFrame frame{tree, p.bodies, p.kinematics.worldPoses, q, qd, 0.2};
    for (int link = 0; link < tree.linkCount(); ++link) {
      if (!oneDof(tree, link)) continue;
      for (const double sign : {1.0, -1.0}) {
        const Eigen::MatrixXd row = jointSpace(tree, p, jointRateRow(frame, link, sign));
        Eigen::RowVectorXd expected = Eigen::RowVectorXd::Zero(tree.nv());
        expected[tree.vIndex(link)] = sign;
        EXPECT_LE((row.row(0) - expected).norm(), 1e-12) << "seed " << seed << " link " << link;
      }
      ++checked;
      prismatic += tree.link(link).joint.type == TreeJointType::Prismatic ? 1 : 0;
    }
  }
  EXPECT_GT(checked, 20);
  EXPECT_GT(prismatic, 0);  // both branches of jointRateRow ran
}

TEST(TreeRowBlocks, LimitMotorAndFrictionRowsCarryTheirModel) {
  const coulomb::geometry::SpatialInertia unit{1.0, Eigen::Vector3d::Zero(),
                                               Eigen::Matrix3d::Identity()};
  TreeJoint shoulder = TreeJoint::revolute("shoulder", {}, Eigen::Vector3d::UnitZ());
  shoulder.lower = -0.5;
  shoulder.upper = 0.4;
  const Articulation tree({{"upper", -1, shoulder, unit}});
  const Eigen::VectorXd qd = Eigen::VectorXd::Constant(1, 0.3);
  const double h = 0.01;
  const int link = 0;
  for (const double qi : {0.1, -0.52}) {  // apart from the lower stop, then past it
    const Eigen::VectorXd q = Eigen::VectorXd::Constant(1, qi);
    const Proxies p = proxiesOf(tree, q);
    const TreeRowFrame frame{tree, p.bodies, p.kinematics.worldPoses, q, qd, 0.25};
    const RowBlock lower = limitRow(frame, link, true, h, 0.5);
    EXPECT_EQ(lower.kind, RowKind::Unilateral);
    EXPECT_NEAR(lower.bias[0], qi > -0.5 ? (qi + 0.5) / h : 0.25 * (qi + 0.5) / h, 1e-12);
    EXPECT_DOUBLE_EQ(lower.warmStart[0], 0.5);
    const RowBlock upper = limitRow(frame, link, false, h, 0.0);
    EXPECT_NEAR(upper.bias[0], (0.4 - qi) / h, 1e-12);
    EXPECT_LE((jointSpace(tree, p, upper).row(0) + jointSpace(tree, p, lower).row(0)).norm(),
              1e-12);
  }
  const double qi = 0.1;
  const Eigen::VectorXd q = Eigen::VectorXd::Constant(1, qi);
  const Proxies p = proxiesOf(tree, q);
  const TreeRowFrame frame{tree, p.bodies, p.kinematics.worldPoses, q, qd, 0.25};

  // Position motor: target velocity gain (target - q) / h, clamped; effort bound maxEffort h.
  JointMotorDesc motor{link, JointMotorMode::Position, qi + 0.1, 30.0, 0.2, 1.5};
  RowBlock m = motorRow(frame, motor, h, 0.0);
  EXPECT_EQ(m.kind, RowKind::Bounded);
  EXPECT_DOUBLE_EQ(m.bias[0], -1.5);  // 0.2 * 0.1 / 0.01 = 2 rad/s, clamped to 1.5
  EXPECT_DOUBLE_EQ(m.lower[0], -0.3);
  EXPECT_DOUBLE_EQ(m.upper[0], 0.3);
  motor.mode = JointMotorMode::Velocity;
  motor.target = -0.7;
  m = motorRow(frame, motor, h, 0.0);
  EXPECT_DOUBLE_EQ(m.bias[0], 0.7);

  const RowBlock friction = frictionRow(frame, link, 4.0, h, 0.01);
  EXPECT_EQ(friction.kind, RowKind::Bounded);
  EXPECT_DOUBLE_EQ(friction.bias[0], 0.0);
  EXPECT_DOUBLE_EQ(friction.upper[0], 0.04);
  EXPECT_DOUBLE_EQ(friction.lower[0], -0.04);
}

TEST(TreeRowBlocks, CouplingRowAndItsBias) {
  RandomSource random(5);
  const Articulation tree = randomtree::randomTree(random, {7, false, false});
  const Eigen::VectorXd q = randomtree::randomConfiguration(tree, random);
  const Eigen::VectorXd qd = randomtree::randomVector(tree.nv(), random, 1.0);
  const Proxies p = proxiesOf(tree, q);
  const TreeRowFrame frame{tree, p.bodies, p.kinematics.worldPoses, q, qd, 0.2};
  std::vector<int> links;
  for (int i = 0; i < tree.linkCount(); ++i)
    if (oneDof(tree, i)) links.push_back(i);
  ASSERT_GE(links.size(), 2u);
  const JointCouplingDesc coupling{links[1], links[0], -2.0, 0.3};
  const Eigen::RowVectorXd row = couplingJointRow(tree, coupling);
  const double h = 0.01;
  const RowBlock block = couplingRow(frame, coupling, h, 0.0);
  // The bias is J v* plus Baumgarte on the position error.
  const double error = q[tree.qIndex(links[1])] + 2.0 * q[tree.qIndex(links[0])] - 0.3;
  EXPECT_NEAR(block.bias[0], row.dot(qd) + 0.2 * error / h, 1e-12);
  EXPECT_EQ(row[tree.vIndex(links[1])], 1.0);
  EXPECT_EQ(row[tree.vIndex(links[0])], 2.0);
  EXPECT_EQ(block.jacobianA.norm() + block.jacobianB.norm(), 0.0);  // the given row carries it
}

TEST(TreeRowBlocks, ClosureRowIsTheRelativeAnchorVelocity) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    RandomSource random(seed);
    const Articulation tree = randomtree::randomTree(random, {6, false, false});
    const Eigen::VectorXd q = randomtree::randomConfiguration(tree, random);
    const Eigen::VectorXd qd = randomtree::randomVector(tree.nv(), random, 1.0);
    const Proxies p = proxiesOf(tree, q);
    const TreeRowFrame frame{tree, p.bodies, p.kinematics.worldPoses, q, qd, 0.2};
    const LoopClosureDesc closure{
        tree.linkCount() - 1, random.vector(0.3), 0, random.vector(0.3), {true, false, true}};
    const auto& poses = p.kinematics.worldPoses;
    const RowBlock block = closureRow(frame, closure, poses[closure.linkA].position,
                                      poses[closure.linkB].position, 0.01, Eigen::Vector3d::Zero());
    ASSERT_EQ(block.rows(), 2);
    // Finite differences of e . (pB - pA) along qd (1-DOF and fixed joints only: q moves by qd).
    bool plain = true;
    for (int i = 0; i < tree.linkCount(); ++i)
      plain = plain && tree.link(i).joint.nq() == tree.link(i).joint.nv();
    if (!plain) continue;
    const double eps = 1e-6;
    const TreeKinematics ahead = forwardKinematics(tree, q + eps * qd);
    const TreeKinematics behind = forwardKinematics(tree, q - eps * qd);
    const auto gap = [&](const TreeKinematics& k) {
      return Eigen::Vector3d(k.worldPoses[closure.linkB].apply(closure.anchorB) -
                             k.worldPoses[closure.linkA].apply(closure.anchorA));
    };
    const Eigen::Vector3d rate = (gap(ahead) - gap(behind)) / (2 * eps);
    const Eigen::VectorXd u = jointSpace(tree, p, block) * qd;
    EXPECT_NEAR(u[0], rate.x(), 1e-7) << "seed " << seed;
    EXPECT_NEAR(u[1], rate.z(), 1e-7) << "seed " << seed;
    // Baumgarte on the gap.
    EXPECT_NEAR(block.bias[0], 0.2 * gap(p.kinematics).x() / 0.01, 1e-12);
  }
}
