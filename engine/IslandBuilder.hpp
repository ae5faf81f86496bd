#pragma once
// Islands: connected components of dynamic bodies linked by constraints (touching manifolds,
// joints). Static and kinematic bodies never link islands (golden rule 6): a floor under two
// separate stacks leaves two islands. Deterministic: bodies and constraints inside an island are in
// ascending order, and islands are ordered (and numbered) by their smallest body index.
#include <coulomb/solvers/UnionFind.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace coulomb::engine {

/// A constraint between two bodies (indices into the body arrays); `bodyB` may be kNoBody
/// (a constraint to the world).
struct ConstraintEdge {
  static constexpr std::int32_t kNoBody = -1;
  std::int32_t bodyA = kNoBody;
  std::int32_t bodyB = kNoBody;
};

struct Island {
  std::int32_t id = 0;                    // 0, 1, ... in order of smallest body index
  std::vector<std::int32_t> bodies;       // dynamic bodies, ascending
  std::vector<std::int32_t> constraints;  // indices into the edge list, ascending
};

class IslandBuilder {
 public:
  /// `isDynamic[i]` says whether body i carries unknowns. An edge whose two ends are both
  /// non-dynamic is dropped (nothing to solve). Dynamic bodies touched by no edge form no island
  /// (they move freely; nothing to solve for them).
  std::vector<Island> build(std::span<const std::uint8_t> isDynamic,
                            std::span<const ConstraintEdge> edges);
  /// The same into `islands`, whose vectors are reused: no allocation while the islands keep
  /// their count and sizes (a steady step).
  void build(std::span<const std::uint8_t> isDynamic, std::span<const ConstraintEdge> edges,
             std::vector<Island>& islands);

 private:
  // Bodies joined by edges; roots are each island's smallest body, whatever the edge order, which
  // keeps the island numbering deterministic. Reused between steps.
  solvers::UnionFind forest_;
  std::vector<std::int32_t> edgeRoot_, islandOfRoot_;
  std::vector<std::uint8_t> rootHasEdge_;
};

}  // namespace coulomb::engine
