#pragma once
// Rows -> solver problem: the one translation between joints/ and solvers/ (docs/architecture.md
// 1). W = J M^-1 J^T assembled block by block over the bodies the rows share, q = J v* + bias.
// 3x3-block sparse; large islands of free bodies keep W factored (body space). Static/kinematic
// bodies and the world carry no unknowns (their inverse mass is 0), so their Jacobian halves never
// enter W.
#include <coulomb/engine/TreeRowMap.hpp>
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/joints/RowSet.hpp>
#include <coulomb/solvers/ContactProblem.hpp>

#include <Eigen/Core>

#include <memory>
#include <span>
#include <vector>

namespace coulomb::engine {

class ArticulationStage;

struct AssemblySettings {
  // [scalar unknowns] Islands with at most this many rows get W's entries, block-sparse (the
  // form every solver works on; a dense W would be converted to it by every solve). Larger ones
  // keep W's factors too, and a Newton step there can be solved in body space: the contact-space
  // LU grows as rows^3, the body-space one with the bodies. Default 48 (16 contacts): columns of
  // 5-8 boxes landing in box_pile_1000 took 3.9 s over the pile's first 60 steps at 96 rows, 3.4
  // at 72, 3.2-3.3 at 48 and 24; a box or two (up to 16 contacts) keep the entries' start sweep
  // (docs/benchmarks.md "Columns in body space").
  int sparseRowLimit = 48;
  // Larger islands without articulation rows, and islands of equality rows only at any size (a
  // joint island, solved by ldlt from the factors), get W factored (solvers::BodySpaceDelassus: J
  // and M^-1 J^T per block side, O(rows)) instead of block-sparse (O(nnz W), ~28 3x3 blocks per
  // contact on a pyramid). Gauss-Seidel then sweeps in body space; false = block-sparse W.
  bool bodySpace = true;
};

/// Where each row block landed in the problem: its first unknown (offset into r) and row count.
struct RowBlockSlot {
  int offset = 0;
  int rows = 0;
};

/// A block (row block, row block) of W's trees' part; a row block has at most 6 rows.
struct DelassusBlock {
  int row = 0, col = 0;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor, 6, 6> value;
  int order = 0;       // emission order (the tree order for a block two trees share)
  double shift = 0.0;  // the emitting tree's diagonal compliance, added once per block
};
/// Sorted by (row, col), one entry per pair, as ProblemAssembler reads them. A vector kept by
/// the caller: cleared and refilled, never reallocated once it has held as many blocks.
using DelassusBlocks = std::vector<DelassusBlock>;

/// One side of a row block on a dynamic body (the assembler's bookkeeping).
struct AssemblyTouch {
  std::uint32_t body = 0;
  int block = 0;
  bool sideB = false;
};

/// What assemble() needs between its passes, kept with the problem so that assembling an island
/// of the same shape again reuses every buffer: a steady step allocates nothing here. W's storage
/// is reused only when no copy of the last problem still shares it.
struct AssemblyScratch {
  using Matrix6k = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;
  using BlockMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor, 6, 6>;
  std::vector<AssemblyTouch> touches, sorted;
  std::vector<Matrix6k> minvJt;  // M^-1 J^T per (block, side)
  std::vector<int> next, groupOfSide, groupStart, columns, blockSizes;
  std::vector<BlockMatrix> strip;
  std::vector<int> firstSolverBlock, csrBlockSizes, rowStart, blockColumns;
  std::vector<double> values;
  std::shared_ptr<solvers::BlockSparseMatrix> sparse;
  std::shared_ptr<solvers::BodySpaceDelassus> bodySpace;
  DelassusBlocks treeBlocks;  // the articulations' part of W
  TreeRowMap trees;           // the trees the rows touch, for W and then the impulses
};

struct AssembledProblem {
  solvers::ContactProblem problem;
  std::vector<RowBlockSlot> slots;  // one per RowSet block, in order
  int degreesOfFreedom = 0;         // 6 x (dynamic bodies touched), the m of nu = 3n/m
  AssemblyScratch scratch;
};

/// World inverse inertias, one per body slot: the velocity problem's may differ from the bodies'
/// own (JointStage::stabilizedInverseInertias).
using InverseInertias = std::vector<Eigen::Matrix3d>;

/// The bodies' velocities at the step's start, before its forces (v_k, by body slot): with
/// them the assembler also gives ContactProblem::arrival.
struct ArrivalVelocities {
  std::span<const Eigen::Vector3d> linear, angular;
};

class ProblemAssembler {
 public:
  explicit ProblemAssembler(AssemblySettings settings = {}) : settings_(settings) {}

  /// The rows' bodies index `state` by BodyId::index; an invalid id is the world. Warm starts
  /// are taken from each block's `warmStart` when all blocks have one of the right size.
  /// `articulations`: rows on link proxies get the trees' part of W (ArticulationStage.hpp).
  /// `inverseInertias`: the world inverse inertias to use (nullptr: state.worldInverseInertias).
  [[nodiscard]] AssembledProblem assemble(const joints::RowSet& rows,
                                          const geometry::BodyState& state,
                                          const ArticulationStage* articulations = nullptr,
                                          const InverseInertias* inverseInertias = nullptr) const;
  /// The same into `out`, reusing its storage (the World's per-island problems); with
  /// `arrival`, also ContactProblem::arrival (for a body-space W).
  void assemble(const joints::RowSet& rows, const geometry::BodyState& state,
                const ArticulationStage* articulations, const InverseInertias* inverseInertias,
                AssembledProblem& out, const ArrivalVelocities* arrival = nullptr) const;
  [[nodiscard]] const AssemblySettings& settings() const { return settings_; }

 private:
  AssemblySettings settings_;
};

/// The rows' velocities at the step's start, J v_k, on the bodies that carry unknowns (a
/// body-space W forms the same from ContactProblem::arrival): for an assembled problem with W's
/// entries, when its solve asks (solvers::ArrivalRowVelocities). Rows on tree links get only
/// their free bodies' part.
void arrivalRowVelocities(const joints::RowSet& rows, const geometry::BodyState& state,
                          const ArrivalVelocities& arrival, const std::vector<RowBlockSlot>& slots,
                          Eigen::VectorXd& out);

}  // namespace coulomb::engine
