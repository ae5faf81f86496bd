#include <coulomb/engine/ImpulseApplier.hpp>
#include <coulomb/engine/PenetrationCorrection.hpp>
#include <coulomb/geometry/Quaternion.hpp>

#include <algorithm>

namespace coulomb::engine {

double baumgarteBias(const PenetrationSettings& settings, double depth, double h) {
  if (settings.method != PenetrationMethod::Baumgarte) return 0.0;
  return -settings.beta * std::max(depth - settings.slop, 0.0) / h;
}

solvers::BlockSparseMatrix normalNormalBlock(const VelocityProblemNormals& normals) {
  const auto contacts = static_cast<int>(normals.normalRows.size());
  std::vector<int> rowStart{0}, columns;
  std::vector<double> values;
  rowStart.reserve(contacts + 1);
  if (const Eigen::MatrixXd* dense = normals.W.denseMatrix()) {
    for (int k = 0; k < contacts; ++k) {
      for (int j = 0; j < contacts; ++j) {
        const double w = (*dense)(normals.normalRows[k], normals.normalRows[j]);
        if (w == 0.0 && j != k) continue;
        columns.push_back(j);
        values.push_back(w);
      }
      rowStart.push_back(static_cast<int>(columns.size()));
    }
  } else {
    const solvers::BlockSparseMatrix& W = normals.W.blockSparseMatrix()
                                              ? *normals.W.blockSparseMatrix()
                                              : normals.W.bodySpaceOperator()->toBlockSparse();
    // Solver block of W <-> contact index, for the blocks that start at a contact's normal row.
    std::vector<int> contactOfBlock(W.blockCount(), -1), blockOfContact(contacts);
    int b = 0;
    for (int k = 0; k < contacts; ++k) {  // normal rows ascend with k
      while (b < W.blockCount() && W.blockOffset(b) < normals.normalRows[k]) ++b;
      blockOfContact[k] = b;
      contactOfBlock.at(b) = k;
    }
    for (int k = 0; k < contacts; ++k) {
      for (int e = W.rowBegin(blockOfContact[k]); e < W.rowEnd(blockOfContact[k]); ++e) {
        const int j = contactOfBlock[W.blockColumn(e)];
        if (j < 0) continue;
        columns.push_back(j);
        values.push_back(W.blockValues(e)[0]);  // (normal, normal) entry of the 3x3 block
      }
      rowStart.push_back(static_cast<int>(columns.size()));
    }
  }
  return solvers::BlockSparseMatrix::fromBlockCsr(
      std::vector<int>(contacts, 1), std::move(rowStart), std::move(columns), std::move(values));
}

bool penetratesBeyondSlop(std::span<const joints::RowBlock> contactBlocks,
                          const std::vector<geometry::ContactManifold>& manifolds,
                          const PenetrationSettings& settings) {
  if (settings.method != PenetrationMethod::SplitImpulse) return false;
  return std::any_of(contactBlocks.begin(), contactBlocks.end(), [&](const joints::RowBlock& b) {
    const geometry::ContactPoint& point =
        manifolds[contactManifold(b.sourceKey)].points[contactPoint(b.sourceKey)];
    return point.depth - settings.slop > 0.0;
  });
}

std::optional<solvers::SolverReport> correctPenetration(
    std::span<const joints::RowBlock> contactBlocks,
    const std::vector<geometry::ContactManifold>& manifolds, const PenetrationSettings& settings,
    double h, geometry::BodyState& state, const solvers::ContactSolver& solver,
    ArticulationStage* articulations, const VelocityProblemNormals* velocityProblem,
    const solvers::SolverOptions& sweep) {
  // Nothing beyond the slop: nothing to build (the common case of a resting stack).
  if (!penetratesBeyondSlop(contactBlocks, manifolds, settings)) return std::nullopt;
  auto pseudoVelocityTarget = [&](const joints::RowBlock& block) {
    const geometry::ContactPoint& point =
        manifolds[contactManifold(block.sourceKey)].points[contactPoint(block.sourceKey)];
    const double excess = point.depth - settings.slop;
    return excess > 0.0 ? -settings.beta * excess / h : 0.0;
  };
  joints::RowSet normals;
  normals.blocks.reserve(contactBlocks.size());
  for (const joints::RowBlock& block : contactBlocks) {
    joints::RowBlock normal;
    normal.kind = joints::RowKind::Unilateral;
    normal.bodyA = block.bodyA;
    normal.bodyB = block.bodyB;
    normal.jacobianA = block.jacobianA.topRows(1);
    normal.jacobianB = block.jacobianB.topRows(1);
    // Target separation speed for the pseudo-velocity; 0 keeps touching rows non-penetrating.
    normal.bias = joints::RowVector::Constant(1, pseudoVelocityTarget(block));
    normals.blocks.push_back(std::move(normal));
  }

  AssembledProblem assembled;
  const bool reusedVelocityProblem =
      velocityProblem != nullptr && velocityProblem->usable(normals.blocks.size());
  if (reusedVelocityProblem) {
    const auto contacts = static_cast<int>(normals.blocks.size());
    if (const auto* body = velocityProblem->W.bodySpaceOperator())  // stays in body space, O(rows)
      assembled.problem.W =
          solvers::DelassusOperator::bodySpace(std::make_shared<const solvers::BodySpaceDelassus>(
              body->selectRows(velocityProblem->normalRows)));
    else
      assembled.problem.W =
          solvers::DelassusOperator::blockSparse(normalNormalBlock(*velocityProblem));
    assembled.problem.blocks.assign(contacts, solvers::ConstraintBlock::unilateral());
    assembled.problem.q.resize(contacts);
    assembled.slots.resize(contacts);
    for (int k = 0; k < contacts; ++k) assembled.slots[k] = {k, 1};
  } else {
    assembled = ProblemAssembler().assemble(normals, state, articulations);
  }
  // The pseudo problem starts from zero pseudo-velocity: q is the bias alone, not J v.
  for (std::size_t k = 0; k < normals.blocks.size(); ++k)
    assembled.problem.q[assembled.slots[k].offset] = normals.blocks[k].bias[0];

  solvers::SolverOptions options = sweep;
  options.maxIterations = settings.iterations;
  options.tolerance = settings.tolerance;
  options.useWarmStart = false;
  const solvers::SolveOutcome outcome = solver.solve(assembled.problem, options);

  std::vector<Eigen::Vector3d> linear(state.size(), Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> angular(state.size(), Eigen::Vector3d::Zero());
  applyImpulsesTo(normals, assembled.slots, outcome.impulses, state, linear, angular);
  for (std::size_t i = 0; i < state.size(); ++i) {
    if (!state.isDynamic(i) || (linear[i].isZero(0.0) && angular[i].isZero(0.0))) continue;
    state.poses[i].position += h * linear[i];
    state.poses[i].rotation =
        geometry::integrateWorldRotation(state.poses[i].rotation, angular[i], h);
    state.refreshWorldInertia(i);
  }
  if (articulations != nullptr) {
    // The assembled path mapped the trees already; the reused W did not.
    if (reusedVelocityProblem) articulations->mapRows(normals, state, assembled.scratch.trees);
    articulations->applyPseudoImpulses(assembled.scratch.trees, assembled.slots, outcome.impulses,
                                       h, state);
  }
  return outcome.report;
}

}  // namespace coulomb::engine
