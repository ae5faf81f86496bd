// Rows on articulation links: which tree constraints are active (their rows are emitted by
// joints/tree/TreeRowBlocks), the trees' part of the Delassus operator and the impulses on joint
// velocities.
//
// A row side on link l (proxy origin c = the link frame origin) with body-twist Jacobian J_side
// (k x 6, (linear, angular) about c) is the joint-space row J_side * twistJacobian(l, c)
// (k x nv; docs/articulations.md). For every tree touched by an island's rows, the joint-space
// rows J_t give W += J_t M^-1 J_t^T column by column through impulse-level ABA
// (ArticulationImpulse::applyInverseMass, Featherstone 2008 Table 7.1 with zero velocity and
// gravity: one O(n) pass per row, M never formed), and the solved impulses give
// qd += M^-1 J_t^T lambda in one pass per tree.
#include <coulomb/engine/ArticulationStage.hpp>
#include <coulomb/engine/ProblemAssembler.hpp>
#include <coulomb/integrators/ArticulationIntegrator.hpp>
#include <coulomb/joints/tree/ArticulationImpulse.hpp>
#include <coulomb/joints/tree/TreeKinematics.hpp>
#include <coulomb/joints/tree/TreeRowBlocks.hpp>

#include <algorithm>

namespace coulomb::engine {

using joints::RowBlock;
using joints::RowKind;
using joints::tree::TreeJointType;

namespace {
// A limit row is emitted when the joint would end the step this close to (or past) its limit:
// [rad or m]. Small: the row is speculative (it lets the joint reach the limit exactly).
constexpr double kLimitMargin = 1e-4;

// Relative diagonal compliance of rows on a tree (see addDelassusBlocks).
constexpr double kRegularization = 1e-9;

// sourceKey layout of the stage's blocks: articulation slot in bits 32-47, then a kind bit
// (closure 31, motor 30, coupling 29, friction 28; none: a limit, (link << 1) | upper) and the
// index. Coupling blocks also carry a tag in bits 56-63 so that treeRows can recognise them among
// any blocks.
constexpr std::uint64_t kClosureBit = 1u << 31;
constexpr std::uint64_t kMotorBit = 1u << 30;
constexpr std::uint64_t kCouplingBit = 1u << 29;
constexpr std::uint64_t kFrictionBit = 1u << 28;
constexpr std::uint64_t kTagMask = 0xffull << 56;
constexpr std::uint64_t kCouplingTag = 0xc5ull << 56;

bool coversEveryRow(const std::vector<RowBlockSlot>& slots, const Eigen::VectorXd& lambda) {
  return !slots.empty() && lambda.size() >= slots.back().offset + slots.back().rows;
}
}  // namespace

void ArticulationStage::appendEdges(std::uint8_t owner, const RowContext& context,
                                    StepEdges& edges) {
  const double h = context.h;
  constraints_.clear();
  const auto add = [&](TreeConstraint c, ConstraintEdge edge) {
    edges.add(owner, static_cast<std::int32_t>(constraints_.size()), edge);
    constraints_.push_back(c);
  };
  for (std::size_t a = 0; a < records_.size(); ++a) {
    Record& r = records_[a];
    if (!r.alive || r.model->nv() == 0) continue;
    const auto representative = static_cast<std::int32_t>(r.linkBodies.front().index);
    for (int i = 0; i < r.model->linkCount(); ++i) {
      const joints::tree::TreeJoint& joint = r.model->link(i).joint;
      if (joint.type != TreeJointType::Revolute && joint.type != TreeJointType::Prismatic) continue;
      const double q = r.q[r.model->qIndex(i)], qd = r.qd[r.model->vIndex(i)];
      const double predicted = q + h * qd;
      const bool lower = std::isfinite(joint.lower) && predicted < joint.lower + kLimitMargin;
      const bool upper = std::isfinite(joint.upper) && predicted > joint.upper - kLimitMargin;
      if (!lower) r.lowerWarm[i] = 0.0;
      if (!upper) r.upperWarm[i] = 0.0;
      for (const auto& [active, kind] :
           {std::pair{lower, ConstraintKind::Lower}, std::pair{upper, ConstraintKind::Upper}}) {
        if (!active) continue;
        add({static_cast<std::int32_t>(a), kind, i}, {representative, ConstraintEdge::kNoBody});
      }
    }
    for (std::size_t m = 0; m < r.motors.size(); ++m) {  // always active
      add({static_cast<std::int32_t>(a), ConstraintKind::Motor, static_cast<std::int32_t>(m)},
          {representative, ConstraintEdge::kNoBody});
    }
    for (int i = 0; i < r.model->linkCount(); ++i) {  // joint friction: always active
      if (r.friction[i] <= 0.0) continue;
      add({static_cast<std::int32_t>(a), ConstraintKind::Friction, i},
          {representative, ConstraintEdge::kNoBody});
    }
    for (std::size_t c = 0; c < r.couplings.size(); ++c) {
      add({static_cast<std::int32_t>(a), ConstraintKind::Coupling, static_cast<std::int32_t>(c)},
          {representative, ConstraintEdge::kNoBody});
    }
    for (std::size_t c = 0; c < r.closures.size(); ++c) {
      const int linkB = r.closures[c].linkB;
      add({static_cast<std::int32_t>(a), ConstraintKind::Closure, static_cast<std::int32_t>(c)},
          {representative, linkB >= 0 ? representative : ConstraintEdge::kNoBody});
    }
  }
}

std::optional<Eigen::RowVectorXd> ArticulationStage::couplingRow(const RowBlock& block) const {
  const std::uint64_t key = block.sourceKey;
  if (block.kind != RowKind::Equality || (key & kTagMask) != kCouplingTag ||
      (key & kCouplingBit) == 0)
    return std::nullopt;
  const auto a = static_cast<std::size_t>((key >> 32) & 0xffffu);
  const auto c = static_cast<std::size_t>(key & 0x1fffffffu);
  if (a >= records_.size() || c >= records_[a].couplings.size()) return std::nullopt;
  const Record& r = records_[a];
  const JointCouplingDesc& coupling = r.couplings[c];
  if (!block.bodyA.valid() || block.bodyA.index != r.linkBodies[coupling.follower].index)
    return std::nullopt;
  return joints::tree::couplingJointRow(*r.model, coupling);
}

// The rows themselves come from joints/tree (TreeRowBlocks); the stage adds their identity
// (sourceKey: which articulation, which constraint), by which storeImpulses keeps warm starts.
RowBlock ArticulationStage::rowBlockOf(const TreeConstraint& c, const geometry::BodyState& state,
                                       double h) const {
  const Record& r = records_[c.articulation];
  const joints::tree::TreeRowFrame tree{*r.model, r.linkBodies, r.linkPoses,
                                        r.q,      r.qd,         r.errorReduction};
  const auto articulation = static_cast<std::uint64_t>(c.articulation) << 32;
  const auto index = static_cast<std::uint64_t>(c.index);
  RowBlock block;
  switch (c.kind) {
    case ConstraintKind::Closure: {
      const LoopClosureDesc& closure = r.closures[c.index];
      const geometry::BodyId bodyA = r.linkBodies[closure.linkA];
      const Eigen::Vector3d positionB =
          closure.linkB >= 0 ? state.poses[r.linkBodies[closure.linkB].index].position
                             : Eigen::Vector3d::Zero();
      block = joints::tree::closureRow(tree, closure, state.poses[bodyA.index].position, positionB,
                                       h, r.closureWarm[c.index]);
      block.sourceKey = articulation | kClosureBit | index;
      return block;
    }
    case ConstraintKind::Motor:
      block = joints::tree::motorRow(tree, r.motors[c.index], h, r.motorWarm[c.index]);
      block.sourceKey = articulation | kMotorBit | index;
      return block;
    case ConstraintKind::Friction:
      block =
          joints::tree::frictionRow(tree, c.index, r.friction[c.index], h, r.frictionWarm[c.index]);
      block.sourceKey = articulation | kFrictionBit | index;
      return block;
    case ConstraintKind::Coupling:
      // Tagged so that treeRows recognises it among any blocks (its joint-space row is given).
      block = joints::tree::couplingRow(tree, r.couplings[c.index], h, r.couplingWarm[c.index]);
      block.sourceKey = kCouplingTag | articulation | kCouplingBit | index;
      return block;
    case ConstraintKind::Lower:
    case ConstraintKind::Upper: {
      const bool lower = c.kind == ConstraintKind::Lower;
      block = joints::tree::limitRow(tree, c.index, lower, h,
                                     lower ? r.lowerWarm[c.index] : r.upperWarm[c.index]);
      block.sourceKey = articulation | (index << 1) | (lower ? 0u : 1u);
      return block;
    }
  }
  return block;
}

void ArticulationStage::emitRows(std::span<const std::int32_t> items, const RowContext& context,
                                 joints::RowSet& rows) {
  for (const std::int32_t k : items)
    rows.blocks.push_back(rowBlockOf(constraints_[k], context.state, context.h));
}

void ArticulationStage::storeImpulses(const joints::RowSet& rows, joints::BlockRange range,
                                      const std::vector<RowBlockSlot>& slots,
                                      const Eigen::VectorXd& lambda, const RowContext&) {
  for (std::size_t k = range.first; k < range.end(); ++k) {
    const std::uint64_t key = rows.blocks[k].sourceKey;
    Record& r = records_[(key >> 32) & 0xffffu];
    const auto impulse = lambda.segment(slots[k].offset, slots[k].rows);
    if ((key & kClosureBit) != 0) {
      const auto index = static_cast<std::size_t>(key & (kClosureBit - 1));
      int row = 0;
      for (int axis = 0; axis < 3; ++axis)
        if (r.closures[index].axes[axis]) r.closureWarm[index][axis] = impulse[row++];
    } else if ((key & kMotorBit) != 0) {
      r.motorWarm[key & (kMotorBit - 1)] = impulse[0];
    } else if ((key & kCouplingBit) != 0) {
      r.couplingWarm[key & (kCouplingBit - 1)] = impulse[0];
    } else if ((key & kFrictionBit) != 0) {
      r.frictionWarm[key & (kFrictionBit - 1)] = impulse[0];
    } else {
      const auto index = static_cast<std::size_t>(key & (kFrictionBit - 1));
      ((index & 1u) == 0 ? r.lowerWarm : r.upperWarm)[index >> 1] = impulse[0];
    }
  }
}

void ArticulationStage::mapRows(const joints::RowSet& rows, const geometry::BodyState& state,
                                TreeRowMap& map) const {
  map.count = 0;
  map.treeIndex.assign(records_.size(), -1);
  if (records_.empty()) return;  // no trees: no row can be on one
  // The map's tree of `articulation`, started (ABA at q now) when first touched.
  const auto treeOf = [&](std::int32_t articulation) -> TreeRowMap::Tree& {
    std::int32_t& index = map.treeIndex[static_cast<std::size_t>(articulation)];
    if (index < 0) {
      index = static_cast<std::int32_t>(map.count++);
      if (map.trees.size() < map.count) map.trees.emplace_back();
      TreeRowMap::Tree& tree = map.trees[static_cast<std::size_t>(index)];
      const Record& r = records_[static_cast<std::size_t>(articulation)];
      tree.articulation = articulation;
      tree.response.reset(*r.model, r.q);
      tree.blocks.clear();
    }
    return map.trees[static_cast<std::size_t>(index)];
  };
  // The next Jacobian slot of `tree`, sized k x nv (storage kept when the size repeats).
  const auto nextJacobian = [](TreeRowMap::Tree& tree) -> Eigen::MatrixXd& {
    if (tree.jacobians.size() <= tree.blocks.size()) tree.jacobians.emplace_back();
    return tree.jacobians[tree.blocks.size()];
  };
  for (int k = 0; k < static_cast<int>(rows.blocks.size()); ++k) {
    const RowBlock& block = rows.blocks[k];
    if (std::optional<Eigen::RowVectorXd> row = couplingRow(block)) {  // joint space already
      TreeRowMap::Tree& tree = treeOf(linkOfBody_[block.bodyA.index].articulation);
      nextJacobian(tree) = *row;
      tree.blocks.push_back(k);
      continue;
    }
    for (const bool sideB : {false, true}) {
      const geometry::BodyId& body = sideB ? block.bodyB : block.bodyA;
      if (!body.valid() || !isLink(body.index)) continue;
      const LinkRef link = linkOfBody_[body.index];
      const Record& r = records_[link.articulation];
      if (r.model->nv() == 0) continue;
      TreeRowMap::Tree& tree = treeOf(link.articulation);
      joints::tree::twistJacobian(*r.model, tree.response.kinematics(), link.link,
                                  state.poses[body.index].position, map.twist);
      const joints::RowJacobian& side = sideB ? block.jacobianB : block.jacobianA;
      if (!tree.blocks.empty() && tree.blocks.back() == k) {
        // both sides on this tree (a loop closure)
        tree.jacobians[tree.blocks.size() - 1].noalias() += side * map.twist;
      } else {
        Eigen::MatrixXd& jointRows = nextJacobian(tree);
        jointRows.resize(side.rows(), map.twist.cols());
        jointRows.noalias() = side * map.twist;
        tree.blocks.push_back(k);
      }
    }
  }
}

int ArticulationStage::addDelassusBlocks(const joints::RowSet& rows,
                                         const geometry::BodyState& state, TreeRowMap& map,
                                         DelassusBlocks& blocks) const {
  int degreesOfFreedom = 0;
  blocks.clear();
  mapRows(rows, state, map);
  for (std::size_t t = 0; t < map.count; ++t) {
    TreeRowMap::Tree& tree = map.trees[t];
    degreesOfFreedom += records_[tree.articulation].model->nv();
    // M^-1 J_t^T, one impulse-level ABA pass per row.
    if (map.minvJt.size() < tree.blocks.size()) map.minvJt.resize(tree.blocks.size());
    for (std::size_t i = 0; i < tree.blocks.size(); ++i) {
      const Eigen::MatrixXd& J = tree.jacobians[i];
      Eigen::MatrixXd& columns = map.minvJt[i];
      columns.resize(J.cols(), J.rows());
      for (Eigen::Index row = 0; row < J.rows(); ++row) {
        map.jointRow = J.row(row).transpose();
        tree.response.applyInverseMass(map.jointRow, map.column);
        columns.col(row) = map.column;
      }
    }
    // A tree with few joints cannot move along some row directions (a 1-DOF arm on a table has
    // no velocity along the hinge axis): those rows have W_rr = 0 and many rows on one tree make
    // W rank-deficient. A relative compliance kRegularization on the diagonal keeps W positive
    // definite; it changes a row's velocity by kRegularization * maxDiagonal * lambda, well below
    // any solver tolerance.
    double maxDiagonal = 0.0;
    for (std::size_t i = 0; i < tree.blocks.size(); ++i)
      for (Eigen::Index row = 0; row < tree.jacobians[i].rows(); ++row)
        maxDiagonal = std::max(maxDiagonal, tree.jacobians[i].row(row).dot(map.minvJt[i].col(row)));
    const double compliance = kRegularization * std::max(maxDiagonal, 1e-12);
    for (std::size_t i = 0; i < tree.blocks.size(); ++i)
      for (std::size_t j = 0; j < tree.blocks.size(); ++j) {
        blocks.emplace_back();
        DelassusBlock& block = blocks.back();
        block.row = tree.blocks[i];
        block.col = tree.blocks[j];
        block.order = static_cast<int>(blocks.size());
        block.value.noalias() = tree.jacobians[i] * map.minvJt[j];
        block.shift = i == j ? compliance : 0.0;
      }
  }
  // One entry per (row, col), in that order: a block shared by two trees (a contact between two
  // robots) is the sum of their parts in tree order, with the first tree's compliance.
  std::sort(blocks.begin(), blocks.end(), [](const DelassusBlock& l, const DelassusBlock& r) {
    return l.row != r.row ? l.row < r.row : l.col != r.col ? l.col < r.col : l.order < r.order;
  });
  std::size_t kept = 0;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    if (kept > 0 && blocks[kept - 1].row == blocks[b].row && blocks[kept - 1].col == blocks[b].col)
      blocks[kept - 1].value += blocks[b].value;
    else if (kept++ != b)
      blocks[kept - 1] = blocks[b];
  }
  blocks.resize(kept);
  for (DelassusBlock& block : blocks)
    if (block.shift != 0.0) block.value.diagonal().array() += block.shift;
  return degreesOfFreedom;
}

