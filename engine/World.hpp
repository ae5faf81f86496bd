#pragma once
// The World owns the body state, the colliders and the settings, and advances them in time.
// step() (WorldStep.cpp) reads as the data flow of docs/architecture.md, "The step": each stage
// reads and writes the step's StepData.
#include <coulomb/engine/ArticulationStage.hpp>
#include <coulomb/engine/BodyDesc.hpp>
#include <coulomb/engine/ContactEvents.hpp>
#include <coulomb/engine/ContactHooks.hpp>
#include <coulomb/engine/ContactSource.hpp>
#include <coulomb/engine/IslandBuilder.hpp>
#include <coulomb/engine/JointStage.hpp>
#include <coulomb/engine/ProblemAssembler.hpp>
#include <coulomb/engine/Quarantine.hpp>
#include <coulomb/engine/Sleep.hpp>
#include <coulomb/engine/SolverPromotion.hpp>
#include <coulomb/engine/StepData.hpp>
#include <coulomb/engine/StepExecutor.hpp>
#include <coulomb/engine/StepReport.hpp>
#include <coulomb/engine/WorldSettings.hpp>
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/geometry/Collider.hpp>
#include <coulomb/geometry/CollisionPipeline.hpp>
#include <coulomb/solvers/SolveWithFallback.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace coulomb::engine {

namespace io {
struct SnapshotAccess;  // io/Snapshot.cpp saves and restores the private state
}
struct ResolvedShape;  // engine/BodyBuilder.hpp

class World {
 public:
  /// Throws CoulombError if a setting is invalid.
  explicit World(WorldSettings settings = {});

  /// Validates `desc` and adds the body with its colliders. On invalid input throws CoulombError
  /// naming the value (e.g. "body 'ball': mass must be finite and > 0 (got -1)") and adds nothing.
  geometry::BodyId createBody(const BodyDesc& desc);
  /// Removes the body and its colliders; its id (and any copy of it) becomes stale.
  void removeBody(geometry::BodyId id);  // and every joint attached to it
  /// True if `id` names a live body (right slot and generation).
  [[nodiscard]] bool contains(geometry::BodyId id) const;
  /// The id of the first live body named `name`, or an invalid id.
  [[nodiscard]] geometry::BodyId findBody(const std::string& name) const;
  [[nodiscard]] std::size_t bodyCount() const;

  // Per-body access; every call throws CoulombError for a stale or invalid id.
  [[nodiscard]] const geometry::Pose& pose(geometry::BodyId id) const;  // COM frame in world
  [[nodiscard]] Eigen::Vector3d linearVelocity(geometry::BodyId id) const;
  [[nodiscard]] Eigen::Vector3d angularVelocity(geometry::BodyId id) const;
  [[nodiscard]] const geometry::SpatialInertia& massProperties(geometry::BodyId id) const;
  [[nodiscard]] const std::string& name(geometry::BodyId id) const;
  void setVelocity(geometry::BodyId id, const Eigen::Vector3d& linear,
                   const Eigen::Vector3d& angular);
  /// Accumulate a force [N] at the COM / at a world point, or a torque [N m]; cleared each step.
  void applyForce(geometry::BodyId id, const Eigen::Vector3d& force);
  void applyForceAtPoint(geometry::BodyId id, const Eigen::Vector3d& force,
                         const Eigen::Vector3d& worldPoint);
  void applyTorque(geometry::BodyId id, const Eigen::Vector3d& torque);
  /// Kinematic bodies (Jolt's MoveKinematic): sets the velocities that bring the body's
  /// reference frame (as in BodyDesc::pose) to `target` in one step of h seconds; the next
  /// step(h) ends there, to rounding, and contacts push what the body meets with those
  /// velocities (a platform carries a box by friction). Call it every step; a body given no new
  /// target keeps its velocities. Throws CoulombError for a body that is not kinematic (or is an
  /// articulation's link), a non-finite or non-unit pose, or h not finite and > 0.
  void setKinematicTarget(geometry::BodyId id, const geometry::Pose& target, double h);
  void setKinematicTarget(geometry::BodyId id, const geometry::Pose& target) {
    setKinematicTarget(id, target, settings_.timeStep);
  }
  /// Adds a collider to a live body: `shape` placed in the body's reference frame (as in
  /// BodyDesc::shapes), checked as createBody checks it. The body's mass, centre of mass and
  /// inertia stay as they are (as after createBody with an explicit mass): a shape is geometry
  /// here. CoulombError for a stale body or a bad shape; nothing is added then.
  geometry::ColliderId addCollider(geometry::BodyId body, const ShapeDesc& shape);
  /// Removes one collider (its contacts end in the next step's events); CoulombError if absent.
  /// A body may be left with no collider (it then touches nothing).
  void removeCollider(geometry::ColliderId id);
  /// The user's value of a body (BodyDesc::userData); never read by the engine.
  [[nodiscard]] std::uint64_t userData(geometry::BodyId id) const;
  void setUserData(geometry::BodyId id, std::uint64_t value);

