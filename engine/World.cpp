#include <coulomb/engine/BodyBuilder.hpp>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>

#include <algorithm>
#include <cmath>

namespace coulomb::engine {

using geometry::BodyId;

namespace {

// A body's own choice: not empty unless automatic, every solver in the registry.
void checkChoice(const solvers::SolverRegistry& registry, const solvers::SolverChoice& choice,
                 const std::string& who) {
  if (choice.mode != solvers::ChoiceMode::Automatic && choice.attempts.empty())
    throw CoulombError(who + "empty solver choice");
  if (auto unknown = solvers::unknownSolver(choice, registry))
    throw CoulombError(who + "unknown solver '" + *unknown + "' (see `coulomb solvers`)");
}

}  // namespace

World::World(WorldSettings settings)
    : settings_(std::move(settings)), collision_(settings_.collision) {
  if (auto problem = settings_.validate()) throw CoulombError("world settings: " + *problem);
  if (auto problem = settings_.solve.validate(&registry_))
    throw CoulombError("world settings: " + *problem + " (see `coulomb solvers`)");
  if (!registry_.find(settings_.contact.penetration.solver))
    throw CoulombError("world settings: unknown penetration solver '" +
                       settings_.contact.penetration.solver + "' (see `coulomb solvers`)");
}

void World::setSolver(const solvers::SolverChoice& choice) {
  solvers::SolvePolicy policy = settings_.solve;
  policy.choice = choice;
  setSolvePolicy(policy);
}

void World::setSolvePolicy(const solvers::SolvePolicy& policy) {
  if (auto problem = policy.validate(&registry_))
    throw CoulombError("setSolvePolicy: " + *problem + " (see `coulomb solvers`)");
  settings_.solve = policy;
  if (!policy.promotion.enabled) promotion_.resetAll();
}

void World::setSolverOverride(BodyId id, std::optional<solvers::SolverChoice> choice) {
  const std::size_t i = slotOf(id);
  if (choice) checkChoice(registry_, *choice, "setSolverOverride: body '" + names_[i] + "': ");
  solverOverrides_[i] = std::move(choice);
}

BodyId World::createBody(const BodyDesc& desc) {
  ResolvedBody body = resolveBody(desc, settings_);  // throws before anything is changed
  if (desc.solver) checkChoice(registry_, *desc.solver, "body '" + desc.name + "': ");
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
    collider.continuous = desc.continuousCollision;
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

}  // namespace coulomb::engine
