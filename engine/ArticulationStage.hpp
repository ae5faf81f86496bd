#pragma once
// The articulations of a World and their part of the step (docs/architecture.md, "Articulations
// in the step"). Design: every link has a *proxy* body slot in geometry::BodyState, a Kinematic
// body whose pose is the link frame (from forward kinematics) and whose velocity is the link's
// (velocity of the link origin, angular velocity; world). So:
//  - collision sees link poses by BodyId.index like any body's, with the link's colliders;
//  - contact rows (and any other RowBlock) name a link by its proxy BodyId, in the usual body
//    twist coordinates; q = J v* comes for free from the proxy velocities (set from v*);
//  - proxies carry no unknowns as bodies (kinematic: inverse mass 0); the tree's unknowns are its
//    joint velocities. ProblemAssembler asks this stage for the tree part of W: each row side on a
//    link becomes a joint-space row J_row * twistJacobian(link, proxy origin) (1 x nv) and
//    W += J_t M^-1 J_t^T by impulse-level ABA (one O(n) pass per row, no M formed);
//  - the impulses update qd by M^-1 J_t^T lambda (one O(n) pass per tree);
//  - islands: a tree is one unit: every link maps to its root link's proxy (the representative),
//    so a link touching a body joins the tree and the body in one island and one problem.
// Joint limits (lower/upper of revolute and prismatic tree joints), joint motors, joint friction,
// mimic couplings and loop closures are row blocks on the proxies as well (relative twist of parent
// and child along the joint axis; point coincidence), with island edges appended after every other
// edge of the step.
#include <coulomb/engine/ArticulationDesc.hpp>
#include <coulomb/engine/IslandBuilder.hpp>
#include <coulomb/engine/ProblemAssembler.hpp>
#include <coulomb/engine/RowSource.hpp>
#include <coulomb/engine/StepExecutor.hpp>
#include <coulomb/engine/WorldSettings.hpp>
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/geometry/Ids.hpp>
#include <coulomb/joints/RowSet.hpp>
#include <coulomb/joints/tree/Articulation.hpp>
#include <coulomb/joints/tree/ArticulationImpulse.hpp>
#include <coulomb/joints/tree/TreeDynamics.hpp>

#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace coulomb::integrators {
struct TreeStepScratch;  // ArticulationIntegrator.hpp
}

namespace coulomb::engine {

struct RowBlockSlot;

// DelassusBlock(s): ProblemAssembler.hpp.

/// Which articulation (slot) and link a proxy body stands for; articulation -1: not a link.
struct LinkRef {
  std::int32_t articulation = -1;
  std::int32_t link = -1;
  [[nodiscard]] bool valid() const { return articulation >= 0; }
};

namespace io {
struct SnapshotAccess;  // io/Snapshot.cpp saves and restores the private state
}

class ArticulationStage final : public RowSource {
 public:
  /// A validated description: the model and the proxy bodies to create (World::createBody).
  struct Prepared {
    std::unique_ptr<joints::tree::Articulation> model;
    std::vector<joints::tree::TreeLink> links;
    Eigen::VectorXd q, qd;
    std::vector<BodyDesc> proxies;  // one per link, Kinematic, at the link pose of q
    ArticulationDesc desc;          // closures, flags
  };
  /// Throws CoulombError naming the articulation, link or value; changes nothing.
  [[nodiscard]] Prepared prepare(const ArticulationDesc& desc, const WorldSettings& settings) const;
  /// Registers a prepared articulation whose proxies the World has just created.
  geometry::ArticulationId add(Prepared prepared, std::vector<geometry::BodyId> proxies,
                               geometry::BodyState& state);

