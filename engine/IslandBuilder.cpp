#include <coulomb/engine/IslandBuilder.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace coulomb::engine {

std::vector<Island> IslandBuilder::build(std::span<const std::uint8_t> isDynamic,
                                         std::span<const ConstraintEdge> edges) {
  std::vector<Island> islands;
  build(isDynamic, edges, islands);
  return islands;
}

void IslandBuilder::build(std::span<const std::uint8_t> isDynamic,
                          std::span<const ConstraintEdge> edges, std::vector<Island>& islands) {
  const auto bodyCount = static_cast<std::int32_t>(isDynamic.size());
  forest_.reset(bodyCount);

  auto dynamicBody = [&](std::int32_t body) {
    if (body == ConstraintEdge::kNoBody) return false;
    if (body < 0 || body >= bodyCount)
      throw std::out_of_range("IslandBuilder: constraint names body " + std::to_string(body) +
                              " of " + std::to_string(bodyCount));
    return isDynamic[body] != 0;
  };

  std::vector<std::int32_t>& edgeRoot = edgeRoot_;
  edgeRoot.assign(edges.size(), ConstraintEdge::kNoBody);
  for (const ConstraintEdge& e : edges) {
    const bool a = dynamicBody(e.bodyA), b = dynamicBody(e.bodyB);
    if (a && b) forest_.unite(e.bodyA, e.bodyB);
  }

  std::vector<std::int32_t>& islandOfRoot = islandOfRoot_;
  islandOfRoot.assign(isDynamic.size(), -1);
  std::size_t islandCount = 0;
  auto islandOf = [&](std::int32_t body) -> Island& {
    const std::int32_t root = forest_.find(body);
    if (islandOfRoot[root] < 0) {
      islandOfRoot[root] = static_cast<std::int32_t>(islandCount);
      if (islandCount == islands.size()) islands.emplace_back();
      Island& fresh = islands[islandCount++];
      fresh.bodies.clear();
      fresh.constraints.clear();
    }
    return islands[islandOfRoot[root]];
  };
  // Visit edges first only to decide which roots have constraints; create islands in root order.
  std::vector<std::uint8_t>& rootHasEdge = rootHasEdge_;
  rootHasEdge.assign(isDynamic.size(), 0);
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const ConstraintEdge& e = edges[k];
    const std::int32_t dyn = dynamicBody(e.bodyA) ? e.bodyA : (dynamicBody(e.bodyB) ? e.bodyB : -1);
    if (dyn < 0) continue;
    edgeRoot[k] = forest_.find(dyn);
    rootHasEdge[edgeRoot[k]] = 1;
  }
  for (std::int32_t i = 0; i < bodyCount; ++i)
    if (isDynamic[i] && rootHasEdge[forest_.find(i)]) islandOf(i).bodies.push_back(i);
  islands.resize(islandCount);
  for (std::size_t k = 0; k < edges.size(); ++k)
    if (edgeRoot[k] >= 0)
      islands[islandOfRoot[edgeRoot[k]]].constraints.push_back(static_cast<std::int32_t>(k));
  for (std::size_t i = 0; i < islands.size(); ++i) islands[i].id = static_cast<std::int32_t>(i);
}

}  // namespace coulomb::engine
