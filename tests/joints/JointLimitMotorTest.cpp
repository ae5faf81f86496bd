// Limit, motor and friction rows on a hinge coordinate (no solver: the rows themselves).
#include <gtest/gtest.h>
#include <coulomb/joints/EmitRows.hpp>
#include <coulomb/joints/JointLimitMotor.hpp>

using namespace coulomb;

namespace {

joints::JointDef hinge() {
  joints::JointDef def;
  def.type = joints::JointType::Hinge;
  def.bodyB = {0, 0};
  def.frameA.axis = def.frameB.axis = Eigen::Vector3d::UnitY();
  def.frameA.normal = def.frameB.normal = Eigen::Vector3d::UnitZ();
  return def;
}

joints::JointCoordinate coordinateAt(double angle) {
  joints::JointCoordinate c;
  c.value = angle;
  c.jacobianA << 0, 0, 0, 0, -1, 0;
  c.jacobianB << 0, 0, 0, 0, 1, 0;
  return c;
}

}  // namespace

TEST(JointLimitMotor, FarFromTheStopsNoLimitRow) {
  joints::JointDef def = hinge();
  def.limit = {true, -1.0, 1.0, 0.0};
  std::vector<joints::RowBlock> rows;
  EXPECT_EQ(joints::appendLimitMotorRows(def, coordinateAt(0.0), 2.0, 0.2, 0.01, rows), 0);
}

TEST(JointLimitMotor, ApproachingTheUpperStopGivesASpeculativeRow) {
  joints::JointDef def = hinge();
  def.limit = {true, -1.0, 1.0, 0.0};
  std::vector<joints::RowBlock> rows;
  // 0.01 rad from the upper stop, closing at 2 rad/s: reached within the step.
  ASSERT_EQ(joints::appendLimitMotorRows(def, coordinateAt(0.99), 2.0, 0.2, 0.01, rows), 1);
  const joints::RowBlock& limit = rows.front();
  EXPECT_EQ(limit.kind, joints::RowKind::Unilateral);
  ASSERT_EQ(limit.rows(), 1);
  EXPECT_EQ(limit.jacobianB(0, 4), -1.0);          // upper stop: u = -rate + bias >= 0
  EXPECT_NEAR(limit.bias[0], 0.01 / 0.01, 1e-12);  // may close the 0.01 rad gap, not cross it
}

TEST(JointLimitMotor, CrossedStopPushesBackAndRestitutionBounces) {
  joints::JointDef def = hinge();
  def.limit = {true, -1.0, 1.0, 0.5};
  std::vector<joints::RowBlock> rows;
  joints::appendLimitMotorRows(def, coordinateAt(-1.02), -1.0, 0.2, 0.01, rows);
  EXPECT_NEAR(rows.front().bias[0], 0.2 * -0.02 / 0.01, 1e-12);  // Baumgarte push-out
  rows.clear();
  joints::appendLimitMotorRows(def, coordinateAt(-0.995), -3.0, 0.2, 0.01, rows);
  EXPECT_NEAR(rows.front().bias[0], 0.5 * -3.0, 1e-12);  // u+ >= -e u-
}

TEST(JointLimitMotor, MotorAndFrictionAreBoundedRows) {
  joints::JointDef def = hinge();
  def.motor = {true, 2.5, 10.0};
  std::vector<joints::RowBlock> rows;
  ASSERT_EQ(joints::appendLimitMotorRows(def, coordinateAt(0.0), 0.0, 0.2, 0.01, rows), 1);
  EXPECT_EQ(rows[0].kind, joints::RowKind::Bounded);
  EXPECT_EQ(rows[0].bias[0], -2.5);
  EXPECT_EQ(rows[0].lower[0], -0.1);
  EXPECT_EQ(rows[0].upper[0], 0.1);
  def.motor.enabled = false;
  def.friction = 3.0;
  rows.clear();
  ASSERT_EQ(joints::appendLimitMotorRows(def, coordinateAt(0.0), 0.0, 0.2, 0.01, rows), 1);
  EXPECT_EQ(rows[0].bias[0], 0.0);
  EXPECT_NEAR(rows[0].upper[0], 0.03, 1e-15);
}

TEST(EmitRows, BaumgarteBiasIsBetaTimesErrorOverH) {
  joints::JointDef def = hinge();
  def.frameB.anchor = Eigen::Vector3d(0.0, 0.0, 0.01);  // B's anchor 1 cm above A's
  joints::JointBodies bodies;
  joints::Stabilization policy;
  policy.method = joints::StabilizationMethod::Baumgarte;
  policy.baumgarte.beta = 0.5;
  std::vector<joints::RowBlock> rows;
  ASSERT_EQ(joints::emitJointRows(def, bodies, policy, 0.01, rows), 1);
  ASSERT_EQ(rows[0].rows(), 5);
  EXPECT_EQ(rows[0].kind, joints::RowKind::Equality);
  EXPECT_NEAR(rows[0].bias[2], 0.5 * 0.01 / 0.01, 1e-12);
  policy.method = joints::StabilizationMethod::PredictedState;
  rows.clear();
  joints::emitJointRows(def, bodies, policy, 0.01, rows);
  EXPECT_TRUE(rows[0].bias.isZero());
}
