// The predicted-state correction (PredictedStateCorrection.hpp): Newton passes on C(t+h), then
// projections where SHAKE has no root; the linear algebra is JointRowSystem's.
#include <coulomb/geometry/Quaternion.hpp>
#include <coulomb/integrators/FreeRotation.hpp>
#include <coulomb/integrators/JointRowSystem.hpp>
#include <coulomb/integrators/PredictedStateCorrection.hpp>
#include <coulomb/joints/JointConstraint.hpp>

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

namespace coulomb::integrators {
using namespace joint_rows;
namespace {

geometry::Pose predictedPoseOf(const geometry::BodyState& state, const geometry::BodyId& id,
                               double h) {
  if (!id.valid() || id.index >= state.size()) return geometry::Pose::identity();
  return predictPose(state, id.index, h);
}

}  // namespace

geometry::Pose predictPose(const geometry::BodyState& state, std::size_t i, double h) {
  using geometry::MotionType;
  geometry::Pose pose = state.poses[i];
  if (state.alive[i] == 0 || state.motionTypes[i] == MotionType::Static) return pose;
  pose.position += h * state.linearVelocities[i];
  if (state.motionTypes[i] == MotionType::Kinematic) {
    pose.rotation = geometry::integrateWorldRotation(pose.rotation, state.angularVelocities[i], h);
    return pose;
  }
  pose.rotation = torqueFreeOrientation(state, i, h);
  return pose;
}

PredictedStateResult correctPredictedState(geometry::BodyState& state,
                                           std::span<const joints::JointDef* const> joints,
                                           const joints::PredictedStateSettings& settings,
                                           double h) {
  PredictedStateWorkspace workspace;
  PredictedStateResult result;
  correctPredictedState(state, joints, settings, h, workspace, result);
  return result;
}

void correctPredictedState(geometry::BodyState& state,
                           std::span<const joints::JointDef* const> joints,
                           const joints::PredictedStateSettings& settings, double h,
                           PredictedStateWorkspace& w, PredictedStateResult& result) {
  // Jacobians at the start of the step (fixed through the iteration, as in Bender's method).
  const double compliance = resetAtCurrentPoses(state, joints, w, result, false);
  if (compliance <= 0.0) return;  // no joint, or none touches a dynamic body
  const auto jointCount = static_cast<int>(joints.size());
  const int n = w.offset[jointCount];

  Eigen::VectorXd& drift = w.drift;
  drift.resize(n);
  // Predicted error of every joint at t+h with the current velocities; returns the largest |C|.
  const auto predictErrors = [&] {
    // Each touched body once (a chain link is on two joints; the torque-free rotation is the
    // cost), the others (world, static, kinematic) per joint side.
    w.predictedPoses.resize(w.bodies.size());
    for (std::size_t k = 0; k < w.bodies.size(); ++k)
      w.predictedPoses[k] = predictPose(state, w.bodies[k], h);
    const auto poseAt = [&](int j, const geometry::BodyId& id, bool sideB) {
      const int k = w.sideBody[2 * j + (sideB ? 1 : 0)];
      return k >= 0 ? w.predictedPoses[k] : predictedPoseOf(state, id, h);
    };
    double largest = 0.0;
    w.predicted.resize(jointCount);  // no allocation once both buffers (see the Newton pass) grew
    for (int j = 0; j < jointCount; ++j) {
      const joints::JointDef& def = *joints[j];
      joints::evaluateJoint(def, poseAt(j, def.bodyA, false), poseAt(j, def.bodyB, true),
                            w.predicted[j]);
      drift.segment(w.offset[j], w.predicted[j].rows()) = w.predicted[j].error;
      largest = std::max(largest, w.predicted[j].error.cwiseAbs().maxCoeff());
    }
    return drift.allFinite() ? largest : std::numeric_limits<double>::infinity();
  };
  const auto applyImpulse = [&](const Eigen::VectorXd& p,
                                const std::vector<joints::ConstraintEval>& along) {
    applyRowImpulses(state, along, p, w);
  };
  const auto saveVelocities = [&] {
    w.saved.clear();
    for (const std::uint32_t body : w.bodies)
      w.saved.emplace_back(state.linearVelocities[body], state.angularVelocities[body]);
  };
  const auto restoreVelocities = [&] {
    std::size_t k = 0;
    for (const std::uint32_t body : w.bodies) {
      state.linearVelocities[body] = w.saved[k].first;
      state.angularVelocities[body] = w.saved[k++].second;
    }
  };

  double largest = predictErrors();
  result.initialError = largest;
  Eigen::VectorXd& total = w.total;
  total.setZero(n);
  Eigen::VectorXd& p = w.p;
  for (int pass = 0; pass < settings.iterations && largest > settings.tolerance; ++pass) {
    // Newton step on p -> C(x(t+h; p)): B p = -C/h with B = J_pred M^-1 J_n^T, the rows'
    // Jacobian taken at the predicted state (Bender's fixed J_n M^-1 J_n^T contracts only by
    // ~h|omega| per pass and fails on a whipping chain's tip). Solved by LU: B is not symmetric,
    // and the normal equations B^T B would square its condition and cost a product per block.
    // A step that does not halve |C| means SHAKE has no root near (B turns singular where a chain
    // passes a straight configuration): the remaining passes project (below).
    assemble(w.predicted, compliance, w);  // M^-1 J^T of the start, as above
    w.target = -drift / h;
    if (!solveNewton(w, p) || !p.allFinite()) break;
    saveVelocities();
    const double norm = drift.norm();
    std::swap(w.predicted, w.predictedBefore);  // kept, to be restored if the step fails
    w.driftBefore = drift;
    applyImpulse(p, w.start);
    const double trial = predictErrors();
    if (!(drift.norm() < norm)) {
      restoreVelocities();
      std::swap(w.predicted, w.predictedBefore);
      drift = w.driftBefore;
      break;
    }
    total += p;
    const bool stalled = trial > 0.5 * largest;  // Newton near a root at least halves |C|
    largest = trial;
    result.iterations = pass + 1;
    if (stalled) break;
  }
  // Where SHAKE has no root (the start-of-step rows J_n cannot reach the manifold; e.g. a heavy
  // load swinging on light links, whose centripetal tension along J_n spins the tilted links),
  // project instead: Gauss-Newton on C with the impulses along the rows at the predicted state,
  // (J_p M^-1 J_p^T) p = -C/h, a step halved until |C| drops (Cline and Pai 2003,
  // post-stabilization). It closes the joints; the step is then not exactly SHAKE.
  for (int pass = result.iterations; pass < settings.iterations && largest > settings.tolerance;
       ++pass) {
    w.along = w.predicted;
    inverseMassTimesRows(state, w.along, w);
    assemble(w.along, compliance, w);
    w.target = -drift / h;
    if (!solveSymmetric(w, p) || !p.allFinite()) break;
    saveVelocities();
    const double norm = drift.norm();
    bool improved = false;
    double trial = largest;
    for (int halving = 0; halving < 8 && !improved; ++halving) {
      applyImpulse(p, w.along);
      trial = predictErrors();
      improved = drift.norm() < norm;
      if (!improved) {
        restoreVelocities();
        p *= 0.5;
      }
    }
    if (!improved) {
      predictErrors();  // velocities restored: refresh the predicted errors
      break;
    }
    total += p;  // along J_p, booked on the start rows (the reaction is approximate there)
    largest = trial;
    result.iterations = pass + 1;
  }
  result.finalError = largest;
  result.converged = largest <= settings.tolerance;
  for (int j = 0; j < jointCount; ++j) {
    result.impulses[j] = total.segment(w.offset[j], w.start[j].rows());
    result.impulsesOnB[j] = w.start[j].jacobianB.transpose() * result.impulses[j];
  }
}

}  // namespace coulomb::integrators