namespace {
// Each mapped tree's `change` = M^-1 J_t^T lambda (a mapped tree has at least one block, whose
// Jacobian has nv columns).
void jointImpulses(TreeRowMap& map, const std::vector<RowBlockSlot>& slots,
                   const Eigen::VectorXd& lambda) {
  for (std::size_t t = 0; t < map.count; ++t) {
    TreeRowMap::Tree& tree = map.trees[t];
    map.jointTau.setZero(tree.jacobians.front().cols());
    for (std::size_t i = 0; i < tree.blocks.size(); ++i) {
      const RowBlockSlot& slot = slots[tree.blocks[i]];
      map.jointTau.noalias() +=
          tree.jacobians[i].transpose() * lambda.segment(slot.offset, slot.rows);
    }
    tree.response.applyInverseMass(map.jointTau, tree.change);
  }
}
}  // namespace

void ArticulationStage::applyImpulses(TreeRowMap& map, const std::vector<RowBlockSlot>& slots,
                                      const Eigen::VectorXd& lambda, geometry::BodyState& state) {
  // Rows touched these trees: they keep the velocity-level step (no Runge-Kutta step over it).
  for (std::size_t t = 0; t < map.count; ++t)
    records_[map.trees[t].articulation].constrained = true;
  if (!coversEveryRow(slots, lambda)) return;  // a solve that returned no impulses
  jointImpulses(map, slots, lambda);
  for (std::size_t t = 0; t < map.count; ++t) {
    Record& r = records_[map.trees[t].articulation];
    r.qd += map.trees[t].change;
    updateProxies(r, state);
  }
}

void ArticulationStage::applyPseudoImpulses(TreeRowMap& map, const std::vector<RowBlockSlot>& slots,
                                            const Eigen::VectorXd& lambda, double h,
                                            geometry::BodyState& state) {
  if (!coversEveryRow(slots, lambda)) return;  // a solve that returned no impulses
  jointImpulses(map, slots, lambda);
  for (std::size_t t = 0; t < map.count; ++t) {
    Record& r = records_[map.trees[t].articulation];
    integrators::integrateConfiguration(*r.model, r.q, map.trees[t].change, h);
    updateProxies(r, state);
  }
}

}  // namespace coulomb::engine
