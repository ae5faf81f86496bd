#pragma once
// One interface for everything that puts rows into an island's problem (docs/architecture.md,
// "The step"): contacts (engine/ContactSource), maximal-coordinate joints (engine/JointStage) and
// trees (engine/ArticulationStage). Each source tags the island edges it adds with its own item
// indices, emits the rows of the items an island holds (the row mathematics lives in joints/ and
// the contact emitter) and takes back the solved impulses of exactly the blocks it emitted. The
// step never slices a shared list by remembered offsets: every range is returned and passed on.
#include <coulomb/engine/ContactSettings.hpp>
#include <coulomb/engine/IslandBuilder.hpp>
#include <coulomb/engine/ProblemAssembler.hpp>
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/geometry/ContactManifold.hpp>
#include <coulomb/joints/RowSet.hpp>
#include <coulomb/joints/Stabilization.hpp>

#include <Eigen/Core>

#include <cstdint>
#include <span>
#include <vector>

namespace coulomb::engine {

/// What a step's constraint edges are: one list of body pairs for the island builder and, per
/// edge, the source that owns it and its item in that source (manifold index, joint slot, tree
/// constraint index).
struct StepEdges {
  std::vector<ConstraintEdge> edges;
  std::vector<std::uint8_t> owners;  // RowSource index per edge
  std::vector<std::int32_t> items;   // the owner's item per edge
  void clear() {
    edges.clear();
    owners.clear();
    items.clear();
  }
  void add(std::uint8_t owner, std::int32_t item, ConstraintEdge edge) {
    edges.push_back(edge);
    owners.push_back(owner);
    items.push_back(item);
  }
};

/// What the row sources of a step read (and, for the manifolds, write back): passed to every
/// call, so a source holds no pointer into the World.
struct RowContext {
  const geometry::BodyState& state;
  double h;
  std::vector<geometry::ContactManifold>& manifolds;  // the step's persistent manifolds
  const ContactSettings& contact;
  const joints::Stabilization& jointPolicy;  // the world's; a joint's own overrides it
};

class RowSource {
 public:
  virtual ~RowSource() = default;
  /// Appends one edge per active item of this step, tagged `owner`.
  virtual void appendEdges(std::uint8_t owner, const RowContext& context, StepEdges& edges) = 0;
  /// Appends the rows of `items` (this source's items in one island, ascending) to `rows`.
  virtual void emitRows(std::span<const std::int32_t> items, const RowContext& context,
                        joints::RowSet& rows) = 0;
  /// Keeps the solved impulses of the blocks `range` of `rows` (warm starts, reactions).
  virtual void storeImpulses(const joints::RowSet& rows, joints::BlockRange range,
                             const std::vector<RowBlockSlot>& slots, const Eigen::VectorXd& lambda,
                             const RowContext& context) = 0;
};

}  // namespace coulomb::engine
