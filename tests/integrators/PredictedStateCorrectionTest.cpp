// Bender's predicted-state correction (survey sec. 4.4.1): the corrected velocities move the
// bodies onto the joint manifold at t+h, by impulses along the start-of-step Jacobian only.
#include <gtest/gtest.h>
#include <coulomb/integrators/PositionUpdate.hpp>
#include <coulomb/integrators/PredictedStateCorrection.hpp>
#include <coulomb/joints/JointConstraint.hpp>

#include <cmath>
#include <vector>

using namespace coulomb;
using geometry::MotionType;

namespace {

joints::JointDef ballToWorld(geometry::BodyId body, const Eigen::Vector3d& bodyAnchor) {
  joints::JointDef def;
  def.type = joints::JointType::Ball;
  def.bodyB = body;
  def.frameB.anchor = bodyAnchor;
  return def;
}

}  // namespace

TEST(PredictedStateCorrection, PendulumLandsOnItsCircle) {
  // Bob 1 m from the pivot swinging at 3 rad/s about y: x + h v and the rotation by 0.03 rad
  // leave the anchor 1 - cos(0.03) = 4.5e-4 m off the pivot; the correction pulls it back.
  geometry::BodyState state;
  state.assign(0, MotionType::Dynamic, geometry::Pose::translation({1, 0, 0}),
               Eigen::Vector3d(0, 0, -3), Eigen::Vector3d(0, 3, 0), 1.0,
               Eigen::Matrix3d::Identity() * 0.001);
  const joints::JointDef joint = ballToWorld({0, 0}, {-1, 0, 0});
  const joints::JointDef* list[] = {&joint};
  joints::PredictedStateSettings settings;
  settings.tolerance = 1e-12;
  const auto result = integrators::correctPredictedState(state, list, settings, 0.01);
  EXPECT_NEAR(result.initialError, 1 - std::cos(0.03), 1e-12);
  EXPECT_TRUE(result.converged);
  EXPECT_LE(result.finalError, 1e-12);
  EXPECT_GE(result.iterations, 1);
  EXPECT_LE(result.iterations, 10);
  integrators::integratePositions(state, 0.01);
  const Eigen::Vector3d anchor = state.poses[0].apply(Eigen::Vector3d(-1, 0, 0));
  EXPECT_LT(anchor.norm(), 1e-12);
  // The impulse acts along the start-of-step joint rows, i.e. on the bob's anchor along -x.
  EXPECT_GT(result.impulses[0].norm(), 0.0);
}

TEST(PredictedStateCorrection, ChainOfTwoClosesBothJointsAndKeepsMomentumFreeDirections) {
  // Two free links joined by a ball joint, no world: the correction impulses are internal, so
  // the total linear momentum is unchanged.
  geometry::BodyState state;
  const Eigen::Matrix3d inertia = Eigen::Vector3d(1e-3, 2e-3, 3e-3).asDiagonal();
  state.assign(0, MotionType::Dynamic, geometry::Pose::translation({0, 0, 0}),
               Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 5), 0.5, inertia);
  state.assign(1, MotionType::Dynamic, geometry::Pose::translation({1, 0, 0}),
               Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(1, 0, -4), 0.7, inertia);
  joints::JointDef joint;
  joint.bodyA = {0, 0};
  joint.bodyB = {1, 0};
  joint.frameA.anchor = {0.5, 0, 0};
  joint.frameB.anchor = {-0.5, 0, 0};
  const joints::JointDef* list[] = {&joint};
  const Eigen::Vector3d momentum =
      0.5 * state.linearVelocities[0] + 0.7 * state.linearVelocities[1];
  const auto result = integrators::correctPredictedState(state, list, {}, 0.01);
  EXPECT_TRUE(result.converged) << result.finalError;
  EXPECT_TRUE((0.5 * state.linearVelocities[0] + 0.7 * state.linearVelocities[1])
                  .isApprox(momentum, 1e-12));
  integrators::integratePositions(state, 0.01);
  EXPECT_LT(joints::evaluateJoint(joint, state.poses[0], state.poses[1]).error.norm(), 1e-10);
}

