#pragma once
// v+ = v* + M^-1 J^T lambda for every row block of an island (Moreau-Jean velocity update).
#include <coulomb/engine/ProblemAssembler.hpp>

namespace coulomb::engine {

/// Applies the impulses `lambda` (indexed as the assembled problem's unknowns) to the velocities
/// of the dynamic bodies of `rows`. Static and kinematic bodies are never changed.
/// `inverseInertias`: those the problem was assembled with (nullptr: the bodies' own).
void applyImpulses(const joints::RowSet& rows, const std::vector<RowBlockSlot>& slots,
                   const Eigen::VectorXd& lambda, geometry::BodyState& state,
                   const InverseInertias* inverseInertias = nullptr);

/// The same update on separate velocity arrays (pseudo-velocities of split-impulse correction).
void applyImpulsesTo(const joints::RowSet& rows, const std::vector<RowBlockSlot>& slots,
                     const Eigen::VectorXd& lambda, const geometry::BodyState& state,
                     std::vector<Eigen::Vector3d>& linear, std::vector<Eigen::Vector3d>& angular);

}  // namespace coulomb::engine
