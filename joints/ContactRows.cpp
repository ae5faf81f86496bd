#include <coulomb/joints/ContactRows.hpp>

#include <Eigen/Geometry>

namespace coulomb::joints {
namespace {

void setRow(RowBlock& block, int row, const ContactPointFrame& c, const Eigen::Vector3d& d) {
  const Eigen::Vector3d armA = c.point - c.centreA;
  const Eigen::Vector3d armB = c.point - c.centreB;
  block.jacobianA.row(row) << -d.transpose(), -armA.cross(d).transpose();
  block.jacobianB.row(row) << d.transpose(), armB.cross(d).transpose();
}

}  // namespace

RowBlock makeContactRows(const ContactPointFrame& contact) {
  const bool frictional = contact.friction > 0.0;
  const int rows = frictional ? 3 : 1;
  RowBlock block;
  block.kind = frictional ? RowKind::Contact3D : RowKind::Unilateral;
  block.bodyA = contact.bodyA;
  block.bodyB = contact.bodyB;
  block.jacobianA.resize(rows, 6);
  block.jacobianB.resize(rows, 6);
  block.bias = RowVector::Zero(rows);
  block.bias[0] = contact.normalVelocityBias;
  block.friction = contact.friction;
  block.sourceKey = contact.key;
  setRow(block, 0, contact, contact.normal);
  if (frictional) {
    setRow(block, 1, contact, contact.tangent1);
    setRow(block, 2, contact, contact.tangent2);
    block.bias.tail<2>() = contact.tangentVelocityBias;
  }
  return block;
}

}  // namespace coulomb::joints