TEST(PredictedStateCorrection, FloatingLoopOfHingesClosesWithRedundantRows) {
  // Four free links on the sides of a square, joined at the corners by hinges about z: a planar
  // loop, 20 rows of which 3 are redundant (17 independent on 24 degrees of freedom). Rows of 5
  // go entry by entry (the scalar LU of B); the compliance keeps B regular on the redundant rows.
  // Spinning about z with a perturbation that the joints do not allow: the correction closes
  // every joint at t+h by Newton passes (the linear rate ~h omega / 2 of the rotation's
  // sensitivity, no projection needed), and its impulses are internal (linear momentum unchanged).
  geometry::BodyState state;
  const Eigen::Matrix3d inertia = Eigen::Vector3d(1e-3, 2e-2, 2e-2).asDiagonal();
  const double side = 1.0, spin = 0.5;
  const Eigen::Vector3d centres[4] = {{0, -0.5, 0}, {0.5, 0, 0}, {0, 0.5, 0}, {-0.5, 0, 0}};
  for (std::uint32_t i = 0; i < 4; ++i) {
    // Link i lies along its side: body x along the side (rotated by 90 degrees per link).
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.5 * M_PI * i, Eigen::Vector3d::UnitZ()));
    const Eigen::Vector3d omega(0.03 * (i % 2 == 0 ? 1 : -1), 0.02 * i, spin);
    const Eigen::Vector3d v = Eigen::Vector3d(0, 0, spin).cross(centres[i]) +
                              Eigen::Vector3d(0.1 * i, -0.05, 0.2 * (i % 3));
    state.assign(i, MotionType::Dynamic, geometry::Pose{q, centres[i]}, v, omega, 0.5 + 0.1 * i,
                 inertia);
  }
  std::vector<joints::JointDef> joints(4);
  for (std::uint32_t i = 0; i < 4; ++i) {
    joints::JointDef& def = joints[i];
    def.type = joints::JointType::Hinge;
    def.bodyA = {i, 0};
    def.bodyB = {(i + 1) % 4, 0};
    def.frameA.anchor = {0.5 * side, 0, 0};  // link i's end meets link i + 1's start
    def.frameB.anchor = {-0.5 * side, 0, 0};
    def.frameA.axis = def.frameB.axis = Eigen::Vector3d::UnitZ();
    def.frameA.normal = Eigen::Vector3d::UnitX();
    def.frameB.normal = Eigen::Vector3d::UnitY();  // the corner's right angle
  }
  std::vector<const joints::JointDef*> list;
  for (const auto& def : joints) {
    ASSERT_LT(joints::evaluateJoint(def, state.poses[def.bodyA.index], state.poses[def.bodyB.index])
                  .error.norm(),
              1e-12);  // closed at the start
    list.push_back(&def);
  }
  Eigen::Vector3d momentum = Eigen::Vector3d::Zero();
  for (std::uint32_t i = 0; i < 4; ++i)
    momentum += state.linearVelocities[i] / state.inverseMasses[i];
  joints::PredictedStateSettings settings;
  settings.tolerance = 1e-11;
  const geometry::BodyState before = state;
  const auto result = integrators::correctPredictedState(state, list, settings, 0.01);
  EXPECT_GT(result.initialError, 1e-4);  // the perturbation opens the joints
  EXPECT_TRUE(result.converged) << result.finalError;
  // Every velocity change is M^-1 J^T p along the start-of-step rows (SHAKE: Newton passes only;
  // a projection pass would push along the rows at the predicted poses). Round-off: the
  // compliance lets p grow along the redundant rows, where J^T p is zero.
  std::vector<Eigen::Vector3d> linear = before.linearVelocities, angular = before.angularVelocities;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const auto& def = joints[j];
    const joints::ConstraintEval start =
        joints::evaluateJoint(def, before.poses[def.bodyA.index], before.poses[def.bodyB.index]);
    for (const bool sideB : {false, true}) {
      const std::uint32_t body = sideB ? def.bodyB.index : def.bodyA.index;
      const joints::RowJacobian& rows = sideB ? start.jacobianB : start.jacobianA;
      linear[body] +=
          before.inverseMasses[body] * rows.leftCols<3>().transpose() * result.impulses[j];
      angular[body] +=
          before.worldInverseInertias[body] * rows.rightCols<3>().transpose() * result.impulses[j];
    }
  }
  for (std::uint32_t i = 0; i < 4; ++i) {
    EXPECT_LT((linear[i] - state.linearVelocities[i]).norm(), 1e-9) << "link " << i;
    EXPECT_LT((angular[i] - state.angularVelocities[i]).norm(), 1e-9) << "link " << i;
  }
  Eigen::Vector3d after = Eigen::Vector3d::Zero();
  for (std::uint32_t i = 0; i < 4; ++i) after += state.linearVelocities[i] / state.inverseMasses[i];
  EXPECT_LT((after - momentum).norm(), 1e-12);
  integrators::integratePositions(state, 0.01);
  for (const auto& def : joints)
    EXPECT_LT(joints::evaluateJoint(def, state.poses[def.bodyA.index], state.poses[def.bodyB.index])
                  .error.cwiseAbs()
                  .maxCoeff(),
              1e-11);
}

