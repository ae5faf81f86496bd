// Every joint type's Jacobian against central finite differences of its C(x), at random poses
// (away from C = 0 too), and C = 0 with the frames matched.
#include <gtest/gtest.h>
#include <coulomb/geometry/Quaternion.hpp>
#include <coulomb/joints/JointConstraint.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <random>

using namespace coulomb;
using joints::JointType;

namespace {

using Twist = Eigen::Matrix<double, 6, 1>;

/// The pose moved by a twist perturbation (dx, dtheta) as the rows assume: x + dx,
/// R <- exp(dtheta) R (world-frame rotation).
geometry::Pose perturbed(const geometry::Pose& p, const Twist& d) {
  return {geometry::quaternionExp(d.tail<3>()) * p.rotation, p.position + d.head<3>()};
}

joints::JointFrame randomFrame(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  joints::JointFrame f;
  f.anchor = Eigen::Vector3d(u(rng), u(rng), u(rng));
  const Eigen::Quaterniond q = Eigen::Quaterniond::UnitRandom();
  f.axis = q * Eigen::Vector3d::UnitX();
  f.normal = q * Eigen::Vector3d::UnitY();
  return f;
}

geometry::Pose randomPose(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return {Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d(u(rng), u(rng), u(rng))};
}

class JointJacobian : public ::testing::TestWithParam<JointType> {};

}  // namespace

TEST_P(JointJacobian, MatchesFiniteDifferencesOfC) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    joints::JointDef def;
    def.type = GetParam();
    def.frameA = randomFrame(rng);
    def.frameB = randomFrame(rng);
    const geometry::Pose a = randomPose(rng), b = randomPose(rng);
    const joints::ConstraintEval eval = joints::evaluateJoint(def, a, b);
    ASSERT_EQ(eval.rows(), joints::equalityRowCount(def.type));
    const double eps = 1e-6;
    for (int side = 0; side < 2; ++side)
      for (int k = 0; k < 6; ++k) {
        const Twist d = Twist::Unit(k) * eps;
        const auto at = [&](const Twist& t) {
          return side == 0 ? joints::evaluateJoint(def, perturbed(a, t), b).error
                           : joints::evaluateJoint(def, a, perturbed(b, t)).error;
        };
        const joints::RowVector numeric = (at(d) - at(-d)) / (2.0 * eps);
        const joints::RowVector analytic = (side == 0 ? eval.jacobianA : eval.jacobianB).col(k);
        EXPECT_LT((numeric - analytic).norm(), 1e-7)
            << joints::jointTypeName(def.type) << " side " << side << " column " << k;
      }
  }
}

TEST_P(JointJacobian, InPlaceEvaluationEqualsTheReturnedOne) {
  // The correction's per-pass form (storage reused, a ball joint's anchors only) gives the same
  // bits as evaluateJoint, whatever the row count the storage held before.
  std::mt19937 rng(5);
  for (int trial = 0; trial < 10; ++trial) {
    joints::JointDef def;
    def.type = GetParam();
    def.frameA = randomFrame(rng);
    def.frameB = randomFrame(rng);
    const geometry::Pose a = randomPose(rng), b = randomPose(rng);
    const joints::ConstraintEval expected = joints::evaluateJoint(def, a, b);
    joints::ConstraintEval reused(trial % 2 == 0 ? 6 : 1);
    reused.jacobianA.setConstant(std::nan(""));
    reused.jacobianB.setConstant(std::nan(""));
    joints::evaluateJoint(def, a, b, reused);
    EXPECT_EQ(reused.error, expected.error) << joints::jointTypeName(def.type);
    EXPECT_EQ(reused.jacobianA, expected.jacobianA) << joints::jointTypeName(def.type);
    EXPECT_EQ(reused.jacobianB, expected.jacobianB) << joints::jointTypeName(def.type);
  }
}

