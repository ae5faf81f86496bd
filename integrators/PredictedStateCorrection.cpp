#include <coulomb/geometry/Quaternion.hpp>
#include <coulomb/integrators/FreeRotation.hpp>
#include <coulomb/integrators/PredictedStateCorrection.hpp>
#include <coulomb/joints/JointConstraint.hpp>

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

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

using Workspace = PredictedStateWorkspace;
using Matrix6k = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;
using Block3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;  // a block of B, 3-row joints
using Rows3 = Eigen::Matrix<double, 3, 6, Eigen::RowMajor>;   // a ball joint's side of J

// The structure's identity: per joint its row count and which of its bodies carry unknowns.
void structureKey(const geometry::BodyState& state, std::span<const joints::JointDef* const> joints,
                  const Workspace& w, std::vector<int>& key) {
  key.clear();
  for (std::size_t j = 0; j < joints.size(); ++j) {
    key.push_back(w.start[j].rows());
    for (const geometry::BodyId* id : {&joints[j]->bodyA, &joints[j]->bodyB})
      key.push_back(dynamicBody(state, *id) ? static_cast<int>(id->index) : -1);
  }
}

// Which joints share a body, the terms of B = J_rows M^-1 J_impulses^T per block, and the patterns
// of B (for its LU) and of J M^-1 J^T (for its LDL^T). Runs when the structure changes only.
void buildStructure(const geometry::BodyState& state,
                    std::span<const joints::JointDef* const> joints, Workspace& w) {
  const auto jointCount = static_cast<int>(joints.size());
  auto rows = [&](int j) { return w.start[j].rows(); };
  w.touches.clear();
  for (int j = 0; j < jointCount; ++j)
    for (const bool sideB : {false, true}) {
      const geometry::BodyId& id = sideB ? joints[j]->bodyB : joints[j]->bodyA;
      if (dynamicBody(state, id)) w.touches.push_back({id.index, j, sideB});
    }
  std::stable_sort(w.touches.begin(), w.touches.end(),
                   [](const auto& l, const auto& r) { return l.body < r.body; });
  w.bodies.clear();
  for (const auto& t : w.touches)
    if (w.bodies.empty() || w.bodies.back() != t.body) w.bodies.push_back(t.body);
  w.sideBody.assign(2 * static_cast<std::size_t>(jointCount), -1);
  for (const auto& t : w.touches)
    w.sideBody[2 * t.joint + (t.sideB ? 1 : 0)] = static_cast<int>(
        std::lower_bound(w.bodies.begin(), w.bodies.end(), t.body) - w.bodies.begin());

  // Pairs (a, b) of joints on one body, every (a, a) too (compliance on every row).
  w.pairs.clear();
  for (int j = 0; j < jointCount; ++j) w.pairs.emplace_back(j, j);
  for (std::size_t g = 0; g < w.touches.size();) {
    std::size_t end = g;
    while (end < w.touches.size() && w.touches[end].body == w.touches[g].body) ++end;
    for (std::size_t a = g; a < end; ++a)
      for (std::size_t b = g; b < end; ++b)
        w.pairs.emplace_back(w.touches[a].joint, w.touches[b].joint);
    g = end;
  }
  std::sort(w.pairs.begin(), w.pairs.end());
  w.pairs.erase(std::unique(w.pairs.begin(), w.pairs.end()), w.pairs.end());
  auto pairIndex = [&](int a, int b) {
    return static_cast<int>(std::lower_bound(w.pairs.begin(), w.pairs.end(), std::pair{a, b}) -
                            w.pairs.begin());
  };
  w.pairValues.assign(w.pairs.size() + 1, 0);
  for (std::size_t q = 0; q < w.pairs.size(); ++q)
    w.pairValues[q + 1] = w.pairValues[q] + rows(w.pairs[q].first) * rows(w.pairs[q].second);
  w.diagonalPair.resize(jointCount);
  for (int j = 0; j < jointCount; ++j) w.diagonalPair[j] = pairIndex(j, j);
  // Terms in the order the triplets of the first version were summed: body, then a, then b.
  w.terms.clear();
  for (std::size_t g = 0; g < w.touches.size();) {
    std::size_t end = g;
    while (end < w.touches.size() && w.touches[end].body == w.touches[g].body) ++end;
    for (std::size_t a = g; a < end; ++a)
      for (std::size_t b = g; b < end; ++b)
        w.terms.push_back({static_cast<int>(a), static_cast<int>(b),
                           pairIndex(w.touches[a].joint, w.touches[b].joint)});
    g = end;
  }

  // The pattern of B and of J M^-1 J^T: by 3 x 3 blocks, or entry by entry.
  const int n = w.offset[jointCount];
  w.byBlocks =
      std::all_of(w.start.begin(), w.start.end(), [](const auto& e) { return e.rows() == 3; });
  if (w.byBlocks) {
    w.blockPairs.clear();
    w.blockSource.clear();
    w.blockMirrorSource.clear();
    for (std::size_t q = 0; q < w.pairs.size(); ++q)
      if (w.pairs[q].first > w.pairs[q].second) {
        w.blockPairs.push_back(w.pairs[q]);
        w.blockSource.push_back(static_cast<int>(q));
        w.blockMirrorSource.push_back(pairIndex(w.pairs[q].second, w.pairs[q].first));
      }
    w.newtonBlockLu.analyze(jointCount, w.blockPairs);
    // Analysed now, though only the projection passes use it: analysed on first use, it
    // allocated in whichever steady step first needed a projection (a chain's first stalled whip).
    w.symmetricBlockLdlt.analyze(jointCount, w.blockPairs);
    w.blockDiagonal.resize(jointCount);
    w.blockCoupling.resize(w.blockPairs.size());
    w.blockMirrored.resize(w.blockPairs.size());
  } else {
    w.scalarPairs.clear();
    w.scalarSource.clear();
    w.scalarMirrorSource.clear();
    w.scalarDiagonalSource.assign(n, 0);
    w.symmetricRows.clear();
    w.symmetricCols.clear();
    w.symmetricSource.clear();
    for (std::size_t q = 0; q < w.pairs.size(); ++q) {
      const auto [a, b] = w.pairs[q];
      if (a < b) continue;
      const int mirror = pairIndex(b, a);
      for (int r = 0; r < rows(a); ++r)
        for (int c = 0; c < rows(b); ++c) {
          if (a == b && c > r) continue;
          const int row = w.offset[a] + r, col = w.offset[b] + c;
          const int source = w.pairValues[q] + r * rows(b) + c;
          w.symmetricRows.push_back(row);
          w.symmetricCols.push_back(col);
          w.symmetricSource.push_back(source);
          if (row == col) {
            w.scalarDiagonalSource[row] = source;
          } else {
            w.scalarPairs.emplace_back(row, col);
            w.scalarSource.push_back(source);
            w.scalarMirrorSource.push_back(w.pairValues[mirror] + c * rows(a) + r);
          }
        }
    }
    w.newtonLu.analyze(n, w.scalarPairs);
    w.symmetricLdlt.analyze(n, w.symmetricRows, w.symmetricCols);  // as above
    w.scalarDiagonal.resize(n);
    w.scalarCoupling.resize(w.scalarPairs.size());
    w.scalarMirrored.resize(w.scalarPairs.size());
  }
  w.along.resize(jointCount);  // the projection's rows, copied into this storage
  w.b.assign(w.pairValues.back(), 0.0);
  w.minvJt.resize(w.touches.size());
}

