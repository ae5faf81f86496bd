#pragma once
// Rows -> solver problem: the one translation between joints/ and solvers/ (ARCHITECTURE.md 1).
// W = J M^-1 J^T assembled block by block over the bodies the rows share, q = J v* + bias.
// Dense for small islands, 3x3-block sparse for large ones. Static/kinematic bodies and the world
// carry no unknowns (their inverse mass is 0), so their Jacobian halves never enter W.
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/joints/RowSet.hpp>
#include <coulomb/solvers/ContactProblem.hpp>

#include <vector>

namespace coulomb::engine {

class ArticulationStage;

struct AssemblySettings {
  // [scalar unknowns] Islands with at most this many rows get a dense W (a dense 3x3 block loop
  // is faster than sparse bookkeeping below ~100 rows); larger ones a block-sparse W.
  int denseRowLimit = 96;
  // Larger islands without articulation rows get W factored (solvers::BodySpaceDelassus: J and
  // M^-1 J^T per block side, O(rows)) instead of block-sparse (O(nnz W), ~28 3x3 blocks per
  // contact on a pyramid). Gauss-Seidel then sweeps in body space; false = block-sparse W.
  bool bodySpace = true;
};

/// Where each row block landed in the problem: its first unknown (offset into r) and row count.
struct RowBlockSlot {
  int offset = 0;
  int rows = 0;
};

struct AssembledProblem {
  solvers::ContactProblem problem;
  std::vector<RowBlockSlot> slots;  // one per RowSet block, in order
  int degreesOfFreedom = 0;         // 6 x (dynamic bodies touched), the m of nu = 3n/m
};

/// World inverse inertias, one per body slot: the velocity problem's may differ from the bodies'
/// own (JointStage::stabilizedInverseInertias).
using InverseInertias = std::vector<Eigen::Matrix3d>;

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
  [[nodiscard]] const AssemblySettings& settings() const { return settings_; }

 private:
  AssemblySettings settings_;
};

}  // namespace coulomb::engine
