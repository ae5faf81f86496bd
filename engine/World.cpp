#include <coulomb/engine/AllocatorTuning.hpp>
#include <coulomb/engine/BodyBuilder.hpp>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/ImpactPropagation.hpp>
#include <coulomb/engine/ImpulseApplier.hpp>
#include <coulomb/engine/PenetrationCorrection.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/integrators/FreeMotion.hpp>
#include <coulomb/integrators/PositionUpdate.hpp>
#include <coulomb/solvers/SolveWithFallback.hpp>
#include <coulomb/solvers/SolverChooser.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace coulomb::engine {

using geometry::BodyId;

namespace {
// True for what SolverChooser accepts: "auto", a registry name, "name!" (that solver alone) or a
// chain "a,b,c" of registry names.
bool isKnownSolverRequest(const solvers::SolverRegistry& registry, const std::string& request) {
  if (request == "auto") return true;
  std::string name;
  for (std::size_t i = 0; i <= request.size(); ++i) {
    if (i < request.size() && request[i] != ',') {
      name += request[i];
      continue;
    }
    if (!name.empty() && name.back() == '!') name.pop_back();
    if (!registry.find(name)) return false;
    name.clear();
  }
  return true;
}
}  // namespace

World::World(WorldSettings settings)
    : settings_(std::move(settings)), collision_(settings_.collision) {
  tuneAllocatorForStepping();  // keep the pages a step frees mapped (AllocatorTuning.hpp)
  if (auto problem = settings_.validate()) throw CoulombError("world settings: " + *problem);
  if (!isKnownSolverRequest(registry_, settings_.solver))
    throw CoulombError("world settings: unknown solver '" + settings_.solver +
                       "' (see `coulomb solvers`)");
}

void World::setSolver(const std::string& solver) {
  if (!isKnownSolverRequest(registry_, solver))
    throw CoulombError("setSolver: unknown solver '" + solver + "' (see `coulomb solvers`)");
  settings_.solver = solver;
}

void World::setPromoteFallbacks(bool on) {
  settings_.promoteFallbacks = on;
  if (!on)
    for (std::size_t i = 0; i < state_.size(); ++i) promotion_.reset(i);
}

void World::setSolverOverride(BodyId id, const std::string& solver) {
  const std::size_t i = slotOf(id);
  if (!solver.empty() && !isKnownSolverRequest(registry_, solver))
    throw CoulombError("setSolverOverride: unknown solver '" + solver + "' for body '" + names_[i] +
                       "' (see `coulomb solvers`)");
  solverOverrides_[i] = solver;
}

BodyId World::createBody(const BodyDesc& desc) {
  ResolvedBody body = resolveBody(desc, settings_);  // throws before anything is changed
  if (!desc.solver.empty() && !isKnownSolverRequest(registry_, desc.solver))
    throw CoulombError("body '" + desc.name + "': unknown solver '" + desc.solver +
                       "' (see `coulomb solvers`)");
  std::size_t slot = state_.size();
  if (!freeSlots_.empty()) {
    const auto lowest = std::min_element(freeSlots_.begin(), freeSlots_.end());
    slot = *lowest;
    freeSlots_.erase(lowest);
  } else {
    generations_.push_back(0);
    names_.emplace_back();
    masses_.emplace_back();
    solverOverrides_.emplace_back();
    promotion_.resize(solverOverrides_.size());
  }
  state_.assign(slot, desc.motionType, body.comPose, desc.linearVelocity, desc.angularVelocity,
                body.massProperties.mass, body.massProperties.inertiaAboutCom);
  names_[slot] = desc.name;
  quarantine_.reset(slot);
  solverOverrides_[slot] = desc.solver;
  promotion_.reset(slot);
  masses_[slot] = body.massProperties;
  const BodyId id{static_cast<std::uint32_t>(slot), generations_[slot]};
  for (ResolvedShape& s : body.shapes) {
    geometry::Collider collider;
    collider.id = geometry::ColliderId{colliderCounter_++, 0};
    collider.body = id;
    collider.localPose = s.localPose;
    collider.shape = std::move(s.shape);
    collider.material = s.material;
    collider.filter = s.filter;
    colliders_.push_back(std::move(collider));
  }
  return id;
}