const joints::RowJacobian& side(const std::vector<joints::ConstraintEval>& at,
                                const Workspace::Touch& t) {
  return t.sideB ? at[t.joint].jacobianB : at[t.joint].jacobianA;
}

// v += M^-1 J^T p on every touched body, J the rows of `along`.
void applyRowImpulses(geometry::BodyState& state, const std::vector<joints::ConstraintEval>& along,
                      const Eigen::VectorXd& p, const Workspace& w) {
  for (const Workspace::Touch& t : w.touches) {
    const joints::RowJacobian& J = side(along, t);
    if (J.rows() == 3) {  // ball joints: fixed sizes
      const Eigen::Vector3d impulse = p.segment<3>(w.offset[t.joint]);
      const Eigen::Map<const Rows3> rows(J.data());
      state.linearVelocities[t.body] +=
          state.inverseMasses[t.body] * (rows.leftCols<3>().transpose() * impulse);
      state.angularVelocities[t.body] +=
          state.worldInverseInertias[t.body] * (rows.rightCols<3>().transpose() * impulse);
      continue;
    }
    const auto impulse = p.segment(w.offset[t.joint], J.rows());
    state.linearVelocities[t.body] +=
        state.inverseMasses[t.body] * (J.leftCols<3>().transpose() * impulse);
    state.angularVelocities[t.body] +=
        state.worldInverseInertias[t.body] * (J.rightCols<3>().transpose() * impulse);
  }
}

// w.minvJt = M^-1 J^T per touch, J the rows of `impulsesAt` (the Newton passes share the start's).
void inverseMassTimesRows(const geometry::BodyState& state,
                          const std::vector<joints::ConstraintEval>& impulsesAt, Workspace& w) {
  for (std::size_t t = 0; t < w.touches.size(); ++t) {
    const auto& touch = w.touches[t];
    const joints::RowJacobian& J = side(impulsesAt, touch);
    Matrix6k& out = w.minvJt[t];
    out.resize(6, J.rows());
    out.topRows<3>() = state.inverseMasses[touch.body] * J.leftCols<3>().transpose();
    out.bottomRows<3>() = state.worldInverseInertias[touch.body] * J.rightCols<3>().transpose();
  }
}

