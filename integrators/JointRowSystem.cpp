// The joints' rows as one linear system (JointRowSystem.hpp).
#include <coulomb/integrators/JointRowSystem.hpp>
#include <coulomb/joints/JointConstraint.hpp>

#include <algorithm>
#include <utility>
#include <vector>

namespace coulomb::integrators::joint_rows {
namespace {

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

}  // namespace

bool dynamicBody(const geometry::BodyState& state, const geometry::BodyId& id) {
  return id.valid() && id.index < state.size() && state.isDynamic(id.index);
}

const joints::RowJacobian& side(const std::vector<joints::ConstraintEval>& at,
                                const Workspace::Touch& t) {
  return t.sideB ? at[t.joint].jacobianB : at[t.joint].jacobianA;
}

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

}  // namespace coulomb::integrators::joint_rows
