#pragma once
// Whether an island's equality rows close a kinematic loop, the only way they can be redundant
// (docs/solver-derivations.md (10.3)): a tree of joints has independent rows. Each block of
// equality rows is an edge between its two bodies, with every body that carries no unknowns
// this step taken as one node (the ground) and every link of a tree as its tree; an edge that
// joins two nodes already joined (or a node to itself: a tree's loop closure) closes a loop.
#include <coulomb/engine/IslandBuilder.hpp>
#include <coulomb/joints/RowSet.hpp>

#include <coulomb/solvers/UnionFind.hpp>

#include <cstdint>
#include <vector>

namespace coulomb::engine {

class ArticulationStage;

struct JointLoopScratch {  // kept with the island for its storage
  std::vector<ConstraintEdge> edges;
  std::vector<std::int32_t> nodes;
  solvers::UnionFind forest;
};

/// `dynamicMask`: per body slot, 1 when it carries unknowns this step (StepData::dynamicMask).
[[nodiscard]] bool equalityRowsCloseALoop(const joints::RowSet& rows,
                                          const std::vector<std::uint8_t>& dynamicMask,
                                          const ArticulationStage& trees,
                                          JointLoopScratch& scratch);

}  // namespace coulomb::engine
