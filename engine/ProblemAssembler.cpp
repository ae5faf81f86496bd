#include <coulomb/engine/ArticulationStage.hpp>
#include <coulomb/engine/ProblemAssembler.hpp>

#include <Eigen/Geometry>

#include <map>
#include <utility>

namespace coulomb::engine {
namespace {

using Matrix6k = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;

bool carriesUnknowns(const geometry::BodyState& state, const geometry::BodyId& body) {
  return body.valid() && body.index < state.size() && state.isDynamic(body.index);
}

/// M_b^-1 J^T for one side of a block: (m^-1 J_lin^T ; I_world^-1 J_ang^T), 6 x k.
Matrix6k inverseMassTimesJacobianT(const geometry::BodyState& state, std::uint32_t body,
                                   const joints::RowJacobian& jacobian) {
  Matrix6k out(6, jacobian.rows());
  out.topRows<3>() = state.inverseMasses[body] * jacobian.leftCols<3>().transpose();
  out.bottomRows<3>() = state.worldInverseInertias[body] * jacobian.rightCols<3>().transpose();
  return out;
}

void appendSolverBlocks(const joints::RowBlock& block, std::vector<solvers::ConstraintBlock>& out) {
  using solvers::ConstraintBlock;
  switch (block.kind) {
    case joints::RowKind::Contact3D:
      out.push_back(ConstraintBlock::contact(block.friction));
      return;
    case joints::RowKind::Equality:
      for (int i = 0; i < block.rows(); ++i) out.push_back(ConstraintBlock::equality());
      return;
    case joints::RowKind::Unilateral:
      for (int i = 0; i < block.rows(); ++i) out.push_back(ConstraintBlock::unilateral());
      return;
    case joints::RowKind::Bounded:
      for (int i = 0; i < block.rows(); ++i)
        out.push_back(ConstraintBlock::bounded(block.lower[i], block.upper[i]));
      return;
  }
}

}  // namespace

AssembledProblem ProblemAssembler::assemble(const joints::RowSet& rows,
                                            const geometry::BodyState& state,
                                            const ArticulationStage* articulations) const {
  AssembledProblem out;
  const auto blockCount = static_cast<int>(rows.blocks.size());
  out.slots.resize(blockCount);
  std::vector<solvers::ConstraintBlock> solverBlocks;
  int size = 0;
  for (int k = 0; k < blockCount; ++k) {
    out.slots[k] = {size, rows.blocks[k].rows()};
    size += rows.blocks[k].rows();
    appendSolverBlocks(rows.blocks[k], solverBlocks);
  }

  // Which (block, side) touches each dynamic body, in block order (deterministic).
  struct Touch {
    int block;
    bool sideB;
  };
  std::map<std::uint32_t, std::vector<Touch>> touches;
  Eigen::VectorXd q(size);
  for (int k = 0; k < blockCount; ++k) {
    const joints::RowBlock& block = rows.blocks[k];
    Eigen::VectorXd u = block.bias;
    for (const bool sideB : {false, true}) {
      const geometry::BodyId& body = sideB ? block.bodyB : block.bodyA;
      if (!body.valid() || body.index >= state.size()) continue;
      const joints::RowJacobian& jac = sideB ? block.jacobianB : block.jacobianA;
      // q = J v* (kinematic bodies contribute their prescribed velocity, static ones zero).
      u += jac.leftCols<3>() * state.linearVelocities[body.index] +
           jac.rightCols<3>() * state.angularVelocities[body.index];
      if (carriesUnknowns(state, body)) touches[body.index].push_back({k, sideB});
    }
    q.segment(out.slots[k].offset, out.slots[k].rows) = u;
  }

  // W_kl = sum over shared bodies b of J_k,b M_b^-1 J_l,b^T, accumulated per pair of row blocks.
  std::map<std::pair<int, int>, Eigen::MatrixXd> pairBlocks;
  for (const auto& [body, list] : touches) {
    out.degreesOfFreedom += 6;
    std::vector<Matrix6k> minvJt;
    minvJt.reserve(list.size());
    for (const Touch& t : list) {
      const joints::RowBlock& b = rows.blocks[t.block];
      minvJt.push_back(inverseMassTimesJacobianT(state, body, t.sideB ? b.jacobianB : b.jacobianA));
    }
    for (std::size_t i = 0; i < list.size(); ++i) {
      const joints::RowBlock& bi = rows.blocks[list[i].block];
      const joints::RowJacobian& ji = list[i].sideB ? bi.jacobianB : bi.jacobianA;
      for (std::size_t j = 0; j < list.size(); ++j) {
        Eigen::MatrixXd contribution = ji * minvJt[j];
        auto [it, inserted] =
            pairBlocks.try_emplace({list[i].block, list[j].block}, std::move(contribution));
        if (!inserted) it->second += ji * minvJt[j];
      }
    }
  }

  // Rows on articulation links: the trees' joint-space part (their proxies carry no unknowns).
  if (articulations != nullptr)
    out.degreesOfFreedom += articulations->addDelassusBlocks(rows, state, pairBlocks);

  if (size <= settings_.denseRowLimit) {
    Eigen::MatrixXd W = Eigen::MatrixXd::Zero(size, size);
    for (const auto& [key, value] : pairBlocks)
      W.block(out.slots[key.first].offset, out.slots[key.second].offset, value.rows(),
              value.cols()) += value;
    out.problem.W = solvers::DelassusOperator::dense(std::move(W));
  } else {
    // Solver blocks: a Contact3D row block is one 3-row block, any other row is its own block.
    std::vector<int> firstSolverBlock(blockCount);
    std::vector<int> blockSizes;
    for (int k = 0; k < blockCount; ++k) {
      firstSolverBlock[k] = static_cast<int>(blockSizes.size());
      if (rows.blocks[k].kind == joints::RowKind::Contact3D)
        blockSizes.push_back(3);
      else
        blockSizes.insert(blockSizes.end(), rows.blocks[k].rows(), 1);
    }
    std::vector<solvers::MatrixBlockEntry> entries;
    for (const auto& [key, value] : pairBlocks) {
      const bool rowIs3 = rows.blocks[key.first].kind == joints::RowKind::Contact3D;
      const bool colIs3 = rows.blocks[key.second].kind == joints::RowKind::Contact3D;
      const int rowParts = rowIs3 ? 1 : static_cast<int>(value.rows());
      const int colParts = colIs3 ? 1 : static_cast<int>(value.cols());
      for (int a = 0; a < rowParts; ++a)
        for (int c = 0; c < colParts; ++c) {
          const int h = rowIs3 ? 3 : 1, w = colIs3 ? 3 : 1;
          solvers::MatrixBlockEntry entry;
          entry.row = firstSolverBlock[key.first] + a;
          entry.col = firstSolverBlock[key.second] + c;
          entry.values.reserve(h * w);
          for (int i = 0; i < h; ++i)
            for (int j = 0; j < w; ++j) entry.values.push_back(value(a * h + i, c * w + j));
          entries.push_back(std::move(entry));
        }
    }
    out.problem.W = solvers::DelassusOperator::blockSparse(
        solvers::BlockSparseMatrix(std::move(blockSizes), std::move(entries)));
  }
  out.problem.q = std::move(q);
  out.problem.blocks = std::move(solverBlocks);

  bool allWarm = blockCount > 0;
  for (const joints::RowBlock& b : rows.blocks) allWarm = allWarm && b.warmStart.size() == b.rows();
  if (allWarm) {
    Eigen::VectorXd warm(size);
    for (int k = 0; k < blockCount; ++k)
      warm.segment(out.slots[k].offset, out.slots[k].rows) = rows.blocks[k].warmStart;
    out.problem.warmStart = std::move(warm);
  }
  return out;
}

}  // namespace coulomb::engine
