#pragma once
// Position-level removal of contact penetration without adding kinetic energy: split impulse
// (Catto, "Iterative Dynamics", GDC 2006; Bullet's splitImpulse). After the velocity solve, a
// second, frictionless problem on the normal rows finds pseudo-impulses p >= 0 with
//     W_NN p - beta max(depth - slop, 0) / h  >= 0  _|_  p >= 0,
// whose pseudo-velocities M^-1 J_N^T p move the positions by h v_p and are then discarded: the
// real velocities never see them, so a resting stack gains no energy from being pushed apart.
#include <coulomb/engine/ArticulationStage.hpp>
#include <coulomb/engine/ContactSource.hpp>
#include <coulomb/engine/ProblemAssembler.hpp>
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/joints/RowSet.hpp>
#include <coulomb/solvers/ContactSolver.hpp>
#include <coulomb/solvers/SolverReport.hpp>

#include <optional>
#include <span>
#include <vector>

namespace coulomb::engine {

/// Where the contact normals sit in the island's velocity problem: its W (shared, not copied)
/// and, per contact row block, the index of its normal row in W. The split impulse reuses
/// W's normal-normal entries instead of assembling a second problem: J_N M^-1 J_N^T is the same
/// matrix up to the step's change of the world inverse inertias (O(h |omega|), far below what
/// a 20-sweep pseudo-solve resolves).
struct VelocityProblemNormals {
  solvers::DelassusOperator W;
  std::vector<int> normalRows;

  [[nodiscard]] bool usable(std::size_t contacts) const {
    return W.rows() > 0 && normalRows.size() == contacts;
  }
};

/// W_NN of the contacts as a block-sparse matrix of 1-row blocks (columns ascending).
solvers::BlockSparseMatrix normalNormalBlock(const VelocityProblemNormals& normals);

/// Whether the split impulse has work: a contact deeper than the slop (correctPenetration
/// returns nullopt otherwise). Lets the step skip setting up the pseudo-solve on a resting island.
[[nodiscard]] bool penetratesBeyondSlop(std::span<const joints::RowBlock> contactBlocks,
                                        const std::vector<geometry::ContactManifold>& manifolds,
                                        const PenetrationSettings& settings);

/// Split impulse: moves the island's dynamic bodies out of penetration (positions and
/// orientations only), given the contact blocks of the step (their sourceKey names the manifold
/// point whose depth is read). `solver` solves the pseudo problem (PenetrationSettings::solver).
/// Returns the pseudo-solve's report (status, sweeps), or nullopt when nothing penetrates.
/// `articulations`: rows on link proxies move their trees' joint positions as well.
/// `velocityProblem`: the island's velocity problem, whose W_NN is reused when given (else the
/// normal rows are assembled again). `sweep`: the options the pseudo-solve starts from (the
/// World's: its split sweeps and threads); iterations, tolerance and warm start are `settings`'.
std::optional<solvers::SolverReport> correctPenetration(
    std::span<const joints::RowBlock> contactBlocks,
    const std::vector<geometry::ContactManifold>& manifolds, const PenetrationSettings& settings,
    double h, geometry::BodyState& state, const solvers::ContactSolver& solver,
    ArticulationStage* articulations = nullptr,
    const VelocityProblemNormals* velocityProblem = nullptr,
    const solvers::SolverOptions& sweep = {});

}  // namespace coulomb::engine
