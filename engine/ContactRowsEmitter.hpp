#pragma once
// Manifold points of one island -> contact row blocks (joints::makeContactRows), with the
// velocity biases of the step: Newton restitution above a velocity threshold and speculative
// gaps. Penetration is NOT corrected here (that would add energy): see PenetrationCorrection.
#include <coulomb/engine/ContactSettings.hpp>
#include <coulomb/engine/IslandBuilder.hpp>
#include <coulomb/engine/ProblemAssembler.hpp>
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/geometry/ContactManifold.hpp>
#include <coulomb/joints/RowSet.hpp>

#include <vector>

namespace coulomb::engine {

/// Where a row block came from: manifold index and point index inside it.
struct ContactRowSource {
  int manifold = 0;
  int point = 0;
  double depth = 0.0;     // [m] penetration at the start of the step (> 0 overlapping)
  double approach = 0.0;  // [m/s] u_N = n . (v_B - v_A) at the point with v*, before the solve
};

/// Emits one block per point of every manifold in `island.constraints` (indices into
/// `manifolds`, which are the island builder's edges one to one), warm-started from the
/// manifold's stored impulses. `sources` gets one entry per block.
joints::RowSet emitContactRows(const Island& island,
                               const std::vector<geometry::ContactManifold>& manifolds,
                               const geometry::BodyState& state, const ContactSettings& settings,
                               double h, std::vector<ContactRowSource>& sources);

/// Stores the solved impulses back into the manifolds' points for the next step's warm start.
void storeContactImpulses(const joints::RowSet& rows, const std::vector<RowBlockSlot>& slots,
                          const Eigen::VectorXd& lambda,
                          const std::vector<ContactRowSource>& sources,
                          std::vector<geometry::ContactManifold>& manifolds);

}  // namespace coulomb::engine
