#include <coulomb/geometry/Quaternion.hpp>
#include <coulomb/integrators/FreeRotation.hpp>
#include <coulomb/integrators/PredictedStateCorrection.hpp>
#include <coulomb/joints/JointConstraint.hpp>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <limits>
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
  const auto inverseMassTimesJt = [&](std::uint32_t body, const joints::RowJacobian& J) {
    Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6> out(6, J.rows());
    out.topRows<3>() = state.inverseMasses[body] * J.leftCols<3>().transpose();
    out.bottomRows<3>() = state.worldInverseInertias[body] * J.rightCols<3>().transpose();
    return out;
  };
  // B = J_row M^-1 J_n^T: with J_row = J_n it is Bender's symmetric A; with J_row the Jacobian
  // at the predicted state it is the Newton matrix of p -> C(x(t+h; p)) (times 1/h).
  const auto side = [](const std::vector<joints::ConstraintEval>& at,
                       const BodyTouch& t) -> const joints::RowJacobian& {
    return t.sideB ? at[t.joint].jacobianB : at[t.joint].jacobianA;
  };
  const auto assemble = [&](const std::vector<joints::ConstraintEval>& rowsAt,
                            const std::vector<joints::ConstraintEval>& impulsesAt) {
    std::vector<Eigen::Triplet<double>> triplets;
    for (const auto& [body, list] : touches)
      for (const BodyTouch& a : list)
        for (const BodyTouch& b : list) {
          const Eigen::MatrixXd block =
              side(rowsAt, a) * inverseMassTimesJt(body, side(impulsesAt, b));
          for (int r = 0; r < block.rows(); ++r)
            for (int c = 0; c < block.cols(); ++c)
              triplets.emplace_back(offset[a.joint] + r, offset[b.joint] + c, block(r, c));
        }
    Eigen::SparseMatrix<double> A(n, n);
    A.setFromTriplets(triplets.begin(), triplets.end());
    return A;
  };
  Eigen::SparseMatrix<double> A = assemble(start, start);
  double maxDiagonal = 0.0;
  for (int i = 0; i < n; ++i) maxDiagonal = std::max(maxDiagonal, A.coeff(i, i));
  if (maxDiagonal <= 0.0) return result;  // no joint touches a dynamic body
  const double compliance = 1e-10 * maxDiagonal;
  Eigen::SparseMatrix<double> identity(n, n);
  identity.setIdentity();
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;

  Eigen::VectorXd drift(n);
  std::vector<joints::ConstraintEval> predicted(jointCount);
  // Predicted error of every joint at t+h with the current velocities; returns the largest |C|.
  const auto predictErrors = [&] {
    double largest = 0.0;
    for (int j = 0; j < jointCount; ++j) {
      const joints::JointDef& def = *joints[j];
      predicted[j] = joints::evaluateJoint(def, predictedPoseOf(state, def.bodyA, h),
                                           predictedPoseOf(state, def.bodyB, h));
      drift.segment(offset[j], predicted[j].rows()) = predicted[j].error;
      largest = std::max(largest, predicted[j].error.cwiseAbs().maxCoeff());
    }
    return drift.allFinite() ? largest : std::numeric_limits<double>::infinity();
  };
  const auto applyImpulse = [&](const Eigen::VectorXd& p,
                                const std::vector<joints::ConstraintEval>& along) {
    for (const auto& [body, list] : touches)
      for (const BodyTouch& t : list) {
        const auto impulse = p.segment(offset[t.joint], start[t.joint].rows());
        const joints::RowJacobian& J = side(along, t);
        state.linearVelocities[body] +=
            state.inverseMasses[body] * (J.leftCols<3>().transpose() * impulse);
        state.angularVelocities[body] +=
            state.worldInverseInertias[body] * (J.rightCols<3>().transpose() * impulse);
      }
  };
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> saved;
  const auto saveVelocities = [&] {
    saved.clear();
    for (const auto& entry : touches)
      saved.emplace_back(state.linearVelocities[entry.first], state.angularVelocities[entry.first]);
  };
  const auto restoreVelocities = [&] {
    std::size_t k = 0;
    for (const auto& entry : touches) {
      state.linearVelocities[entry.first] = saved[k].first;
      state.angularVelocities[entry.first] = saved[k++].second;
    }
  };

  double largest = predictErrors();
  result.initialError = largest;
  Eigen::VectorXd total = Eigen::VectorXd::Zero(n);
  double damping = 1e-12;  // Levenberg-Marquardt mu, relative to max diag(B^T B)
  for (int pass = 0; pass < settings.iterations && largest > settings.tolerance; ++pass) {
    // Newton step on p -> C(x(t+h; p)): B p = -C/h with B = J_pred M^-1 J_n^T, the rows'
    // Jacobian taken at the predicted state (Bender's fixed J_n M^-1 J_n^T contracts only by
    // ~h|omega| per pass and fails on a whipping chain's tip). B turns singular where a chain
    // passes a straight configuration, so the step is Levenberg-Marquardt damped:
    // (B^T B + mu I) p = B^T (-C/h), mu shrunk after a success and grown until the error drops.
    const Eigen::SparseMatrix<double> B = assemble(predicted, start) + compliance * identity;
    const Eigen::SparseMatrix<double> normal = B.transpose() * B;
    const Eigen::VectorXd rhs = B.transpose() * (-drift / h);
    double scaleOfNormal = 0.0;
    for (int i = 0; i < n; ++i) scaleOfNormal = std::max(scaleOfNormal, normal.coeff(i, i));
    saveVelocities();
    const double norm = drift.norm();
    double trial = largest;
    bool improved = false;
    Eigen::VectorXd p;
    for (int attempt = 0; attempt < 12 && !improved; ++attempt) {
      ldlt.compute(normal + damping * scaleOfNormal * identity);
      if (ldlt.info() != Eigen::Success) break;
      p = ldlt.solve(rhs);
      if (!p.allFinite()) break;
      applyImpulse(p, start);
      trial = predictErrors();
      improved = drift.norm() < norm;
      if (improved) {
        damping = std::max(damping * 0.1, 1e-12);
      } else {
        restoreVelocities();
        damping *= 10.0;
      }
    }
    if (!improved) {
      predictErrors();  // velocities restored: refresh the predicted errors
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
    const std::vector<joints::ConstraintEval> along = predicted;
    ldlt.compute(assemble(along, along) + compliance * identity);
    if (ldlt.info() != Eigen::Success) break;
    Eigen::VectorXd p = ldlt.solve(-drift / h);
    if (!p.allFinite()) break;
    saveVelocities();
    const double norm = drift.norm();
    bool improved = false;
    double trial = largest;
    for (int halving = 0; halving < 8 && !improved; ++halving) {
      applyImpulse(p, along);
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
  for (int j = 0; j < jointCount; ++j)
    result.impulses[j] = total.segment(offset[j], start[j].rows());
  return result;
}

}  // namespace coulomb::integrators
