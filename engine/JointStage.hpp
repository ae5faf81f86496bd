#pragma once
// The joints of a World and their part of the step: a row source (island edges, rows, warm
// starts), the stabilizing inertias of loaded bodies, the predicted-state correction, reaction
// forces, breakage and the drift report. The World calls one method per stage (WorldStep.cpp is
// the data flow); the joint mathematics lives in joints/ and integrators/PredictedStateCorrection.
#include <coulomb/engine/IslandBuilder.hpp>
#include <coulomb/engine/ProblemAssembler.hpp>
#include <coulomb/engine/RowSource.hpp>
#include <coulomb/engine/StepReport.hpp>
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/geometry/Ids.hpp>
#include <coulomb/integrators/PredictedStateCorrection.hpp>
#include <coulomb/joints/JointDef.hpp>
#include <coulomb/joints/RowSet.hpp>

#include <span>
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
struct SnapshotAccess;  // io/Snapshot.cpp saves and restores the private state
}

class JointStage final : public RowSource {
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

  // ---- row source (RowSource.hpp); items are joint slots ---------------------------------------
  /// One edge per active (live, unbroken) joint; clears the impulses accumulated for reactions.
  void appendEdges(std::uint8_t owner, const RowContext& context, StepEdges& edges) override;
  /// Each joint's equality block first, then its limit/motor rows, warm-started.
  void emitRows(std::span<const std::int32_t> items, const RowContext& context,
                joints::RowSet& rows) override;
  /// Kept as next step's warm start and accumulated into the reaction.
  void storeImpulses(const joints::RowSet& rows, joints::BlockRange range,
                     const std::vector<RowBlockSlot>& slots, const Eigen::VectorXd& lambda,
                     const RowContext& context) override;

  /// The world inverse inertias the velocity problem is assembled and applied with when some
  /// dynamic body's joint forces (the last step's reactions) would make the explicit step
  /// unstable: `state`'s, with those bodies' replaced by the inverse of
  /// joints::stabilizingInertia (docs/tuning.md, "Heavy loads"). False (and `out` untouched)
  /// when no body needs it. The body state is not changed: the predicted-state correction and
  /// the position update keep the true inertia (SHAKE measured better with it).
  bool stabilizedInverseInertias(const geometry::BodyState& state, double h,
                                 std::vector<Eigen::Matrix3d>& out) const;
  /// Predicted-state correction of the `active` joints whose policy is PredictedState.
  void correctDrift(geometry::BodyState& state, std::span<const std::int32_t> active,
                    const joints::Stabilization& worldPolicy, double h, JointStepReport& report);
  /// The second half of the symmetric step of islands of ideal joints: the velocities of the
  /// bodies of the joints `items` projected onto J(x) v = 0 at their poses after the position
  /// update (integrators::projectJointVelocities); the impulses count in the reactions.
  void projectVelocities(geometry::BodyState& state, std::span<const std::int32_t> items);
  /// What the island whose joint slots are `items` keeps through the energy projection
  /// (integrators/EnergyProjection.hpp): its joints' common PredictedStateSettings::energy when
  /// they are all ideal joints under the predicted-state policy (no limit, motor or friction)
  /// between dynamic bodies or to the world or static bodies (no kinematic driver), else None.
  /// `anchored`: some joint holds the island to the world; `tolerance`: the largest correction
  /// tolerance of its joints [m].
  [[nodiscard]] joints::EnergyTarget energyTarget(std::span<const std::int32_t> items,
                                                  const joints::Stabilization& worldPolicy,
                                                  const geometry::BodyState& state, bool& anchored,
                                                  double& tolerance) const;
  /// Whether some live joint asks for an energy projection (its policy's
  /// PredictedStateSettings::energy is not None).
  [[nodiscard]] bool projectsEnergy(const joints::Stabilization& worldPolicy) const;
  /// The linear velocities u that the bodies' angular velocities give through the joints of
  /// `items` at the poses `poses` (`state` for the bodies' motion types): from a body held to the
  /// world or a static body at anchor p, u = omega x (x - p); across a joint from a body with u
  /// known, u_B = u_A + omega_A x (p - x_A)
  /// + omega_B x (x_B - p); a free island starts from its lowest body's own linear velocity. This
  /// is the tangent velocity of the step boundary at the generalized rates of the step, where the
  /// chord velocity of the SHAKE step dips by h/2 omega x (omega x r) (the O(h^2) term of the
  /// modified energy, integrators/EnergyProjection.hpp). Written into `out` per body slot for the
  /// bodies the joints reach; false (out unspecified) when a prismatic joint is among them (its
  /// slide is a rate of its own).
  bool boundaryVelocities(std::span<const std::int32_t> items, const geometry::BodyState& state,
                          std::span<const geometry::Pose> poses,
                          std::span<const Eigen::Vector3d> linear,
                          std::span<const Eigen::Vector3d> angular,
                          std::vector<Eigen::Vector3d>& out) const;
  /// After the position update: reactions [N], breakage, and the drift left by the step.
  void finishStep(const geometry::BodyState& state, std::span<const std::int32_t> active, double h,
                  JointStepReport& report);

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
  struct StiffnessTerm {  // one joint's geometric stiffness on one body
    std::uint32_t body = 0, order = 0;
    Eigen::Matrix3d stiffness;
  };
  mutable std::vector<StiffnessTerm> stiffnessTerms_;  // stabilizedInverseInertias, kept
  mutable std::vector<std::uint8_t> reached_;          // boundaryVelocities, per body slot
  // The predicted-state correction's joints, workspace and result, kept between steps.
  std::vector<const joints::JointDef*> correctionDefs_;
  std::vector<std::uint32_t> correctionSlots_;
  integrators::PredictedStateWorkspace correction_;
  integrators::PredictedStateResult correctionResult_;
  // The symmetric step's velocity projection, kept like the correction's.
  std::vector<const joints::JointDef*> projectionDefs_;
  integrators::PredictedStateWorkspace projection_;
  integrators::PredictedStateResult projectionResult_;
};

}  // namespace coulomb::engine