TEST(PredictedStateCorrection, StaticEndsAndNoJointsAreHarmless) {
  geometry::BodyState state;
  state.assign(0, MotionType::Static, {}, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 0.0,
               Eigen::Matrix3d::Zero());
  EXPECT_EQ(integrators::correctPredictedState(state, {}, {}, 0.01).iterations, 0);
  joints::JointDef joint = ballToWorld({0, 0}, {1, 0, 0});
  const joints::JointDef* list[] = {&joint};
  const auto result = integrators::correctPredictedState(state, list, {}, 0.01);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_TRUE(state.poses[0].position.isZero());
}

TEST(PredictedStateCorrection, PredictPoseMatchesIntegratePositions) {
  geometry::BodyState state;
  state.assign(0, MotionType::Dynamic, geometry::Pose::translation({1, 2, 3}),
               Eigen::Vector3d(0.3, -1, 2), Eigen::Vector3d(3, -2, 7), 2.0,
               Eigen::Vector3d(0.1, 0.2, 0.25).asDiagonal());
  const geometry::Pose predicted = integrators::predictPose(state, 0, 0.01);
  integrators::integratePositions(state, 0.01);
  EXPECT_EQ(predicted.position, state.poses[0].position);
  EXPECT_EQ(predicted.rotation.coeffs(), state.poses[0].rotation.coeffs());
}

namespace {

// Largest |J v| over the joints at the bodies' current poses.
double largestRowVelocity(const geometry::BodyState& state,
                          const std::vector<joints::JointDef>& joints) {
  double largest = 0.0;
  for (const joints::JointDef& def : joints) {
    const auto pose = [&](const geometry::BodyId& id) {
      return id.valid() ? state.poses[id.index] : geometry::Pose::identity();
    };
    const auto velocity = [&](const geometry::BodyId& id) {
      Eigen::Matrix<double, 6, 1> v = Eigen::Matrix<double, 6, 1>::Zero();
      if (id.valid()) v << state.linearVelocities[id.index], state.angularVelocities[id.index];
      return v;
    };
    const joints::ConstraintEval eval =
        joints::evaluateJoint(def, pose(def.bodyA), pose(def.bodyB));
    const Eigen::VectorXd rate =
        eval.jacobianA * velocity(def.bodyA) + eval.jacobianB * velocity(def.bodyB);
    largest = std::max(largest, rate.cwiseAbs().maxCoeff());
  }
  return largest;
}

double kineticEnergy(const geometry::BodyState& state) {
  double energy = 0.0;
  for (std::size_t i = 0; i < state.size(); ++i)
    energy += 0.5 * state.linearVelocities[i].squaredNorm() / state.inverseMasses[i] +
              0.5 * state.angularVelocities[i].dot(state.worldInverseInertias[i].inverse() *
                                                   state.angularVelocities[i]);
  return energy;
}

}  // namespace