  /// Forgets the articulation (its id and every copy become stale) and returns its link proxies,
  /// no longer links, for the World to remove. Throws CoulombError for a stale id.
  std::vector<geometry::BodyId> remove(geometry::ArticulationId id);
  [[nodiscard]] bool contains(geometry::ArticulationId id) const;
  /// Slots ever used (removed ones included) and the live id in a slot (invalid if removed).
  [[nodiscard]] std::size_t slots() const { return records_.size(); }
  [[nodiscard]] geometry::ArticulationId idAt(std::size_t slot) const;
  /// ArticulationDesc::userData; throws for a stale id.
  [[nodiscard]] std::uint64_t userData(geometry::ArticulationId id) const;
  [[nodiscard]] std::size_t count() const;
  [[nodiscard]] const joints::tree::Articulation& model(geometry::ArticulationId id) const;
  [[nodiscard]] const Eigen::VectorXd& q(geometry::ArticulationId id) const;
  [[nodiscard]] const Eigen::VectorXd& qd(geometry::ArticulationId id) const;
  [[nodiscard]] geometry::BodyId linkBody(geometry::ArticulationId id, int link) const;
  [[nodiscard]] const geometry::Pose& linkPose(geometry::ArticulationId id, int link) const;
  /// Sets q and qd (checked: sizes, finiteness, quaternions) and moves the proxies.
  void setState(geometry::ArticulationId id, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                geometry::BodyState& state);
  /// Accumulates generalised joint forces (nv values) for the next step; cleared every step.
  void applyJointForces(geometry::ArticulationId id, const Eigen::VectorXd& tau);
  /// Motor `motor` (ArticulationDesc::motors order) gets a new target (finite).
  void setMotorTarget(geometry::ArticulationId id, int motor, double target);
  /// The index of the motor on the joint named `joint`; CoulombError listing the motorised
  /// joints if none.
  [[nodiscard]] int motorOf(geometry::ArticulationId id, const std::string& joint) const;
  /// The motors as created (targets as last set).
  [[nodiscard]] const std::vector<JointMotorDesc>& motors(geometry::ArticulationId id) const;

  [[nodiscard]] bool isLink(std::size_t bodyIndex) const {
    return bodyIndex < linkOfBody_.size() && linkOfBody_[bodyIndex].valid();
  }
  [[nodiscard]] LinkRef linkOf(std::size_t bodyIndex) const {
    return isLink(bodyIndex) ? linkOfBody_[bodyIndex] : LinkRef{};
  }

  // ---- the step, in order --------------------------------------------------------------------
  /// v* = qd + h ABA(q, qd, tau) with the world's gravity; proxies get the links' velocities.
  /// Trees are independent here: they run on `executor`'s threads (each writes its own record
  /// and its links' proxies).
  void predictVelocities(const Eigen::Vector3d& gravity, double h, geometry::BodyState& state,
                         StepExecutor& executor);
  /// Collision filter: false for two links of one tree unless self-collision is on (then false
  /// only for a parent and its child). True for any pair not made of two links.
  [[nodiscard]] bool keepPair(std::size_t bodyA, std::size_t bodyB) const;
  /// Island mask: a tree with unknowns counts as one dynamic body, its root link's proxy.
  void markIslandBodies(std::vector<std::uint8_t>& mask) const;
  /// Every link index in `edges` becomes its tree's representative (the root link's proxy).
  void mapEdges(std::vector<ConstraintEdge>& edges) const;
  // ---- row source (RowSource.hpp); items index this step's tree constraints ------------------
  /// One edge per active joint limit, motor, joint friction, coupling and loop closure, on the
  /// tree's representative (the root link's proxy).
  void appendEdges(std::uint8_t owner, const RowContext& context, StepEdges& edges) override;
  /// The limit, motor, friction, coupling and closure blocks of `items` (warm-started).
  void emitRows(std::span<const std::int32_t> items, const RowContext& context,
                joints::RowSet& rows) override;
  /// Keeps the impulses of the blocks `range` as warm starts.
  void storeImpulses(const joints::RowSet& rows, joints::BlockRange range,
                     const std::vector<RowBlockSlot>& slots, const Eigen::VectorXd& lambda,
                     const RowContext& context) override;
  /// The trees `rows` touch, in joint space (their Jacobians and impulse-level ABA at q now).
  void mapRows(const joints::RowSet& rows, const geometry::BodyState& state, TreeRowMap& map) const;
  /// For ProblemAssembler: maps `rows` (mapRows) and adds J_t M^-1 J_t^T of every tree touched
  /// to `blocks`; returns the number of joint velocities involved (degrees of freedom).
  int addDelassusBlocks(const joints::RowSet& rows, const geometry::BodyState& state,
                        TreeRowMap& map, DelassusBlocks& blocks) const;
  /// qd += M^-1 J_t^T lambda for every tree of `map` (the rows' map, built at their assembly);
  /// refreshes the proxy velocities.
  void applyImpulses(TreeRowMap& map, const std::vector<RowBlockSlot>& slots,
                     const Eigen::VectorXd& lambda, geometry::BodyState& state);
  /// q <- q (+) h qd on the joint manifolds; proxies follow forward kinematics. With
  /// TreeIntegrator::RungeKutta a tree that no row touched this step (applyImpulses never saw it)
  /// is instead integrated by Runge-Kutta from its state at predictVelocities.
  void integratePositions(double h, TreeIntegrator integrator, geometry::BodyState& state,
                          StepExecutor& executor);
  /// Split impulse: q <- q (+) h M^-1 J_t^T p (pseudo-velocities, then discarded), `map` that
  /// of the pseudo problem's rows.
  void applyPseudoImpulses(TreeRowMap& map, const std::vector<RowBlockSlot>& slots,
                           const Eigen::VectorXd& lambda, double h, geometry::BodyState& state);
  void clearForces();

