#pragma once
// The World-level guard of issue 13 item 2: a dynamic body whose state becomes non-finite or
// leaves the sanity limits below is *quarantined* so that it cannot poison the rest of the world:
//  - its pose goes back to the pose it had at the start of the step (its last good state), its
//    velocities to zero, and it becomes Static (infinite mass: integrators and solvers skip it);
//  - it leaves collision (no pair with a quarantined body is tested) and every maximal-coordinate
//    joint attached to it breaks, so nothing keeps pushing on or pulling at a frozen body;
//  - the step's StepReport lists it (StepReport::quarantined, with the reason), once; the body
//    stays in the World (its id stays valid, World::quarantined(id) is true) until removed.
// An articulation whose q or qd becomes non-finite (or too fast) gets back the q of the start of
// the step with qd = 0 and is listed too; it keeps being simulated.
// The check runs twice per step: after the velocity prediction (catches forces that overflowed
// before they reach any contact: neighbours are never solved together with an infinite velocity)
// and at the end of the step (catches anything the solve or the integration produced).
// Kinematic bodies move as told and are not checked; static bodies do not move.
#include <coulomb/engine/ArticulationStage.hpp>
#include <coulomb/engine/QuarantineSettings.hpp>
#include <coulomb/engine/StepReport.hpp>
#include <coulomb/geometry/BodyState.hpp>

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace coulomb::engine {

namespace io {
struct SnapshotAccess;  // io/Snapshot.cpp saves and restores the flags
}

class Quarantine {
 public:
  /// Start of a step: remembers the poses and the trees' q (the last good state).
  void begin(const geometry::BodyState& state, const ArticulationStage& trees);
  /// The reason body `i` (dynamic, not yet quarantined) must be quarantined, or nullopt.
  [[nodiscard]] std::optional<std::string> check(std::size_t i, const geometry::BodyState& state,
                                                 const QuarantineSettings& limits) const;
  /// Isolates body `i`: back to its start pose, at rest, Static, flagged.
  void isolate(std::size_t i, geometry::BodyState& state);
  /// Resets every tree whose q or qd is bad to its start q with qd = 0; returns the events.
  std::vector<QuarantineEvent> guardTrees(ArticulationStage& trees, geometry::BodyState& state,
                                          const QuarantineSettings& limits) const;
  [[nodiscard]] bool isolated(std::size_t i) const { return i < flags_.size() && flags_[i] != 0; }
  /// A slot is reused by a new body: it starts healthy.
  void reset(std::size_t i) {
    if (i < flags_.size()) flags_[i] = 0;
  }

 private:
  friend struct io::SnapshotAccess;
  std::vector<std::uint8_t> flags_;         // per body slot: 1 = quarantined
  std::vector<geometry::Pose> startPoses_;  // per body slot, at the start of the step
  std::vector<Eigen::VectorXd> startQ_;     // per articulation, at the start of the step
};

}  // namespace coulomb::engine