void World::removeBody(BodyId id) {
  const std::size_t slot = slotOf(id);
  if (articulations_.isLink(slot))
    throw CoulombError("removeBody: body '" + names_[slot] + "' is a link of an articulation");
  for (const geometry::JointId joint : joints_.jointsOf(id)) joints_.remove(joint);
  std::erase_if(colliders_, [&](const geometry::Collider& c) { return c.body == id; });
  state_.clear(slot);
  names_[slot].clear();
  masses_[slot] = {};
  ++generations_[slot];
  freeSlots_.push_back(static_cast<std::uint32_t>(slot));
}

geometry::JointId World::createJoint(const JointDesc& desc) {
  const std::string who = "joint '" + desc.name + "': ";
  joints::JointDef def = desc;
  bool anyDynamic = false;
  for (auto [id, frame] : {std::pair{def.bodyA, &def.frameA}, std::pair{def.bodyB, &def.frameB}}) {
    if (!id.valid()) continue;
    if (!contains(id)) throw CoulombError(who + "a body id is stale or invalid");
    frame->anchor -= masses_[id.index].centerOfMass;  // reference frame -> COM frame (same axes)
    anyDynamic = anyDynamic || state_.isDynamic(id.index) || articulations_.isLink(id.index);
  }
  if (auto bad = joints::validateJointDef(def)) throw CoulombError(*bad);
  if (!anyDynamic) throw CoulombError(who + "neither end is a dynamic body");
  return joints_.create(std::move(def));
}

void World::removeJoint(geometry::JointId id) {
  joints_.remove(id);
}

geometry::ArticulationId World::createArticulation(const ArticulationDesc& desc) {
  ArticulationStage::Prepared prepared = articulations_.prepare(desc, settings_);  // may throw
  std::vector<BodyId> proxies;
  for (const BodyDesc& proxy : prepared.proxies) proxies.push_back(createBody(proxy));
  return articulations_.add(std::move(prepared), std::move(proxies), state_);
}

void World::setArticulationState(geometry::ArticulationId id, const Eigen::VectorXd& q,
                                 const Eigen::VectorXd& qd) {
  articulations_.setState(id, q, qd, state_);
}

void World::applyJointForces(geometry::ArticulationId id, const Eigen::VectorXd& tau) {
  articulations_.applyJointForces(id, tau);
}

void World::setJointMotorTarget(geometry::ArticulationId id, int motor, double target) {
  articulations_.setMotorTarget(id, motor, target);
}

bool World::contains(BodyId id) const {
  return id.valid() && id.index < state_.size() && state_.alive[id.index] != 0 &&
         generations_[id.index] == id.generation;
}

BodyId World::findBody(const std::string& bodyName) const {
  for (std::size_t i = 0; i < state_.size(); ++i)
    if (state_.alive[i] != 0 && names_[i] == bodyName) return idAt(i);
  return {};
}

std::size_t World::bodyCount() const {
  return static_cast<std::size_t>(std::count(state_.alive.begin(), state_.alive.end(), 1));
}

BodyId World::idAt(std::size_t index) const {
  if (index >= state_.size() || state_.alive[index] == 0) return {};
  return {static_cast<std::uint32_t>(index), generations_[index]};
}

std::size_t World::slotOf(BodyId id) const {
  if (!contains(id))
    throw CoulombError("body id (index " + std::to_string(id.index) + ", generation " +
                       std::to_string(id.generation) + ") is stale or invalid");
  return id.index;
}

const geometry::Pose& World::pose(BodyId id) const {
  return state_.poses[slotOf(id)];
}
Eigen::Vector3d World::linearVelocity(BodyId id) const {
  return state_.linearVelocities[slotOf(id)];
}
Eigen::Vector3d World::angularVelocity(BodyId id) const {
  return state_.angularVelocities[slotOf(id)];
}
const geometry::SpatialInertia& World::massProperties(BodyId id) const {
  return masses_[slotOf(id)];
}
const std::string& World::name(BodyId id) const {
  return names_[slotOf(id)];
}