 private:
  friend struct io::SnapshotAccess;
  struct Record {
    std::string name;
    std::vector<joints::tree::TreeLink> links;
    std::unique_ptr<joints::tree::Articulation> model;
    Eigen::VectorXd q, qd, tau;
    std::vector<geometry::BodyId> linkBodies;
    std::vector<geometry::Pose> linkPoses;
    std::vector<LoopClosureDesc> closures;
    std::vector<Eigen::Vector3d> closureWarm;
    std::vector<double> lowerWarm, upperWarm;  // per link
    std::vector<JointMotorDesc> motors;
    std::vector<double> motorWarm;
    std::vector<JointCouplingDesc> couplings;
    std::vector<double> couplingWarm;
    std::vector<double> friction, frictionWarm;  // per link; friction 0 = no row
    Eigen::VectorXd constantTau;                 // ArticulationDesc::jointTorques, every step
    double errorReduction = 0.2;
    bool selfCollision = false;
    bool alive = true;  // false once removed: its slot is kept (ids stay unique), never stepped
    std::uint64_t userData = 0;
    std::uint32_t generation = 0;
    // The step's scratch, kept for its storage: ABA's per-link values, tau + constantTau, qdd,
    // the proxies' kinematics and link velocities.
    joints::tree::AbaWorkspace aba;
    Eigen::VectorXd totalTau, qdd;
    // The step's start (before v*), whether rows touched the tree in its solve, and the
    // Runge-Kutta storage (made on first use; its type stays in ArticulationIntegrator.hpp).
    Eigen::VectorXd qdStart;
    bool constrained = false;
    std::shared_ptr<integrators::TreeStepScratch> integration;
    joints::tree::TreeKinematics proxyKinematics;
    std::vector<geometry::Vector6d> proxyVelocities;
  };
  enum class ConstraintKind : std::uint8_t { Lower, Upper, Closure, Motor, Coupling, Friction };
  struct TreeConstraint {
    std::int32_t articulation = 0;
    ConstraintKind kind = ConstraintKind::Lower;
    std::int32_t index = 0;  // link (limits, friction), closure, motor or coupling
  };
  Record& record(geometry::ArticulationId id);
  [[nodiscard]] const Record& record(geometry::ArticulationId id) const;
  void updateProxies(Record& r, geometry::BodyState& state) const;
  /// The joint-space row of a coupling block (sourceKey tagged kCouplingTag), else nullopt.
  [[nodiscard]] std::optional<Eigen::RowVectorXd> couplingRow(const joints::RowBlock& block) const;
  [[nodiscard]] joints::RowBlock rowBlockOf(const TreeConstraint& c,
                                            const geometry::BodyState& state, double h) const;
  std::vector<Record> records_;
  std::vector<LinkRef> linkOfBody_;          // per body slot
  std::vector<TreeConstraint> constraints_;  // this step's, indexed by the edges' items
};

}  // namespace coulomb::engine
