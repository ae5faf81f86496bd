#include <coulomb/geometry/Quaternion.hpp>
#include <coulomb/integrators/FreeRotation.hpp>
#include <coulomb/integrators/PredictedStateCorrection.hpp>
#include <coulomb/joints/JointConstraint.hpp>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <map>

namespace coulomb::integrators {
namespace {

bool dynamicBody(const geometry::BodyState& state, const geometry::BodyId& id) {
  return id.valid() && id.index < state.size() && state.isDynamic(id.index);
}

geometry::Pose predictedPoseOf(const geometry::BodyState& state, const geometry::BodyId& id,
                               double h) {
  if (!id.valid() || id.index >= state.size()) return geometry::Pose::identity();
  return predictPose(state, id.index, h);
}

/// Which (joint, side) rows touch each dynamic body, with that side's M^-1 J^T (6 x k).
struct BodyTouch {
  int joint;
  bool sideB;
};

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
  pose.rotation = rotateTorqueFree(pose.rotation, state.principalFrames[i],
                                   state.principalMoments[i], state.angularMomentum(i), h);
  return pose;
}

PredictedStateResult correctPredictedState(geometry::BodyState& state,
                                           std::span<const joints::JointDef* const> joints,
                                           const joints::PredictedStateSettings& settings,
                                           double h) {
  PredictedStateResult result;
  const auto jointCount = static_cast<int>(joints.size());
  result.impulses.resize(jointCount);
  if (jointCount == 0) return result;

  // Jacobians at the start of the step (fixed through the iteration, as in Bender's method).
  std::vector<joints::ConstraintEval> start;
  std::vector<int> offset(jointCount + 1, 0);
  start.reserve(jointCount);
  for (int j = 0; j < jointCount; ++j) {
    const joints::JointDef& def = *joints[j];
    const auto pose = [&](const geometry::BodyId& id) {
      return id.valid() ? state.poses[id.index] : geometry::Pose::identity();
    };
    start.push_back(joints::evaluateJoint(def, pose(def.bodyA), pose(def.bodyB)));
    offset[j + 1] = offset[j] + start.back().rows();
    result.impulses[j] = joints::RowVector::Zero(start.back().rows());
  }
  const int n = offset[jointCount];

  // A = J M^-1 J^T, accumulated per shared body (deterministic: std::map by body index).
  std::map<std::uint32_t, std::vector<BodyTouch>> touches;
  for (int j = 0; j < jointCount; ++j)
    for (const bool sideB : {false, true}) {
      const geometry::BodyId& id = sideB ? joints[j]->bodyB : joints[j]->bodyA;
      if (dynamicBody(state, id)) touches[id.index].push_back({j, sideB});
    }
  const auto jac = [&](const BodyTouch& t) -> const joints::RowJacobian& {
    return t.sideB ? start[t.joint].jacobianB : start[t.joint].jacobianA;
  };
  const auto inverseMassTimesJt = [&](std::uint32_t body, const joints::RowJacobian& J) {
    Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6> out(6, J.rows());
    out.topRows<3>() = state.inverseMasses[body] * J.leftCols<3>().transpose();
    out.bottomRows<3>() = state.worldInverseInertias[body] * J.rightCols<3>().transpose();
    return out;
  };
  std::vector<Eigen::Triplet<double>> triplets;
  for (const auto& [body, list] : touches)
    for (const BodyTouch& a : list)
      for (const BodyTouch& b : list) {
        const Eigen::MatrixXd block = jac(a) * inverseMassTimesJt(body, jac(b));
        for (int r = 0; r < block.rows(); ++r)
          for (int c = 0; c < block.cols(); ++c)
            triplets.emplace_back(offset[a.joint] + r, offset[b.joint] + c, block(r, c));
      }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(triplets.begin(), triplets.end());
  double maxDiagonal = 0.0;
  for (int i = 0; i < n; ++i) maxDiagonal = std::max(maxDiagonal, A.coeff(i, i));
  if (maxDiagonal <= 0.0) return result;  // no joint touches a dynamic body
  for (int i = 0; i < n; ++i) A.coeffRef(i, i) += 1e-10 * maxDiagonal;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor(A);
  if (factor.info() != Eigen::Success) return result;

  Eigen::VectorXd drift(n);
  for (int pass = 0;; ++pass) {
    // Predicted error of every joint at t+h with the current velocities.
    double largest = 0.0;
    for (int j = 0; j < jointCount; ++j) {
      const joints::JointDef& def = *joints[j];
      const joints::ConstraintEval predicted = joints::evaluateJoint(
          def, predictedPoseOf(state, def.bodyA, h), predictedPoseOf(state, def.bodyB, h));
      drift.segment(offset[j], predicted.rows()) = predicted.error;
      largest = std::max(largest, predicted.error.cwiseAbs().maxCoeff());
    }
    if (pass == 0) result.initialError = largest;
    result.finalError = largest;
    result.converged = largest <= settings.tolerance;
    if (result.converged || pass == settings.iterations || !drift.allFinite()) break;

    const Eigen::VectorXd p = factor.solve(-drift / h);  // J M^-1 J^T p = dv = -d/h
    if (!p.allFinite()) break;
    result.iterations = pass + 1;
    for (const auto& [body, list] : touches)
      for (const BodyTouch& t : list) {
        const auto impulse = p.segment(offset[t.joint], start[t.joint].rows());
        const joints::RowJacobian& J = jac(t);
        state.linearVelocities[body] +=
            state.inverseMasses[body] * (J.leftCols<3>().transpose() * impulse);
        state.angularVelocities[body] +=
            state.worldInverseInertias[body] * (J.rightCols<3>().transpose() * impulse);
      }
    for (int j = 0; j < jointCount; ++j)
      result.impulses[j] += p.segment(offset[j], start[j].rows());
  }
  return result;
}

}  // namespace coulomb::integrators