void World::setVelocity(BodyId id, const Eigen::Vector3d& linear, const Eigen::Vector3d& angular) {
  const std::size_t i = slotOf(id);
  if (!linear.allFinite() || !angular.allFinite())
    throw CoulombError("setVelocity: velocities must be finite");
  if (state_.motionTypes[i] == geometry::MotionType::Static)
    throw CoulombError("setVelocity: body '" + names_[i] + "' is static");
  sleep_.wake(i, state_);
  state_.linearVelocities[i] = linear;
  state_.angularVelocities[i] = angular;
}

void World::applyForce(BodyId id, const Eigen::Vector3d& force) {
  const std::size_t i = slotOf(id);
  if (!force.allFinite()) throw CoulombError("applyForce: force must be finite");
  sleep_.wake(i, state_);
  state_.forces[i] += force;
}

void World::applyForceAtPoint(BodyId id, const Eigen::Vector3d& force,
                              const Eigen::Vector3d& worldPoint) {
  const std::size_t i = slotOf(id);
  if (!force.allFinite() || !worldPoint.allFinite())
    throw CoulombError("applyForceAtPoint: force and point must be finite");
  state_.forces[i] += force;
  state_.torques[i] += (worldPoint - state_.poses[i].position).cross(force);
  sleep_.wake(i, state_);
}

void World::applyTorque(BodyId id, const Eigen::Vector3d& torque) {
  const std::size_t i = slotOf(id);
  if (!torque.allFinite()) throw CoulombError("applyTorque: torque must be finite");
  state_.torques[i] += torque;
  sleep_.wake(i, state_);
}

void World::setGravity(const Eigen::Vector3d& gravity) {
  if (!gravity.allFinite()) throw CoulombError("setGravity: gravity must be finite");
  settings_.gravity = gravity;
}

double World::mechanicalEnergy() const {
  double energy = 0.0;
  for (std::size_t i = 0; i < state_.size(); ++i) {
    if (!state_.isDynamic(i) || !(state_.inverseMasses[i] > 0.0)) continue;
    energy += state_.kineticEnergy(i) -
              settings_.gravity.dot(state_.poses[i].position) / state_.inverseMasses[i];
  }
  return energy;
}

std::uint64_t World::stateHash() const {
  return geometry::stateHash(state_);
}