// The symmetric step's second half (RATTLE): velocities that violate the joints are projected
// onto J v = 0 in the kinetic metric. The change is M^-1 J^T p, so it is orthogonal (in M) to the
// result: T falls by exactly the change's own kinetic energy. Ball joints only (3 x 3 blocks) and
// a hinge among them (entry by entry).
TEST(JointVelocityProjection, LandsOnTheJointsTangentSpaceByTheSmallestChange) {
  for (const bool withHinge : {false, true}) {
    geometry::BodyState state;
    const Eigen::Matrix3d inertia = Eigen::Vector3d(1e-3, 2e-3, 3e-3).asDiagonal();
    for (std::uint32_t i = 0; i < 3; ++i)
      state.assign(i, MotionType::Dynamic,
                   geometry::Pose{Eigen::Quaterniond(Eigen::AngleAxisd(
                                      0.3 * i, Eigen::Vector3d(1, 2, 3).normalized())),
                                  Eigen::Vector3d(0.5 + i, 0.1 * i, -0.2 * i)},
                   Eigen::Vector3d(0.3 * i, 1.0 - i, 0.5), Eigen::Vector3d(2.0, -1.0 * i, 0.7 * i),
                   0.4 + 0.3 * i, inertia * (1.0 + i));
    std::vector<joints::JointDef> joints(3);
    joints[0] = ballToWorld({0, 0}, {-0.5, 0, 0});
    for (std::uint32_t i = 1; i < 3; ++i) {
      joints::JointDef& def = joints[i];
      def.type = withHinge && i == 2 ? joints::JointType::Hinge : joints::JointType::Ball;
      def.bodyA = {i - 1, 0};
      def.bodyB = {i, 0};
      def.frameA.anchor = {0.5, 0, 0};
      def.frameB.anchor = {-0.5, 0, 0};
    }
    std::vector<const joints::JointDef*> list;
    for (const joints::JointDef& def : joints) list.push_back(&def);
    const geometry::BodyState before = state;
    ASSERT_GT(largestRowVelocity(state, joints), 0.1);
    integrators::PredictedStateWorkspace workspace;
    integrators::PredictedStateResult result;
    integrators::projectJointVelocities(state, list, workspace, result);
    EXPECT_TRUE(result.converged);
    EXPECT_EQ(result.iterations, 1);
    EXPECT_LT(largestRowVelocity(state, joints), 1e-8) << withHinge;
    double changeEnergy = 0.0;
    for (std::size_t i = 0; i < state.size(); ++i) {
      EXPECT_TRUE(state.poses[i].position == before.poses[i].position);  // velocities only
      const Eigen::Vector3d dv = state.linearVelocities[i] - before.linearVelocities[i];
      const Eigen::Vector3d dw = state.angularVelocities[i] - before.angularVelocities[i];
      changeEnergy += 0.5 * dv.squaredNorm() / state.inverseMasses[i] +
                      0.5 * dw.dot(state.worldInverseInertias[i].inverse() * dw);
    }
    EXPECT_GT(changeEnergy, 1e-3);
    // (to the rows' 1e-10 relative compliance)
    EXPECT_NEAR(kineticEnergy(state), kineticEnergy(before) - changeEnergy, 1e-8) << withHinge;
    // On the tangent space already: a second projection changes nothing measurable.
    const geometry::BodyState projected = state;
    integrators::projectJointVelocities(state, list, workspace, result);
    for (std::size_t i = 0; i < state.size(); ++i)
      EXPECT_LT((state.linearVelocities[i] - projected.linearVelocities[i]).norm(), 1e-8);
  }
}