  /// Validates `desc` (ArticulationDesc.hpp) and adds the tree with one Kinematic *proxy* body
  /// per link, named "articulation/link", that carries the link's colliders and follows its pose
  /// (docs/architecture.md, "Articulations"). Throws CoulombError naming the problem; adds nothing.
  /// A link proxy cannot be removed with removeBody; it may be an end of a joint (createJoint).
  geometry::ArticulationId createArticulation(const ArticulationDesc& desc);
  /// Removes the articulation, its link proxies and every joint attached to them; its id (and
  /// every copy) becomes stale. Throws CoulombError for a stale id.
  void removeArticulation(geometry::ArticulationId id);
  /// ArticulationDesc::userData; throws for a stale id.
  [[nodiscard]] std::uint64_t userData(geometry::ArticulationId id) const {
    return articulations_.userData(id);
  }
  /// Joint state, link poses, link proxies and the model (ArticulationStage.hpp).
  [[nodiscard]] const ArticulationStage& articulations() const { return articulations_; }
  /// Sets q (nq) and qd (nv); throws CoulombError for a stale id or a bad vector.
  void setArticulationState(geometry::ArticulationId id, const Eigen::VectorXd& q,
                            const Eigen::VectorXd& qd);
  /// Accumulates generalised joint forces tau (nv values) for the next step; cleared each step.
  void applyJointForces(geometry::ArticulationId id, const Eigen::VectorXd& tau);
  /// Changes the target of motor `motor` (ArticulationDesc::motors order); CoulombError if absent.
  void setJointMotorTarget(geometry::ArticulationId id, int motor, double target);
  /// The same for the motor of the joint named `joint` (TreeJoint::name, the URDF joint name);
  /// CoulombError listing the motorised joints if there is none.
  void setJointMotorTarget(geometry::ArticulationId id, const std::string& joint, double target);

  /// Advances by h [s] (finite, > 0; else CoulombError) or by settings().timeStep. The report
  /// is the World's own and is overwritten by the next step (copy it to keep it): one report
  /// reused, so a steady step allocates nothing.
  const StepReport& step(double h);
  const StepReport& step() { return step(settings_.timeStep); }
  /// The report of the last step (empty before the first).
  [[nodiscard]] const StepReport& lastReport() const { return report_; }