StepReport World::step(double h) {
  if (!std::isfinite(h) || h <= 0.0)
    throw CoulombError("step: h must be finite and > 0 s (got " + std::to_string(h) + ")");
  const auto started = std::chrono::steady_clock::now();
  StepReport report;
  report.stepIndex = stepCount_;
  report.timeStep = h;
  for (std::size_t i = 0; i < state_.size(); ++i) {
    if (state_.isDynamic(i)) ++report.dynamicBodies;
    if (state_.alive[i] != 0 && state_.motionTypes[i] == geometry::MotionType::Kinematic)
      ++report.kinematicBodies;
  }

  quarantine_.begin(state_, articulations_);                         // last good
  integrators::predictFreeVelocities(state_, settings_.gravity, h);  // v*
  articulations_.predictVelocities(settings_.gravity, h, state_);    // trees' v*
  guard("after the velocity prediction", report);                    // bad v*
  // Manifolds; speculative margins swept by v* (docs/collision.md).
  const geometry::SweepMotion sweep{state_.linearVelocities, state_.angularVelocities, h};
  collision_.step(colliders_, state_.poses, sweep, [this](const auto& a, const auto& b) {
    if (!articulations_.keepPair(a.body.index, b.body.index)) return false;
    if (quarantine_.isolated(a.body.index) || quarantine_.isolated(b.body.index)) return false;
    return state_.isDynamic(a.body.index) || state_.isDynamic(b.body.index) ||
           articulations_.isLink(a.body.index) || articulations_.isLink(b.body.index);
  });
  sleep_.wakeTouched(collision_.cache().manifolds(), state_, settings_.gravity, h);  // touched
  std::vector<ConstraintEdge> edges = constraintEdges();
  articulations_.appendConstraintEdges(edges, h);  // tree joint limits and loop closures
  articulations_.mapEdges(edges);                  // a tree is one unit (its root link's proxy)
  const std::vector<Island> islands = islandBuilder_.build(dynamicMask(), edges);
  joints_.stiffenLoadedBodies(state_, h);  // geometric stiffness of heavy joint loads
  std::vector<joints::RowSet> rows(islands.size());
  std::vector<std::vector<ContactRowSource>> sources(islands.size());
  std::vector<VelocityProblemNormals> normals(islands.size());  // W_NN for the split impulse
  for (std::size_t k = 0; k < islands.size(); ++k)              // v* -> v+
    report.islands.push_back(solveIsland(islands[k], h, rows[k], sources[k], normals[k]));
  joints_.restoreInertias(state_);                                               // true inertia
  joints_.correctDrift(state_, settings_.jointStabilization, h, report.joints);  // predicted state
  integrators::integratePositions(state_, h);                                    // x+ from v+
  articulations_.integratePositions(h, state_);            // q+ from qd+; link proxies follow
  correctPenetrations(h, rows, sources, normals, report);  // split impulse
  joints_.finishStep(state_, h, report.joints);            // reactions, breakage, drift
  sleep_.update(islands, state_, settings_.sleep, h);      // slow islands fall asleep
  guard("at the end of the step", report);                 // non-finite or runaway bodies

  state_.clearForces();
  articulations_.clearForces();
  report.collision = collision_.diagnostics().stats;
  report.collisionFailures = collision_.diagnostics().failures;
  report.sleepingBodies = sleep_.sleepingBodies(state_);
  ++stepCount_;
  time_ += h;
  report.time = time_;
  report.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return report;
}

void World::guard(const char* stage, StepReport& report) {
  for (std::size_t i = 0; i < state_.size(); ++i) {
    if (!state_.isDynamic(i) || quarantine_.isolated(i)) continue;
    const std::optional<std::string> why = quarantine_.check(i, state_, settings_.quarantine);
    if (!why) continue;
    const BodyId id = idAt(i);
    quarantine_.isolate(i, state_);
    for (const geometry::JointId joint : joints_.jointsOf(id)) joints_.breakJoint(joint);
    report.quarantined.push_back({id, {}, names_[i], *why + " " + stage});
  }
  for (QuarantineEvent& e : quarantine_.guardTrees(articulations_, state_, settings_.quarantine)) {
    e.name = names_[articulations_.linkBody(e.articulation, 0).index];
    e.reason += std::string(" ") + stage;
    report.quarantined.push_back(std::move(e));
  }
}