// w.b = blocks of J_rows M^-1 J^T (the rows' Jacobians taken from `rowsAt`, M^-1 J^T from
// w.minvJt), plus `compliance` on every diagonal entry.
void assemble(const std::vector<joints::ConstraintEval>& rowsAt, double compliance, Workspace& w) {
  std::fill(w.b.begin(), w.b.end(), 0.0);
  for (const Workspace::Term& term : w.terms) {
    const joints::RowJacobian& Ja = side(rowsAt, w.touches[term.row]);
    const Matrix6k& Gb = w.minvJt[term.column];
    double* block = w.b.data() + w.pairValues[term.pair];
    const auto cols = Gb.cols();
    if (Ja.rows() == 3 && cols == 3) {  // ball joints: fixed sizes (several times fewer operations)
      Eigen::Map<Block3>(block).noalias() +=
          Eigen::Map<const Rows3>(Ja.data()) *
          Eigen::Map<const Eigen::Matrix<double, 6, 3>>(Gb.data());
      continue;
    }
    for (Eigen::Index r = 0; r < Ja.rows(); ++r)
      for (Eigen::Index c = 0; c < cols; ++c) block[r * cols + c] += Ja.row(r).dot(Gb.col(c));
  }
  if (compliance != 0.0)
    for (std::size_t j = 0; j < w.diagonalPair.size(); ++j) {
      const int q = w.diagonalPair[j], k = w.start[j].rows();
      for (int r = 0; r < k; ++r) w.b[w.pairValues[q] + r * k + r] += compliance;
    }
}

// p = B^-1 target, B (w.b, as assembled: B(a, b) and B(b, a) are separate blocks) factorized by
// LU; false when the factorization fails (a singular pivot).
bool solveNewton(Workspace& w, Eigen::VectorXd& p) {
  if (w.byBlocks) {
    for (std::size_t j = 0; j < w.blockDiagonal.size(); ++j)
      w.blockDiagonal[j] = Eigen::Map<const Block3>(w.b.data() + w.pairValues[w.diagonalPair[j]]);
    for (std::size_t q = 0; q < w.blockPairs.size(); ++q) {
      w.blockCoupling[q] = Eigen::Map<const Block3>(w.b.data() + w.pairValues[w.blockSource[q]]);
      w.blockMirrored[q] =
          Eigen::Map<const Block3>(w.b.data() + w.pairValues[w.blockMirrorSource[q]]);
    }
    if (!w.newtonBlockLu.factorize(w.blockDiagonal, w.blockCoupling, w.blockMirrored)) return false;
    w.newtonBlockLu.solve(w.target, p);
    return true;
  }
  for (std::size_t e = 0; e < w.scalarDiagonal.size(); ++e)
    w.scalarDiagonal[e](0, 0) = w.b[w.scalarDiagonalSource[e]];
  for (std::size_t e = 0; e < w.scalarPairs.size(); ++e) {
    w.scalarCoupling[e](0, 0) = w.b[w.scalarSource[e]];
    w.scalarMirrored[e](0, 0) = w.b[w.scalarMirrorSource[e]];
  }
  if (!w.newtonLu.factorize(w.scalarDiagonal, w.scalarCoupling, w.scalarMirrored)) return false;
  w.newtonLu.solve(w.target, p);
  return true;
}

// p = (J M^-1 J^T)^-1 target, the projection's symmetric matrix (w.b assembled with the same rows
// twice) factorized by LDL^T; false when the factorization fails.
bool solveSymmetric(Workspace& w, Eigen::VectorXd& p) {
  if (w.byBlocks) {
    for (std::size_t j = 0; j < w.blockDiagonal.size(); ++j)
      w.blockDiagonal[j] = Eigen::Map<const Block3>(w.b.data() + w.pairValues[w.diagonalPair[j]]);
    for (std::size_t q = 0; q < w.blockPairs.size(); ++q)
      w.blockCoupling[q] = Eigen::Map<const Block3>(w.b.data() + w.pairValues[w.blockSource[q]]);
    if (!w.symmetricBlockLdlt.factorize(w.blockDiagonal, w.blockCoupling)) return false;
    w.symmetricBlockLdlt.solve(w.target, p);
    return true;
  }
  w.entries.resize(w.symmetricSource.size());
  for (std::size_t e = 0; e < w.symmetricSource.size(); ++e)
    w.entries[e] = w.b[w.symmetricSource[e]];
  if (!w.symmetricLdlt.factorize(w.entries)) return false;
  w.symmetricLdlt.solve(w.target, p);
  return true;
}