  [[nodiscard]] const geometry::BodyState& state() const { return state_; }
  [[nodiscard]] const std::vector<geometry::Collider>& colliders() const { return colliders_; }
  [[nodiscard]] const WorldSettings& settings() const { return settings_; }
  /// The threads a step runs on (WorldSettings::threads resolved: 1 without oneTBB).
  [[nodiscard]] int threads() const { return executor_.threads(); }
  /// Replaces every setting between steps, validated as a whole as the constructor does
  /// (CoulombError naming the first bad value; nothing changes then). Every field may change
  /// except `collision`, fixed when the World is built (its margins size the broad phase and
  /// the contact cache). Turning sleep off wakes the sleeping bodies; turning promotion off drops
  /// the recorded promotions. docs/embedding.md, "Settings at run time".
  void setSettings(const WorldSettings& settings);
  void setGravity(const Eigen::Vector3d& gravity);
  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] std::uint64_t stepCount() const { return stepCount_; }
  /// Mechanical energy of the dynamic bodies [J]: sum of 1/2 m v^2 + 1/2 w^T I w - m g.p in the
  /// world's gravity (datum at the origin). A conservative step keeps it; `coulomb compare`, the
  /// conformance cases and the joint tests report its change.
  [[nodiscard]] double mechanicalEnergy() const;
  /// Hash of every body's pose and velocities (bit patterns): equal across identical runs.
  [[nodiscard]] std::uint64_t stateHash() const;
  /// True once the World-level guard isolated the body (engine/Quarantine.hpp); throws for a
  /// stale id.
  [[nodiscard]] bool quarantined(geometry::BodyId id) const {
    return quarantine_.isolated(slotOf(id));
  }
  /// The id of the body in slot `index` (for iterating over state() arrays), or an invalid id.
  [[nodiscard]] geometry::BodyId idAt(std::size_t index) const;

  /// The persistent contact manifolds of the last step (points, normals, depths, impulses).
  [[nodiscard]] const std::vector<geometry::ContactManifold>& contacts() const {
    return collision_.cache().manifolds();
  }
  /// The collider with this id (colliders() is sorted by id); throws CoulombError if removed.
  [[nodiscard]] const geometry::Collider& collider(geometry::ColliderId id) const;
  /// Begin / persist / end events of the contact pairs of the last step, in collider-pair order
  /// (ContactEvents.hpp); overwritten by the next step.
  [[nodiscard]] const std::vector<ContactEvent>& contactEvents() const {
    return events_.contacts();
  }
  /// Begin / end of overlaps with sensor colliders (ShapeDesc::sensor) in the last step.
  [[nodiscard]] const std::vector<SensorEvent>& sensorEvents() const { return events_.sensors(); }
  /// Which candidate pairs are detected (ContactHooks.hpp); empty (the default) = all that pass
  /// the category/mask filters. Not part of the state: a snapshot does not carry it.
  void setContactFilter(ContactFilter filter) { contactFilter_ = std::move(filter); }
  /// Called for every contact manifold of a step before the solve (ContactHooks.hpp): change
  /// friction, restitution or surface velocity, or turn the contact off. Empty = none.
  void setPreSolveHook(PreSolveHook hook) { preSolve_ = std::move(hook); }
  /// The solver registry islands are solved with; add entries to use your own solvers by name.
  [[nodiscard]] solvers::SolverRegistry& solverRegistry() { return registry_; }
  /// Solvers for the island of this body (nullopt = WorldSettings::solve.choice). When an island
  /// holds bodies with different overrides, the one of its smallest body index wins. Throws
  /// CoulombError for an unknown solver.
  void setSolverOverride(geometry::BodyId id, std::optional<solvers::SolverChoice> choice);
  /// WorldSettings::solve.choice, validated against solverRegistry().
  void setSolver(const solvers::SolverChoice& choice);
  /// The whole solve policy (choice, options, chooser thresholds, promotion rule), validated
  /// once here; takes effect in the next step. Turning promotion off drops the promotions
  /// already recorded.
  void setSolvePolicy(const solvers::SolvePolicy& policy);

  /// Validates `desc` (joints/JointDef.hpp; frames in each body's reference frame) and adds the
  /// joint. Throws CoulombError naming the joint and the problem (stale body, non-unit axis, NaN
  /// frame, a body joined to itself, no dynamic end, bad limit/motor) and adds nothing.
  geometry::JointId createJoint(const JointDesc& desc);
  void removeJoint(geometry::JointId id);  // throws CoulombError for a stale id
  [[nodiscard]] bool contains(geometry::JointId id) const { return joints_.contains(id); }
  [[nodiscard]] std::size_t jointCount() const { return joints_.count(); }
  /// The joint as stored (frames in the bodies' COM frames); throws for a stale id.
  [[nodiscard]] const joints::JointDef& joint(geometry::JointId id) const {
    return joints_.def(id);
  }
  /// Average force and torque the joint applied to body B over the last step.
  [[nodiscard]] const JointReaction& jointReaction(geometry::JointId id) const {
    return joints_.reaction(id);
  }
  /// True once the joint's reaction exceeded its break force or torque (it no longer acts).
  [[nodiscard]] bool jointBroken(geometry::JointId id) const { return joints_.broken(id); }
  /// Called for every island of every step with its assembled problem, once the islands are
  /// solved, in island order on the thread that called step() (the island id is that of the
  /// step's IslandReport; stepCount() is the index of the step being taken). For capturing
  /// problems, e.g. `coulomb run --capture`. Empty (the default) = none. Not part of the state: a
  /// copy or snapshot does not carry it.
  using ProblemObserver =
      std::function<void(std::int32_t island, const solvers::ContactProblem& problem)>;
  void setProblemObserver(ProblemObserver observer) { problemObserver_ = std::move(observer); }

 private:
  friend struct io::SnapshotAccess;  // io/Snapshot.cpp: saves and restores the state
  /// Quarantines every dynamic body whose state is bad after `stage` (engine/Quarantine.hpp).
  void guard(const char* stage, StepReport& report);
  // The stages of step() (WorldStep.cpp), each reading and writing `step_`.
  void detectContacts(double h);
  /// The narrow phase's share of the step's threads (empty with one thread).
  [[nodiscard]] geometry::ParallelFor narrowPhaseThreads();
  void modifyContacts();  // the pre-solve hook
  geometry::ColliderId attachCollider(geometry::BodyId body, ResolvedShape shape, bool continuous);
  [[nodiscard]] const geometry::Collider* findCollider(geometry::ColliderId id) const;
  void buildIslands();
  void emitRows(IslandWork& island);
  void solveIsland(IslandWork& island);
  void applyImpulses(IslandWork& island);
  /// After the islands' solves, on the calling thread in island order: the problem observer and
  /// the warnings of islands no solver could take.
  void reportIslands();
  [[nodiscard]] const solvers::SolverChoice& choiceOf(const IslandWork& island) const;
  // The options every solve of the step shares: the sweep split and the executor's threads.
  [[nodiscard]] solvers::SolverOptions sweepOptions();
  void correctPenetrations();
  void correctPenetrations(IslandWork& island);
  void recordStartEnergies();         // E~ of every body at the step's start (energy projection)
  void projectJointIslandEnergies();  // islands of ideal joints back to their start E~
  void splitJointIslandKicks();       // islands of ideal joints: the first half kick only
  void finishJointIslandKicks();      // their second half kick, then J(x+) v = 0 (RATTLE)
  void fillIslandReport(IslandWork& island, IslandReport& report);
  /// Adds a StepReport warning when no solver of the island's plan could run (said once per
  /// choice of solvers).
  void warnIfUnsolved(const IslandWork& island, const solvers::SolverChoice& choice);
  void resetReport(double h);
  [[nodiscard]] RowContext rowContext();
  [[nodiscard]] RowSource& rowSource(RowOwner owner);
  std::size_t slotOf(geometry::BodyId id) const;  // throws for a stale id

  WorldSettings settings_;
  geometry::BodyState state_;
  std::vector<std::uint32_t> generations_;        // per slot
  std::vector<std::uint32_t> freeSlots_;          // reused lowest-first (deterministic)
  std::vector<std::string> names_;                // per slot
  std::vector<geometry::SpatialInertia> masses_;  // per slot: mass, COM in the reference frame
  std::vector<std::uint64_t> userData_;           // per slot
  std::vector<geometry::Collider> colliders_;
  std::uint32_t colliderCounter_ = 0;
  std::vector<std::optional<solvers::SolverChoice>> solverOverrides_;  // per slot
  SolverPromotion promotion_;  // per slot: a fallback to run first next step
  geometry::CollisionPipeline collision_;
  IslandBuilder islandBuilder_;
  Sleep sleep_;
  ContactSource contactRows_;
  JointStage joints_;
  ArticulationStage articulations_;
  Quarantine quarantine_;
  solvers::SolverRegistry registry_ = solvers::SolverRegistry::builtIn();
  StepData step_;                    // this step's data; kept for its capacity
  StepReport report_;                // the last step's report; kept for its capacity
  std::vector<std::string> warned_;  // keys of the StepReport::warnings already given
  StepExecutor executor_;            // settings_.threads: the islands' threads
  ProblemObserver problemObserver_;
  ContactEvents events_;
  ContactFilter contactFilter_;
  PreSolveHook preSolve_;
  double time_ = 0.0;
  std::uint64_t stepCount_ = 0;
};

}  // namespace coulomb::engine
