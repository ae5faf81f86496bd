#include <coulomb/engine/ArticulationStage.hpp>
#include <coulomb/engine/ProblemAssembler.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <compare>
#include <memory>
#include <utility>

namespace coulomb::engine {
namespace {

using Matrix6k = AssemblyScratch::Matrix6k;
using BlockMatrix = AssemblyScratch::BlockMatrix;
// BodySpaceDelassus::setSide reads these layouts raw: J rows of 6, M^-1 J^T columns of 6.
static_assert(joints::RowJacobian::IsRowMajor && joints::RowJacobian::ColsAtCompileTime == 6);
static_assert(!Matrix6k::IsRowMajor && Matrix6k::RowsAtCompileTime == 6);

using Touch = AssemblyTouch;  // grouped by body, block order inside

bool carriesUnknowns(const geometry::BodyState& state, const geometry::BodyId& body) {
  return body.valid() && body.index < state.size() && state.isDynamic(body.index);
}

/// M_b^-1 J^T for one side of a block: (m^-1 J_lin^T ; I_world^-1 J_ang^T), 6 x k.
void inverseMassTimesJacobianT(const geometry::BodyState& state,
                               const std::vector<Eigen::Matrix3d>& inverseInertias,
                               std::uint32_t body, const joints::RowJacobian& jacobian,
                               Matrix6k& out) {
  if (jacobian.rows() == 3) {  // contacts and ball joints: fixed sizes (no dynamic products)
    using J3 = Eigen::Matrix<double, 3, 6, Eigen::RowMajor>;
    const Eigen::Map<const J3> rows(jacobian.data());
    out.resize(6, 3);
    Eigen::Map<Eigen::Matrix<double, 6, 3>> columns(out.data());
    columns.topRows<3>() = state.inverseMasses[body] * rows.leftCols<3>().transpose();
    columns.bottomRows<3>() = inverseInertias[body] * rows.rightCols<3>().transpose();
    return;
  }
  out.resize(6, jacobian.rows());
  out.topRows<3>() = state.inverseMasses[body] * jacobian.leftCols<3>().transpose();
  out.bottomRows<3>() = inverseInertias[body] * jacobian.rightCols<3>().transpose();
}

// value += J_k,b (M_b^-1 J_j,b^T): fixed-size when both are contact blocks (3 x 6 times 6 x 3,
// the common case), where Eigen's dynamic-size product costs several times the arithmetic.
void addSharedBodyProduct(const joints::RowJacobian& jk, const Matrix6k& minvJtj,
                          BlockMatrix& value) {
  if (jk.rows() == 3 && minvJtj.cols() == 3) {
    using J3 = Eigen::Matrix<double, 3, 6, Eigen::RowMajor>;
    using MJ3 = Eigen::Matrix<double, 6, 3>;
    const Eigen::Matrix3d product =
        Eigen::Map<const J3>(jk.data()) * Eigen::Map<const MJ3>(minvJtj.data());
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 3; ++c) value(i, c) += product(i, c);
    return;
  }
  value.noalias() += jk * minvJtj;
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

// W in block-CSR form over the solver blocks (a Contact3D row block is one 3-row solver block,
// any other row its own 1-row block), filled row block by row block in increasing order.
class SparseRowsBuilder {
 public:
  SparseRowsBuilder(const joints::RowSet& rows, int blockCount, AssemblyScratch& scratch)
      : rows_(rows),
        firstSolverBlock_(scratch.firstSolverBlock),
        blockSizes_(scratch.csrBlockSizes),
        rowStart_(scratch.rowStart),
        blockColumns_(scratch.blockColumns),
        values_(scratch.values) {
    firstSolverBlock_.resize(blockCount);
    blockSizes_.clear();
    for (int k = 0; k < blockCount; ++k) {
      firstSolverBlock_[k] = static_cast<int>(blockSizes_.size());
      if (isContact(k))
        blockSizes_.push_back(3);
      else
        blockSizes_.insert(blockSizes_.end(), rows.blocks[k].rows(), 1);
    }
    rowStart_.assign(1, 0);
    blockColumns_.clear();
    values_.clear();
  }