IslandReport World::solveIsland(const Island& island, double h, joints::RowSet& rows,
                                std::vector<ContactRowSource>& sources,
                                VelocityProblemNormals& normals) {
  auto& manifolds = collision_.cache().manifolds();
  const Island bodyPart = articulations_.withoutTreeConstraints(island);
  joints::RowSet all = joints_.emitRows(bodyPart, state_, settings_.jointStabilization, h);
  const std::size_t jointBlocks = all.blocks.size();  // joint rows first, then the contacts
  const Island contactPart = joints_.contactPart(bodyPart);
  if (settings_.contact.impactLaw == ImpactLaw::Propagating)  // pairwise impacts change v* first
    propagateImpacts(contactPart, manifolds, settings_.contact, h, state_);
  rows = emitContactRows(contactPart, manifolds, state_, settings_.contact, h, sources);
  all.blocks.reserve(all.blocks.size() + rows.blocks.size());
  all.blocks.insert(all.blocks.end(), rows.blocks.begin(), rows.blocks.end());
  const std::size_t treeBlocks = all.blocks.size();  // tree limits and closures last
  articulations_.emitRows(island, state_, h, all);
  AssembledProblem assembled =
      assembler_.assemble(all, state_, &articulations_);  // W = J M^-1 J^T, q = J v*
  if (problemObserver_) problemObserver_(island.id, assembled.problem);
  normals.W = assembled.problem.W;  // shared storage, no copy
  normals.normalRows.clear();
  for (std::size_t k = jointBlocks; k < jointBlocks + rows.blocks.size(); ++k)
    normals.normalRows.push_back(assembled.slots[k].offset);
  const std::string& override = solverOverrides_[island.bodies.front()];
  const std::string& requested = override.empty() ? settings_.solver : override;
  // Automatic plans only (and WorldSettings::promoteFallbacks): the solver that finished this
  // island's last step goes first (a named solver always runs first).
  const bool automatic = settings_.promoteFallbacks && (requested.empty() || requested == "auto") &&
                         assembled.problem.size() > kPromotionMinUnknowns;
  bool promoted = false;
  solvers::SolvePlan plan = solvers::SolverChooser().choose(
      assembled.problem, {assembled.degreesOfFreedom}, requested, settings_.solverOptions);
  if (automatic) plan = promotion_.apply(island, std::move(plan), promoted);
  solvers::PlanOutcome outcome = solvers::solveWithFallback(assembled.problem, plan, registry_);
  promotion_.record(island, plan, outcome, promoted || !automatic);
  applyImpulses(all, assembled.slots, outcome.best.impulses, state_);  // v+ = v* + M^-1 J^T r
  articulations_.applyImpulses(all, assembled.slots, outcome.best.impulses, state_);  // qd+
  articulations_.storeImpulses(all, treeBlocks, assembled.slots, outcome.best.impulses);
  joints_.storeImpulses(all, jointBlocks, assembled.slots, outcome.best.impulses);
  const std::vector<RowBlockSlot> contactSlots(assembled.slots.begin() + jointBlocks,
                                               assembled.slots.end());
  storeContactImpulses(rows, contactSlots, outcome.best.impulses, sources, manifolds);

  IslandReport report;
  report.island = island.id;
  report.bodies = island.bodies.size();
  report.contacts = rows.blocks.size();
  report.unknowns = assembled.problem.size();
  report.degreesOfFreedom = assembled.degreesOfFreedom;
  report.reason = plan.reason;
  report.solve = std::move(outcome.best.report);
  report.attempts = std::move(outcome.attempts);
  return report;
}

void World::correctPenetrations(double h, std::vector<joints::RowSet>& rows,
                                std::vector<std::vector<ContactRowSource>>& sources,
                                const std::vector<VelocityProblemNormals>& normals,
                                StepReport& report) {
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto started = std::chrono::steady_clock::now();
    correctPenetration(rows[k], sources[k], settings_.contact.penetration, h, state_,
                       &articulations_, &normals[k]);
    report.islands[k].penetrationSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  }
}

std::vector<ConstraintEdge> World::constraintEdges() {
  std::vector<ConstraintEdge> edges = contactEdges();
  joints_.appendEdges(edges);
  return edges;
}

std::vector<ConstraintEdge> World::contactEdges() const {
  const auto& manifolds = collision_.cache().manifolds();
  std::vector<ConstraintEdge> edges;
  edges.reserve(manifolds.size());
  for (const geometry::ContactManifold& m : manifolds)
    edges.push_back(
        {static_cast<std::int32_t>(m.bodyA.index), static_cast<std::int32_t>(m.bodyB.index)});
  return edges;
}

std::vector<std::uint8_t> World::dynamicMask() const {
  std::vector<std::uint8_t> mask(state_.size());
  for (std::size_t i = 0; i < state_.size(); ++i) mask[i] = state_.isDynamic(i) ? 1 : 0;
  articulations_.markIslandBodies(mask);  // a tree counts once, as its root link's proxy
  return mask;
}

}  // namespace coulomb::engine
