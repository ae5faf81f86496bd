#include <gtest/gtest.h>
#include <coulomb/joints/ContactRows.hpp>

#include <Eigen/Geometry>

using namespace coulomb::joints;
using coulomb::geometry::BodyId;

namespace {
ContactPointFrame boxCornerOnGround() {
  ContactPointFrame c;
  c.bodyA = BodyId{};      // the world (ground)
  c.bodyB = BodyId{3, 0};  // a box whose centre is at (0, 0, 0.5)
  c.point = Eigen::Vector3d(0.5, -0.5, 0.0);
  c.centreB = Eigen::Vector3d(0.0, 0.0, 0.5);
  c.friction = 0.4;
  return c;
}

Eigen::Matrix<double, 6, 1> twist(const Eigen::Vector3d& v, const Eigen::Vector3d& w) {
  Eigen::Matrix<double, 6, 1> t;
  t << v, w;
  return t;
}
}  // namespace

TEST(ContactRows, FrictionalContactIsOneConeBlock) {
  const RowBlock block = makeContactRows(boxCornerOnGround());
  EXPECT_EQ(block.kind, RowKind::Contact3D);
  EXPECT_EQ(block.rows(), 3);
  EXPECT_DOUBLE_EQ(block.friction, 0.4);
}

TEST(ContactRows, FrictionlessContactIsOneUnilateralRow) {
  ContactPointFrame c = boxCornerOnGround();
  c.friction = 0.0;
  const RowBlock block = makeContactRows(c);
  EXPECT_EQ(block.kind, RowKind::Unilateral);
  EXPECT_EQ(block.rows(), 1);
}

TEST(ContactRows, RowsMeasureThePointVelocityOfBRelativeToA) {
  const ContactPointFrame c = boxCornerOnGround();
  const RowBlock block = makeContactRows(c);
  // Box B moves up at 1 m/s and spins about z at 2 rad/s: the corner's velocity is
  // v + w x (p - c) = (0,0,1) + (0,0,2) x (0.5,-0.5,-0.5) = (1, 1, 1).
  const Eigen::Vector3d v(0, 0, 1), w(0, 0, 2);
  const Eigen::Vector3d expected(1.0, 1.0, 1.0);
  const Eigen::VectorXd u = block.jacobianB * twist(v, w);
  EXPECT_NEAR(u[0], expected.dot(c.normal), 1e-15);  // separating: positive
  EXPECT_NEAR(u[1], expected.dot(c.tangent1), 1e-15);
  EXPECT_NEAR(u[2], expected.dot(c.tangent2), 1e-15);
  // The same motion given to A instead is seen with the opposite sign.
  const Eigen::VectorXd uA = block.jacobianA * twist(v, w);
  // A's centre is at the origin, so its arm differs: check against the formula directly.
  const Eigen::Vector3d pointVelocityA = v + w.cross(c.point - c.centreA);
  EXPECT_NEAR(uA[0], -pointVelocityA.dot(c.normal), 1e-15);
}
