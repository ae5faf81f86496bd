#pragma once
// Contacts as a row source (RowSource.hpp): one edge per manifold, one block per manifold point
// (joints::makeContactRows) with the velocity biases of the step: Newton restitution above a
// velocity threshold and speculative gaps. Penetration is NOT corrected here (that would add
// energy): see PenetrationCorrection. A block's sourceKey names its manifold and point
// (contactKey), so the impulses go back to the right point without a side list.
#include <coulomb/engine/RowSource.hpp>

#include <cstdint>

namespace coulomb::engine {

/// sourceKey of a contact block: manifold index and point index inside it.
inline std::uint64_t contactKey(std::int32_t manifold, int point) {
  return (static_cast<std::uint64_t>(manifold) << 8) | static_cast<std::uint64_t>(point);
}
inline std::int32_t contactManifold(std::uint64_t key) {
  return static_cast<std::int32_t>(key >> 8);
}
inline int contactPoint(std::uint64_t key) {
  return static_cast<int>(key & 0xff);
}

class ContactSource final : public RowSource {
 public:
  void appendEdges(std::uint8_t owner, const RowContext& context, StepEdges& edges) override;
  /// One block per point of the manifolds `items`, warm-started from the points' stored
  /// impulses; each point keeps the approach velocity u_N (v*) it had before the solve.
  void emitRows(std::span<const std::int32_t> items, const RowContext& context,
                joints::RowSet& rows) override;
  /// The impulses back into the manifolds' points (the next step's warm start).
  void storeImpulses(const joints::RowSet& rows, joints::BlockRange range,
                     const std::vector<RowBlockSlot>& slots, const Eigen::VectorXd& lambda,
                     const RowContext& context) override;
};

}  // namespace coulomb::engine
