// Joint validation: every bad input gets a message naming the joint and the value.
#include <gtest/gtest.h>
#include <coulomb/joints/JointDef.hpp>

#include <limits>

using namespace coulomb;
using joints::JointType;

namespace {

joints::JointDef goodHinge() {
  joints::JointDef def;
  def.name = "knee";
  def.type = JointType::Hinge;
  def.bodyA = {0, 0};
  def.bodyB = {1, 0};
  return def;
}

std::string problemOf(const joints::JointDef& def) {
  const auto bad = joints::validateJointDef(def);
  return bad ? *bad : "";
}

}  // namespace

TEST(JointDef, AcceptsAGoodJointAndAWorldEnd) {
  EXPECT_EQ(problemOf(goodHinge()), "");
  joints::JointDef toWorld = goodHinge();
  toWorld.bodyA = {};
  EXPECT_EQ(problemOf(toWorld), "");
}

TEST(JointDef, RejectsAJointToItselfAndTwoWorldEnds) {
  joints::JointDef def = goodHinge();
  def.bodyB = def.bodyA;
  EXPECT_NE(problemOf(def).find("joint 'knee' (hinge): joins a body to itself"), std::string::npos);
  def.bodyA = def.bodyB = {};
  EXPECT_NE(problemOf(def).find("both ends are the world"), std::string::npos);
}

TEST(JointDef, RejectsNonUnitAndNonPerpendicularAxes) {
  joints::JointDef def = goodHinge();
  def.frameA.axis = {1.2, 0, 0};
  EXPECT_NE(problemOf(def).find("frameA.axis must have unit length (got 1.2)"), std::string::npos);
  def = goodHinge();
  def.frameB.normal = {0, 0.5, 0};
  EXPECT_NE(problemOf(def).find("frameB.normal must have unit length"), std::string::npos);
  def = goodHinge();
  def.frameB.normal = Eigen::Vector3d(1, 1, 0).normalized();
  EXPECT_NE(problemOf(def).find("perpendicular"), std::string::npos);
}

TEST(JointDef, RejectsNaNFrames) {
  joints::JointDef def = goodHinge();
  def.frameA.anchor.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(problemOf(def).find("frameA must be finite"), std::string::npos);
}

TEST(JointDef, RejectsBadLimitsMotorsFrictionAndThresholds) {
  joints::JointDef def = goodHinge();
  def.limit = {true, 1.0, -1.0, 0.0};
  EXPECT_NE(problemOf(def).find("lower <= upper"), std::string::npos);
  def = goodHinge();
  def.limit = {true, -1.0, 1.0, 1.5};
  EXPECT_NE(problemOf(def).find("restitution"), std::string::npos);
  def = goodHinge();
  def.motor = {true, 1.0, -2.0};
  EXPECT_NE(problemOf(def).find("max force >= 0"), std::string::npos);
  def = goodHinge();
  def.friction = -1.0;
  EXPECT_NE(problemOf(def).find("friction must be finite"), std::string::npos);
  def = goodHinge();
  def.motor = {true, 1.0, 2.0};
  def.friction = 1.0;
  EXPECT_NE(problemOf(def).find("both a motor and friction"), std::string::npos);
  def = goodHinge();
  def.breakForce = 0.0;
  EXPECT_NE(problemOf(def).find("break force"), std::string::npos);
  def = goodHinge();
  def.type = JointType::Ball;
  def.motor = {true, 1.0, 2.0};
  EXPECT_NE(problemOf(def).find("need a hinge or prismatic joint"), std::string::npos);
  def = goodHinge();
  def.stabilization = joints::Stabilization{};
  def.stabilization->baumgarte.beta = 2.0;
  EXPECT_NE(problemOf(def).find("baumgarte beta"), std::string::npos);
}

TEST(JointDef, NamesRoundTrip) {
  for (auto t : {JointType::Ball, JointType::Hinge, JointType::Prismatic, JointType::Fixed,
                 JointType::Universal})
    EXPECT_EQ(joints::jointTypeFromName(joints::jointTypeName(t)), t);
  EXPECT_FALSE(joints::jointTypeFromName("revolute"));
  EXPECT_EQ(joints::stabilizationMethodFromName("predicted_state"),
            joints::StabilizationMethod::PredictedState);
  EXPECT_FALSE(joints::stabilizationMethodFromName("erp"));
}