TEST_P(JointJacobian, ErrorIsZeroWhenTheFramesCoincide) {
  std::mt19937 rng(11);
  joints::JointDef def;
  def.type = GetParam();
  def.frameA = randomFrame(rng);
  const geometry::Pose a = randomPose(rng), b = randomPose(rng);
  // Frame B = frame A carried into B's COM frame.
  def.frameB.anchor = b.applyInverse(a.apply(def.frameA.anchor));
  def.frameB.axis = b.rotation.conjugate() * (a.rotation * def.frameA.axis);
  def.frameB.normal = b.rotation.conjugate() * (a.rotation * def.frameA.normal);
  EXPECT_LT(joints::evaluateJoint(def, a, b).error.norm(), 1e-14);
  if (auto c = joints::jointCoordinate(def, a, b)) {
    EXPECT_NEAR(c->value, 0.0, 1e-14);
  }
}

TEST_P(JointJacobian, CoordinateRateMatchesFiniteDifferences) {
  if (!joints::hasCoordinate(GetParam())) GTEST_SKIP() << "no coordinate";
  std::mt19937 rng(5);
  joints::JointDef def;
  def.type = GetParam();
  def.frameA = randomFrame(rng);
  const geometry::Pose a = randomPose(rng);
  // B in a pose that satisfies the joint: rotated about / slid along the joint axis.
  const Eigen::Vector3d axisWorld = a.rotation * def.frameA.axis;
  const Eigen::Vector3d anchorWorld = a.apply(def.frameA.anchor);
  const geometry::Pose offset = randomPose(rng);
  def.frameB.anchor = offset.applyInverse(anchorWorld);
  def.frameB.axis = offset.rotation.conjugate() * axisWorld;
  def.frameB.normal = offset.rotation.conjugate() * (a.rotation * def.frameA.normal);
  const double moved = 0.3;
  geometry::Pose b = offset;
  if (def.type == JointType::Hinge) {
    const Eigen::Quaterniond turn(Eigen::AngleAxisd(moved, axisWorld));
    b = {turn * offset.rotation, anchorWorld + turn * (offset.position - anchorWorld)};
  } else {
    b.position += moved * axisWorld;
  }
  const auto c = joints::jointCoordinate(def, a, b);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->value, moved, 1e-12);
  const double eps = 1e-6;
  for (int k = 0; k < 6; ++k) {
    const Twist d = Twist::Unit(k) * eps;
    const double numericB = (joints::jointCoordinate(def, a, perturbed(b, d))->value -
                             joints::jointCoordinate(def, a, perturbed(b, -d))->value) /
                            (2 * eps);
    const double numericA = (joints::jointCoordinate(def, perturbed(a, d), b)->value -
                             joints::jointCoordinate(def, perturbed(a, -d), b)->value) /
                            (2 * eps);
    EXPECT_NEAR(numericB, c->jacobianB[k], 1e-7) << "column " << k;
    EXPECT_NEAR(numericA, c->jacobianA[k], 1e-7) << "column " << k;
  }
}

INSTANTIATE_TEST_SUITE_P(AllTypes, JointJacobian,
                         ::testing::Values(JointType::Ball, JointType::Hinge, JointType::Prismatic,
                                           JointType::Fixed, JointType::Universal),
                         [](const auto& info) { return joints::jointTypeName(info.param); });

TEST(JointConstraint, ErrorSplitsLinearAndAngularRows) {
  joints::JointDef def;  // hinge about y, identical frames but anchor B 2 mm above A
  def.type = JointType::Hinge;
  def.frameA.axis = def.frameB.axis = Eigen::Vector3d::UnitY();
  def.frameA.normal = def.frameB.normal = Eigen::Vector3d::UnitZ();
  def.frameB.anchor = Eigen::Vector3d(0.0, 0.0, -0.002);
  const joints::JointError gap =
      joints::jointError(def, joints::evaluateJoint(def, geometry::Pose{}, geometry::Pose{}));
  EXPECT_NEAR(gap.linear, 0.002, 1e-15);
  EXPECT_NEAR(gap.angular, 0.0, 1e-15);
  // Tilting B by 0.02 rad about x moves its axis off y: |normal_A . axis_B| = sin(0.02).
  const geometry::Pose tilted{geometry::axisRotation(0, 0.02), Eigen::Vector3d::Zero()};
  def.frameB.anchor.setZero();
  const joints::JointError tilt =
      joints::jointError(def, joints::evaluateJoint(def, geometry::Pose{}, tilted));
  EXPECT_NEAR(tilt.linear, 0.0, 1e-15);
  EXPECT_NEAR(tilt.angular, std::sin(0.02), 1e-12);
}
