#include <coulomb/joints/tree/TreeRowBlocks.hpp>

#include <Eigen/Geometry>

#include <algorithm>

namespace coulomb::joints::tree {

RowBlock jointRateRow(const TreeRowFrame& tree, int link, double sign) {
  // Exactly sign * qd_link after the joint-space transform: a revolute joint's rate is the
  // relative angular velocity along its axis, a prismatic one's the velocity of the child origin
  // relative to the parent's point there.
  const TreeJoint& joint = tree.model.link(link).joint;
  const int parent = tree.model.parent(link);
  const auto at = [](auto span, int i) { return span[static_cast<std::size_t>(i)]; };
  const Eigen::Vector3d axis = at(tree.linkPoses, link).rotation * joint.axis;  // world
  RowBlock block;
  block.kind = RowKind::Equality;
  block.bodyB = at(tree.linkBodies, link);
  if (parent >= 0) block.bodyA = at(tree.linkBodies, parent);
  block.jacobianA = RowJacobian::Zero(1, 6);
  block.jacobianB = RowJacobian::Zero(1, 6);
  if (joint.type == TreeJointType::Revolute || joint.type == TreeJointType::Continuous) {
    block.jacobianB.row(0).tail<3>() = sign * axis.transpose();
    block.jacobianA.row(0).tail<3>() = -sign * axis.transpose();
  } else {
    const Eigen::Vector3d lever =
        at(tree.linkPoses, link).position -
        (parent >= 0 ? at(tree.linkPoses, parent).position : Eigen::Vector3d::Zero());
    block.jacobianB.row(0).head<3>() = sign * axis.transpose();
    block.jacobianA.row(0) << -sign * axis.transpose(), -sign * lever.cross(axis).transpose();
  }
  block.bias = RowVector::Zero(1);
  return block;
}

RowBlock limitRow(const TreeRowFrame& tree, int link, bool lower, double h, double warmStart) {
  const TreeJoint& joint = tree.model.link(link).joint;
  RowBlock block = jointRateRow(tree, link, lower ? 1.0 : -1.0);
  block.kind = RowKind::Unilateral;
  const double q = tree.q[tree.model.qIndex(link)];
  const double distance = lower ? q - joint.lower : joint.upper - q;
  block.bias =
      RowVector::Constant(1, distance >= 0.0 ? distance / h : tree.errorReduction * distance / h);
  block.warmStart = RowVector::Constant(1, warmStart);
  return block;
}

RowBlock motorRow(const TreeRowFrame& tree, const JointMotorDesc& motor, double h,
                  double warmStart) {
  double velocity = motor.target;
  if (motor.mode == JointMotorMode::Position) {
    const double q = tree.q[tree.model.qIndex(motor.link)];
    velocity = std::clamp(motor.positionGain * (motor.target - q) / h, -motor.maxVelocity,
                          motor.maxVelocity);
  }
  RowBlock block = jointRateRow(tree, motor.link, 1.0);
  block.kind = RowKind::Bounded;
  block.bias = RowVector::Constant(1, -velocity);
  block.lower = RowVector::Constant(1, -motor.maxEffort * h);
  block.upper = RowVector::Constant(1, motor.maxEffort * h);
  block.warmStart = RowVector::Constant(1, warmStart);
  return block;
}

RowBlock frictionRow(const TreeRowFrame& tree, int link, double friction, double h,
                     double warmStart) {
  RowBlock block = jointRateRow(tree, link, 1.0);
  block.kind = RowKind::Bounded;
  block.lower = RowVector::Constant(1, -friction * h);
  block.upper = RowVector::Constant(1, friction * h);
  block.warmStart = RowVector::Constant(1, warmStart);
  return block;
}

RowBlock couplingRow(const TreeRowFrame& tree, const JointCouplingDesc& coupling, double h,
                     double warmStart) {
  const int f = coupling.follower, l = coupling.leader;
  const Articulation& model = tree.model;
  const double error =
      tree.q[model.qIndex(f)] - coupling.multiplier * tree.q[model.qIndex(l)] - coupling.offset;
  const double rate = tree.qd[model.vIndex(f)] - coupling.multiplier * tree.qd[model.vIndex(l)];
  RowBlock block;
  block.kind = RowKind::Equality;
  block.bodyA = tree.linkBodies[static_cast<std::size_t>(f)];
  block.bodyB = tree.linkBodies[static_cast<std::size_t>(l)];
  block.jacobianA = RowJacobian::Zero(1, 6);
  block.jacobianB = RowJacobian::Zero(1, 6);
  block.bias = RowVector::Constant(1, rate + tree.errorReduction * error / h);
  block.warmStart = RowVector::Constant(1, warmStart);
  return block;
}

Eigen::RowVectorXd couplingJointRow(const Articulation& model, const JointCouplingDesc& coupling) {
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(model.nv());
  row[model.vIndex(coupling.follower)] += 1.0;
  row[model.vIndex(coupling.leader)] -= coupling.multiplier;
  return row;
}

RowBlock closureRow(const TreeRowFrame& tree, const LoopClosureDesc& closure,
                    const Eigen::Vector3d& proxyPositionA, const Eigen::Vector3d& proxyPositionB,
                    double h, const Eigen::Vector3d& warmStart) {
  const auto pose = [&](int link) { return tree.linkPoses[static_cast<std::size_t>(link)]; };
  const Eigen::Vector3d pA = pose(closure.linkA).apply(closure.anchorA);
  const bool world = closure.linkB < 0;
  const Eigen::Vector3d pB = world ? closure.anchorB : pose(closure.linkB).apply(closure.anchorB);
  RowBlock block;
  block.kind = RowKind::Equality;
  block.bodyA = tree.linkBodies[static_cast<std::size_t>(closure.linkA)];
  if (!world) block.bodyB = tree.linkBodies[static_cast<std::size_t>(closure.linkB)];
  const Eigen::Vector3d rA = pA - proxyPositionA;
  const Eigen::Vector3d rB = world ? Eigen::Vector3d::Zero() : Eigen::Vector3d(pB - proxyPositionB);
  const int k = static_cast<int>(std::count(closure.axes.begin(), closure.axes.end(), true));
  block.jacobianA = RowJacobian::Zero(k, 6);
  block.jacobianB = RowJacobian::Zero(k, 6);
  block.bias.resize(k);
  block.warmStart.resize(k);
  int row = 0;
  for (int axis = 0; axis < 3; ++axis) {
    if (!closure.axes[static_cast<std::size_t>(axis)]) continue;
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(axis);
    // u = e . (v_B(pB) - v_A(pA)); e . (w x r) = w . (r x e).
    block.jacobianA.row(row) << -e.transpose(), -rA.cross(e).transpose();
    block.jacobianB.row(row) << e.transpose(), rB.cross(e).transpose();
    block.bias[row] = tree.errorReduction * e.dot(pB - pA) / h;  // Baumgarte on the gap
    block.warmStart[row] = warmStart[axis];
    ++row;
  }
  return block;
}

}  // namespace coulomb::joints::tree
