#include <coulomb/engine/JointLoops.hpp>

#include <coulomb/engine/ArticulationStage.hpp>

#include <algorithm>

namespace coulomb::engine {

bool equalityRowsCloseALoop(const joints::RowSet& rows,
                            const std::vector<std::uint8_t>& dynamicMask,
                            const ArticulationStage& trees, JointLoopScratch& scratch) {
  std::vector<ConstraintEdge>& edges = scratch.edges;
  edges.clear();
  auto raw = [](const geometry::BodyId& body) {
    return body.valid() ? static_cast<std::int32_t>(body.index) : ConstraintEdge::kNoBody;
  };
  for (const joints::RowBlock& block : rows.blocks)
    if (block.kind == joints::RowKind::Equality)
      edges.push_back({raw(block.bodyA), raw(block.bodyB)});
  if (edges.empty()) return false;
  // Links become their tree's representative (the root link's proxy, which the mask marks when
  // the tree carries unknowns); then every body without unknowns becomes the ground.
  trees.mapEdges(edges);
  auto ground = [&](std::int32_t& body) {
    if (body < 0 || static_cast<std::size_t>(body) >= dynamicMask.size() || dynamicMask[body] == 0)
      body = ConstraintEdge::kNoBody;
  };
  for (ConstraintEdge& e : edges) {
    ground(e.bodyA);
    ground(e.bodyB);
  }
  // Union-find over the edges' nodes, numbered compactly (the ground is kNoBody, numbered too).
  std::vector<std::int32_t>& nodes = scratch.nodes;
  nodes.clear();
  for (const ConstraintEdge& e : edges) {
    nodes.push_back(e.bodyA);
    nodes.push_back(e.bodyB);
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  solvers::UnionFind& forest = scratch.forest;
  forest.reset(static_cast<int>(nodes.size()));
  auto index = [&](std::int32_t body) {
    return static_cast<int>(std::lower_bound(nodes.begin(), nodes.end(), body) - nodes.begin());
  };
  for (const ConstraintEdge& e : edges)
    if (!forest.unite(index(e.bodyA), index(e.bodyB))) return true;
  return false;
}

}  // namespace coulomb::engine