  // The nonzero blocks (k, columns[c]) = strip[c] of row block k, columns ascending.
  void addRowBlock(int k, const std::vector<int>& columns, const std::vector<BlockMatrix>& strip) {
    const bool rowIs3 = isContact(k);
    const int rowParts = rowIs3 ? 1 : rows_.blocks[k].rows();
    const int height = rowIs3 ? 3 : 1;
    for (int a = 0; a < rowParts; ++a) {
      for (std::size_t c = 0; c < columns.size(); ++c) {
        const int j = columns[c];
        const bool colIs3 = isContact(j);
        const int colParts = colIs3 ? 1 : rows_.blocks[j].rows();
        const int width = colIs3 ? 3 : 1;
        for (int part = 0; part < colParts; ++part) {
          blockColumns_.push_back(firstSolverBlock_[j] + part);
          for (int i = 0; i < height; ++i)
            for (int w = 0; w < width; ++w)
              values_.push_back(strip[c](a * height + i, part * width + w));
        }
      }
      rowStart_.push_back(static_cast<int>(blockColumns_.size()));
    }
  }

  void build(solvers::BlockSparseMatrix& out) const {
    out.adoptBlockCsr(blockSizes_, rowStart_, blockColumns_, values_);
  }

 private:
  [[nodiscard]] bool isContact(int k) const {
    return rows_.blocks[k].kind == joints::RowKind::Contact3D;
  }
  const joints::RowSet& rows_;
  std::vector<int>&firstSolverBlock_, &blockSizes_, &rowStart_, &blockColumns_;
  std::vector<double>& values_;
};

// Appends the blocks on block k's bodies, ascending, once each: a merge of its (at most two) body
// groups, each already in block order (a block on one body twice is there twice, side by side).
inline void appendBodyColumns(int k, const AssemblyScratch& scratch, std::vector<int>& columns) {
  const std::vector<AssemblyTouch>& touches = scratch.touches;
  const std::vector<int>&groupOfSide = scratch.groupOfSide, &groupStart = scratch.groupStart;
  const std::size_t first = columns.size();
  int g0 = groupOfSide[2 * k], g1 = groupOfSide[2 * k + 1];
  if (g1 == g0) g1 = -1;          // one body on both sides: its group once
  if (g0 < 0) std::swap(g0, g1);  // g0 is a group whenever k has one
  int t0 = g0 >= 0 ? groupStart[g0] : 0, t1 = g1 >= 0 ? groupStart[g1] : 0;
  const int end0 = g0 >= 0 ? groupStart[g0 + 1] : 0, end1 = g1 >= 0 ? groupStart[g1 + 1] : 0;
  while (t0 < end0 || t1 < end1) {
    const int j = t1 >= end1 || (t0 < end0 && touches[t0].block <= touches[t1].block)
                      ? touches[t0++].block
                      : touches[t1++].block;
    if (columns.size() == first || columns.back() != j) columns.push_back(j);
  }
}

// W of an island of contact blocks only (the common small island): its 3 x 3 blocks straight
// into block-CSR, each pair (k, j) computed once and mirrored (W_jk = W_kj^T, and the diagonal
// blocks' upper triangles, so W is exactly symmetric). The block pattern is symmetric: j is in row
// k when the two share a dynamic body.
void assembleContactBlocks(const joints::RowSet& rows, AssemblyScratch& scratch,
                           solvers::BlockSparseMatrix& out) {
  using J3 = Eigen::Matrix<double, 3, 6, Eigen::RowMajor>;
  using MJ3 = Eigen::Matrix<double, 6, 3>;
  using Block3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  const auto blockCount = static_cast<int>(rows.blocks.size());
  const std::vector<int>& groupOfSide = scratch.groupOfSide;
  std::vector<int>&rowStart = scratch.rowStart, &columns = scratch.blockColumns;
  // The pattern: row k's columns are the blocks on k's bodies, ascending, once each.
  rowStart.assign(1, 0);
  columns.clear();
  for (int k = 0; k < blockCount; ++k) {
    appendBodyColumns(k, scratch, columns);
    rowStart.push_back(static_cast<int>(columns.size()));
  }
  std::vector<double>& values = scratch.values;
  values.resize(9 * columns.size());
  // Entries below the diagonal are filled from above: row j's columns k < j arrive in increasing
  // k, so a cursor per row finds each mirror position.
  std::vector<int>& mirror = scratch.next;
  mirror.assign(rowStart.begin(), rowStart.end() - 1);
  for (int k = 0; k < blockCount; ++k) {
    const joints::RowBlock& bk = rows.blocks[k];
    // k's body groups in increasing body index (the summation order of the general path).
    int groups[2] = {groupOfSide[2 * k], groupOfSide[2 * k + 1]};
    const joints::RowJacobian* sides[2] = {&bk.jacobianA, &bk.jacobianB};
    if (groups[0] >= 0 && groups[1] >= 0 && groups[1] < groups[0]) {
      std::swap(groups[0], groups[1]);
      std::swap(sides[0], sides[1]);
    }
    for (int e = rowStart[k]; e < rowStart[k + 1]; ++e) {
      const int j = columns[e];
      if (j < k) continue;  // mirrored from row j
      Block3 value = Block3::Zero();
      for (int g = 0; g < 2; ++g) {
        if (groups[g] < 0) continue;
        const Eigen::Map<const J3> jk(sides[g]->data());
        for (int side = 0; side < 2; ++side)
          if (groupOfSide[2 * j + side] == groups[g])
            value.noalias() += jk * Eigen::Map<const MJ3>(scratch.minvJt[2 * j + side].data());
      }
      if (j == k) {  // the upper triangle, mirrored
        value(1, 0) = value(0, 1);
        value(2, 0) = value(0, 2);
        value(2, 1) = value(1, 2);
      }
      Eigen::Map<Block3>(values.data() + 9 * e) = value;
      if (j > k) Eigen::Map<Block3>(values.data() + 9 * mirror[j]++) = value.transpose();
    }
  }
  std::vector<int>& sizes = scratch.csrBlockSizes;
  sizes.assign(blockCount, 3);
  out.adoptBlockCsr(sizes, rowStart, columns, values);
}

// `kept` when no operator shares it any more (refilled in place), else a fresh one.
template <class T>
T& reusable(std::shared_ptr<T>& kept) {
  if (!kept || kept.use_count() > 1) kept = std::make_shared<T>();
  return *kept;
}

}  // namespace

AssembledProblem ProblemAssembler::assemble(const joints::RowSet& rows,
                                            const geometry::BodyState& state,
                                            const ArticulationStage* articulations,
                                            const InverseInertias* inverseInertias) const {
  AssembledProblem out;
  assemble(rows, state, articulations, inverseInertias, out);
  return out;
}

void ProblemAssembler::assemble(const joints::RowSet& rows, const geometry::BodyState& state,
                                const ArticulationStage* articulations,
                                const InverseInertias* inverseInertias, AssembledProblem& out,
                                const ArrivalVelocities* arrival) const {
  const InverseInertias& inertias =
      inverseInertias != nullptr ? *inverseInertias : state.worldInverseInertias;
  AssemblyScratch& scratch = out.scratch;
  out.problem.W = solvers::DelassusOperator();  // releases last step's W for reuse
  out.problem.name.clear();
  const auto blockCount = static_cast<int>(rows.blocks.size());
  out.slots.resize(blockCount);
  std::vector<solvers::ConstraintBlock>& solverBlocks = out.problem.blocks;
  solverBlocks.clear();
  int size = 0;
  for (int k = 0; k < blockCount; ++k) {
    out.slots[k] = {size, rows.blocks[k].rows()};
    size += rows.blocks[k].rows();
    appendSolverBlocks(rows.blocks[k], solverBlocks);
  }

  // q = J v* + bias (kinematic bodies contribute their prescribed velocity, static ones zero),
  // and the (block, side) pairs on dynamic bodies with their M_b^-1 J^T.
  Eigen::VectorXd& q = out.problem.q;
  q.resize(size);
  std::vector<Touch>& touches = scratch.touches;
  touches.clear();
  std::vector<Matrix6k>& minvJt = scratch.minvJt;
  minvJt.resize(2 * blockCount);
  for (int k = 0; k < blockCount; ++k) {
    const joints::RowBlock& block = rows.blocks[k];
    joints::RowVector u = block.bias;
    for (const bool sideB : {false, true}) {
      const geometry::BodyId& body = sideB ? block.bodyB : block.bodyA;
      if (!body.valid() || body.index >= state.size()) continue;
      const joints::RowJacobian& jac = sideB ? block.jacobianB : block.jacobianA;
      if (jac.rows() == 3) {  // fixed sizes, as inverseMassTimesJacobianT
        const Eigen::Map<const Eigen::Matrix<double, 3, 6, Eigen::RowMajor>> rows3(jac.data());
        u.head<3>() += rows3.leftCols<3>() * state.linearVelocities[body.index] +
                       rows3.rightCols<3>() * state.angularVelocities[body.index];
      } else {
        u += jac.leftCols<3>() * state.linearVelocities[body.index] +
             jac.rightCols<3>() * state.angularVelocities[body.index];
      }
      if (!carriesUnknowns(state, body)) continue;
      touches.push_back({body.index, k, sideB});
      inverseMassTimesJacobianT(state, inertias, body.index, jac, minvJt[2 * k + (sideB ? 1 : 0)]);
    }
    q.segment(out.slots[k].offset, out.slots[k].rows) = u;
  }
  // Grouped by body, in block order inside a body (deterministic): a stable counting sort by
  // body gives std::sort's order, as the touches were appended in (block, side) order. Its
  // counts span the world's bodies when they are no more than the touches (one island holding
  // the world), else the island's range of body indices, found in one pass over the touches:
  // one island among many costs what its own bodies do.
  if (!touches.empty()) {
    std::uint32_t lowest = 0, highest = static_cast<std::uint32_t>(state.size() - 1);
    if (state.size() > touches.size()) {
      lowest = highest = touches.front().body;
      for (const Touch& t : touches) {
        lowest = std::min(lowest, t.body);
        highest = std::max(highest, t.body);
      }
    }
    std::vector<int>& next = scratch.next;
    next.assign(highest - lowest + 2, 0);
    for (const Touch& t : touches) ++next[t.body - lowest + 1];
    for (std::size_t b = 1; b < next.size(); ++b) next[b] += next[b - 1];
    std::vector<Touch>& sorted = scratch.sorted;
    sorted.resize(touches.size());
    for (const Touch& t : touches) sorted[next[t.body - lowest]++] = t;
    touches.swap(sorted);
  }
  std::vector<int>& groupOfSide = scratch.groupOfSide;  // (block, side) -> its body's group
  groupOfSide.assign(2 * blockCount, -1);
  std::vector<int>& groupStart = scratch.groupStart;
  groupStart.clear();
  for (int t = 0; t < static_cast<int>(touches.size()); ++t) {
    if (t == 0 || touches[t].body != touches[t - 1].body) groupStart.push_back(t);
    groupOfSide[2 * touches[t].block + (touches[t].sideB ? 1 : 0)] =
        static_cast<int>(groupStart.size()) - 1;
  }
  groupStart.push_back(static_cast<int>(touches.size()));
  out.degreesOfFreedom = 6 * (static_cast<int>(groupStart.size()) - 1);

  // Rows on articulation links: the trees' joint-space part (their proxies carry no unknowns).
  DelassusBlocks& treeBlocks = scratch.treeBlocks;
  treeBlocks.clear();
  scratch.trees.count = 0;  // no trees unless the stage maps some
  if (articulations != nullptr)
    out.degreesOfFreedom +=
        articulations->addDelassusBlocks(rows, state, scratch.trees, treeBlocks);

  // One warm-started block makes the island's warm start; a block without one (a contact new this
  // step) starts at r = 0 within it. Dropping the whole start for one new contact made a settling
  // packing or a landing column solve cold on every step that a contact appeared.
  bool anyWarm = false;
  for (const joints::RowBlock& b : rows.blocks) anyWarm = anyWarm || b.warmStart.size() == b.rows();
  if (anyWarm) {
    if (!out.problem.warmStart) out.problem.warmStart.emplace();
    Eigen::VectorXd& warm = *out.problem.warmStart;
    warm.resize(size);
    for (int k = 0; k < blockCount; ++k) {
      const joints::RowBlock& b = rows.blocks[k];
      auto slot = warm.segment(out.slots[k].offset, out.slots[k].rows);
      if (b.warmStart.size() == b.rows())
        slot = b.warmStart;
      else
        slot.setZero();
    }
  } else {
    out.problem.warmStart.reset();
  }

  // Equality rows only (a joint island: ldlt forms its 3 x 3 blocks from the factors) keep W
  // factored at any size; other small islands get W's entries (Newton's dense path needs them).
  bool equalityOnly = true;
  for (const joints::RowBlock& b : rows.blocks)
    equalityOnly = equalityOnly && b.kind == joints::RowKind::Equality;
  const bool small = size <= settings_.sparseRowLimit && !equalityOnly;
  if (!small && treeBlocks.empty() && settings_.bodySpace) {
    // Large islands of free bodies: W stays factored (J, M^-1 J^T per side; BodySpaceDelassus),
    // O(rows) to build; Gauss-Seidel never forms W, other solvers build it once on demand.
    std::vector<int>& sizes = scratch.blockSizes;
    sizes.clear();
    for (const solvers::ConstraintBlock& b : out.problem.blocks) sizes.push_back(b.size());
    if (!scratch.bodySpace || scratch.bodySpace.use_count() > 1)
      scratch.bodySpace = std::make_shared<solvers::BodySpaceDelassus>(0, std::vector<int>{});
    solvers::BodySpaceDelassus* factors = scratch.bodySpace.get();
    factors->reset(static_cast<int>(groupStart.size()) - 1, sizes);
    int solverBlock = 0;
    for (int k = 0; k < blockCount; ++k) {
      const joints::RowBlock& bk = rows.blocks[k];
      const bool contact = bk.kind == joints::RowKind::Contact3D;
      const int parts = contact ? 1 : bk.rows(), height = contact ? 3 : 1;
      for (int part = 0; part < parts; ++part, ++solverBlock)
        for (const int side : {0, 1}) {
          if (groupOfSide[2 * k + side] < 0) continue;
          // Raw rows: J row-major (6 per row), M^-1 J^T column-major (6 per column), so the
          // rows of part `part` start 6 * height * part further on in both (no temporaries).
          const joints::RowJacobian& jac = side == 1 ? bk.jacobianB : bk.jacobianA;
          factors->setSide(solverBlock, side, groupOfSide[2 * k + side],
                           jac.data() + 6 * height * part,
                           minvJt[2 * k + side].data() + 6 * height * part);
        }
    }
    out.problem.W = solvers::DelassusOperator::bodySpace(scratch.bodySpace);
    // The bodies' velocities at the step's start, in the operator's body order (ContactProblem).
    const int groups = static_cast<int>(groupStart.size()) - 1;
    if (arrival != nullptr && arrival->linear.size() >= state.size() &&
        arrival->angular.size() >= state.size()) {
      out.problem.arrival.resize(6 * groups);
      for (int g = 0; g < groups; ++g) {
        const std::uint32_t body = touches[groupStart[g]].body;
        out.problem.arrival.segment<3>(6 * g) = arrival->linear[body];
        out.problem.arrival.segment<3>(6 * g + 3) = arrival->angular[body];
      }
    } else {
      out.problem.arrival.resize(0);
    }
    return;
  }
  out.problem.arrival.resize(0);  // used with a body-space W only

  bool contactsOnly = treeBlocks.empty();
  for (const joints::RowBlock& b : rows.blocks)
    contactsOnly = contactsOnly && b.kind == joints::RowKind::Contact3D && b.rows() == 3;
  if (contactsOnly) {
    assembleContactBlocks(rows, scratch, reusable(scratch.sparse));
    out.problem.W = solvers::DelassusOperator::blockSparse(scratch.sparse);
    return;
  }

  // W_kj = sum over the bodies b shared by blocks k and j (in increasing body index) of
  // J_k,b M_b^-1 J_j,b^T, plus the trees' part; built row block by row block, columns ascending.
  SparseRowsBuilder sparse(rows, blockCount, scratch);
  std::vector<int>& columns = scratch.columns;
  std::vector<BlockMatrix>& strip = scratch.strip;
  auto tree = treeBlocks.begin();
  for (int k = 0; k < blockCount; ++k) {
    const joints::RowBlock& bk = rows.blocks[k];
    // The body groups of block k, in increasing body index (the summation order).
    int groups[2] = {groupOfSide[2 * k], groupOfSide[2 * k + 1]};
    bool sidesOfGroup[2] = {false, true};
    if (groups[0] >= 0 && groups[1] >= 0 && groups[1] < groups[0]) {
      std::swap(groups[0], groups[1]);
      std::swap(sidesOfGroup[0], sidesOfGroup[1]);
    }
    columns.clear();
    appendBodyColumns(k, scratch, columns);
    const auto treeBegin = tree;
    for (; tree != treeBlocks.end() && tree->row == k; ++tree) columns.push_back(tree->col);
    if (tree != treeBegin) {  // the trees' columns among the bodies' ones
      std::sort(columns.begin(), columns.end());
      columns.erase(std::unique(columns.begin(), columns.end()), columns.end());
    }

    strip.resize(columns.size());
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const int j = columns[c];
      BlockMatrix& value = strip[c];
      value.setZero(bk.rows(), rows.blocks[j].rows());
      for (int g = 0; g < 2; ++g) {
        if (groups[g] < 0) continue;
        const joints::RowJacobian& jk = sidesOfGroup[g] ? bk.jacobianB : bk.jacobianA;
        for (const int side : {0, 1})
          if (groupOfSide[2 * j + side] == groups[g])
            addSharedBodyProduct(jk, minvJt[2 * j + side], value);
      }
      for (auto it = treeBegin; it != tree; ++it)
        if (it->col == j) value += it->value;
    }
    sparse.addRowBlock(k, columns, strip);
  }

  sparse.build(reusable(scratch.sparse));
  out.problem.W = solvers::DelassusOperator::blockSparse(scratch.sparse);
}

void arrivalRowVelocities(const joints::RowSet& rows, const geometry::BodyState& state,
                          const ArrivalVelocities& arrival, const std::vector<RowBlockSlot>& slots,
                          Eigen::VectorXd& out) {
  int size = 0;
  for (const RowBlockSlot& slot : slots) size += slot.rows;
  out.setZero(size);
  if (arrival.linear.size() < state.size() || arrival.angular.size() < state.size()) return;
  for (std::size_t k = 0; k < rows.blocks.size() && k < slots.size(); ++k) {
    const joints::RowBlock& block = rows.blocks[k];
    for (const bool sideB : {false, true}) {
      const geometry::BodyId& body = sideB ? block.bodyB : block.bodyA;
      if (!carriesUnknowns(state, body)) continue;
      const joints::RowJacobian& jac = sideB ? block.jacobianB : block.jacobianA;
      out.segment(slots[k].offset, slots[k].rows) +=
          jac.leftCols<3>() * arrival.linear[body.index] +
          jac.rightCols<3>() * arrival.angular[body.index];
    }
  }
}

}  // namespace coulomb::engine