// w.start, w.offset and w.minvJt for the joints at the bodies' current poses, the structure
// rebuilt when it changed; returns the compliance of every row, 1e-10 of the largest diagonal
// entry of J M^-1 J^T (0 when no joint touches a dynamic body).
double rowsAtCurrentPoses(const geometry::BodyState& state,
                          std::span<const joints::JointDef* const> joints, Workspace& w) {
  const auto jointCount = static_cast<int>(joints.size());
  w.start.resize(jointCount);
  w.offset.assign(jointCount + 1, 0);
  for (int j = 0; j < jointCount; ++j) {
    const joints::JointDef& def = *joints[j];
    const auto pose = [&](const geometry::BodyId& id) {
      return id.valid() ? state.poses[id.index] : geometry::Pose::identity();
    };
    joints::evaluateJoint(def, pose(def.bodyA), pose(def.bodyB), w.start[j]);
    w.offset[j + 1] = w.offset[j] + w.start[j].rows();
  }
  const int n = w.offset[jointCount];
  {
    std::vector<int>& key = w.key;  // compared in place: no allocation when unchanged
    std::vector<int> fresh;
    fresh.swap(w.keyScratch);
    structureKey(state, joints, w, fresh);
    if (fresh != key) {
      key = fresh;
      buildStructure(state, joints, w);
    }
    w.keyScratch.swap(fresh);
  }
  inverseMassTimesRows(state, w.start, w);
  w.target.setZero(n);  // the diagonal of J M^-1 J^T, summed over the joint's sides
  for (std::size_t t = 0; t < w.touches.size(); ++t) {
    const joints::RowJacobian& J = side(w.start, w.touches[t]);
    const int first = w.offset[w.touches[t].joint];
    for (Eigen::Index r = 0; r < J.rows(); ++r)
      w.target[first + r] += J.row(r).dot(w.minvJt[t].col(r));
  }
  const double maxDiagonal = n > 0 ? w.target.maxCoeff() : 0.0;
  return maxDiagonal > 0.0 ? 1e-10 * maxDiagonal : 0.0;
}

// `result` reset (no pass, zero impulses per joint, `converged` as given) and the joints' rows at
// the bodies' current poses (rowsAtCurrentPoses); returns their compliance, 0 when there is
// nothing to do (no joint, or none on a dynamic body).
double resetAtCurrentPoses(const geometry::BodyState& state,
                           std::span<const joints::JointDef* const> joints, Workspace& w,
                           PredictedStateResult& result, bool converged) {
  const auto jointCount = static_cast<int>(joints.size());
  result.iterations = 0;
  result.initialError = result.finalError = 0.0;
  result.converged = converged;
  result.impulses.resize(jointCount);
  result.impulsesOnB.resize(jointCount);
  if (jointCount == 0) return 0.0;
  const double compliance = rowsAtCurrentPoses(state, joints, w);
  for (int j = 0; j < jointCount; ++j) {
    result.impulses[j] = joints::RowVector::Zero(w.start[j].rows());
    result.impulsesOnB[j].setZero();
  }
  return compliance;
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

void projectJointVelocities(geometry::BodyState& state,
                            std::span<const joints::JointDef* const> joints,
                            PredictedStateWorkspace& w, PredictedStateResult& result) {
  const double compliance = resetAtCurrentPoses(state, joints, w, result, true);
  if (compliance <= 0.0) return;
  const auto jointCount = static_cast<int>(joints.size());
  // -J v: the bodies that are not touched (the world, static bodies) do not move.
  w.target.setZero(w.offset[jointCount]);
  for (const Workspace::Touch& t : w.touches) {
    const joints::RowJacobian& J = side(w.start, t);
    w.target.segment(w.offset[t.joint], J.rows()) -=
        J.leftCols<3>() * state.linearVelocities[t.body] +
        J.rightCols<3>() * state.angularVelocities[t.body];
  }
  result.initialError = w.target.cwiseAbs().maxCoeff();
  assemble(w.start, compliance, w);
  if (!solveSymmetric(w, w.p) || !w.p.allFinite()) {
    result.converged = false;
    result.finalError = result.initialError;
    return;
  }
  applyRowImpulses(state, w.start, w.p, w);
  result.iterations = 1;
  for (int j = 0; j < jointCount; ++j) {
    result.impulses[j] = w.p.segment(w.offset[j], w.start[j].rows());
    result.impulsesOnB[j] = w.start[j].jacobianB.transpose() * result.impulses[j];
  }
}

}  // namespace coulomb::integrators
