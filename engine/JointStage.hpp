#pragma once
// The joints of a World and their part of the step: island edges, row emission (before the
// contacts of each island), warm starts, the predicted-state correction, reaction forces,
// breakage and the drift report. The World calls one method per stage (World.cpp stays the data
// flow); the joint mathematics lives in joints/ and integrators/PredictedStateCorrection.
#include <coulomb/engine/IslandBuilder.hpp>
#include <coulomb/engine/ProblemAssembler.hpp>
#include <coulomb/engine/StepReport.hpp>
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/geometry/Ids.hpp>
#include <coulomb/joints/JointDef.hpp>
#include <coulomb/joints/RowSet.hpp>

#include <vector>

namespace coulomb::engine {

/// The wrench a joint applied to body B over the last step (average over the step).
struct JointReaction {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // [N] on B, world axes
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // [N m] on B about the anchor, world axes
};

/// What World::createJoint takes: frames in each body's *reference* frame (as BodyDesc shapes;
/// the world frame for an invalid body id). The World stores them in the COM frames.
using JointDesc = joints::JointDef;

namespace io {
struct SnapshotAccess;  // engine/io/Snapshot.cpp saves and restores the private state
}

class JointStage {
 public:
  /// Adds a joint whose frames are already in the bodies' COM frames and which is valid.
  geometry::JointId create(joints::JointDef def);
  void remove(geometry::JointId id);  // throws CoulombError for a stale id
  [[nodiscard]] bool contains(geometry::JointId id) const;
  [[nodiscard]] const joints::JointDef& def(geometry::JointId id) const;
  [[nodiscard]] const JointReaction& reaction(geometry::JointId id) const;
  [[nodiscard]] bool broken(geometry::JointId id) const;
  /// Marks the joint broken (it stops acting), e.g. when one of its bodies is quarantined.
  void breakJoint(geometry::JointId id);
  [[nodiscard]] std::size_t count() const;
  /// Live joints with `body` at either end (for removing a body).
  [[nodiscard]] std::vector<geometry::JointId> jointsOf(geometry::BodyId body) const;

  /// Appends one edge per active (live, unbroken) joint after the edges already in `edges`.
  void appendEdges(std::vector<ConstraintEdge>& edges);
  /// The island without its joint edges (the contact manifolds, which come first).
  [[nodiscard]] Island contactPart(const Island& island) const;
  /// The rows of the island's joints (its constraints at or after the first joint edge), each
  /// joint's equality block first, warm-started; the World appends the contacts after them.
  joints::RowSet emitRows(const Island& island, const geometry::BodyState& state,
                          const joints::Stabilization& worldPolicy, double h);
  /// The island's solved impulses (the joint blocks are the first blocks of `rows`): kept as next
  /// step's warm start and accumulated into the reaction.
  void storeImpulses(const joints::RowSet& rows, std::size_t jointBlocks,
                     const std::vector<RowBlockSlot>& slots, const Eigen::VectorXd& lambda);
  /// Before the velocity solve: every dynamic body whose joint forces (the last step's reactions)
  /// would make the explicit step unstable gets the inverse of joints::stabilizingInertia as its
  /// world inverse inertia, with which the velocity problem is assembled and its impulses applied;
  /// restoreInertias() puts the true ones back before the predicted-state correction (which
  /// measured better with the true inertia: SHAKE then stalls on fewer steps).
  void stiffenLoadedBodies(geometry::BodyState& state, double h);
  void restoreInertias(geometry::BodyState& state);
  /// Predicted-state correction of every active joint whose policy is PredictedState.
  void correctDrift(geometry::BodyState& state, const joints::Stabilization& worldPolicy, double h,
                    JointStepReport& report);
  /// After the position update: reactions [N], breakage, and the drift left by the step.
  void finishStep(const geometry::BodyState& state, double h, JointStepReport& report);

 private:
  friend struct io::SnapshotAccess;
  struct Record {
    joints::JointDef def;
    std::uint32_t generation = 0;
    bool alive = false;
    bool broken = false;
    std::vector<joints::RowVector> warmStarts;  // per emitted block of the last step
    Eigen::Matrix<double, 6, 1> impulseOnB = Eigen::Matrix<double, 6, 1>::Zero();  // J_B^T lambda
    Eigen::Vector3d armB = Eigen::Vector3d::Zero();  // anchor B - COM B at the step's start
    JointReaction reaction;
  };
  std::size_t slotOf(geometry::JointId id) const;
  [[nodiscard]] const joints::Stabilization& policyOf(const Record& r,
                                                      const joints::Stabilization& world) const;

  std::vector<Record> records_;
  std::vector<std::uint32_t> freeSlots_;
  std::vector<std::uint32_t> edgeJoints_;  // joint slot of each appended edge
  std::size_t firstEdge_ = 0;              // index of the first joint edge of this step
  std::vector<std::uint32_t> stiffened_;   // bodies given a stabilizing inertia this step
};

}  // namespace coulomb::engine
