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

// The whole settings struct against itself and the registry (`who` starts the message).
void checkSettings(const WorldSettings& settings, const solvers::SolverRegistry& registry,
                   const std::string& who) {
  if (auto problem = settings.validate()) throw CoulombError(who + *problem);
  if (auto problem = settings.solve.validate(&registry))
    throw CoulombError(who + *problem + " (see `coulomb solvers`)");
  if (!registry.find(settings.contact.penetration.solver))
    throw CoulombError(who + "unknown penetration solver '" + settings.contact.penetration.solver +
                       "' (see `coulomb solvers`)");
}

}  // namespace

World::World(WorldSettings settings)
    : settings_(std::move(settings)), collision_(settings_.collision) {
  checkSettings(settings_, registry_, "world settings: ");
  executor_.setThreads(settings_.threads);
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

void World::setSettings(const WorldSettings& settings) {
  checkSettings(settings, registry_, "setSettings: ");
  if (!(settings.collision == collision_.settings()))
    throw CoulombError(
        "setSettings: the collision settings (speculative margin and sweep, match distance, mesh "
        "contacts) are fixed when the World is built; build a new World to change them");
  const bool wakeAll = settings_.sleep.enabled && !settings.sleep.enabled;
  settings_ = settings;
  executor_.setThreads(settings_.threads);
  if (!settings_.solve.promotion.enabled) promotion_.resetAll();
  if (wakeAll)
    for (std::size_t i = 0; i < state_.size(); ++i)
      if (state_.alive[i] != 0 && state_.asleep[i] != 0) sleep_.wake(i, state_);
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
    userData_.emplace_back();
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
  userData_[slot] = desc.userData;
  const BodyId id{static_cast<std::uint32_t>(slot), generations_[slot]};
  for (ResolvedShape& s : body.shapes) attachCollider(id, std::move(s), desc.continuousCollision);
  return id;
}

geometry::ColliderId World::attachCollider(BodyId body, ResolvedShape shape, bool continuous) {
  geometry::Collider collider;
  collider.id =
      geometry::ColliderId{colliderCounter_++, 0};  // the largest: colliders_ stays sorted
  collider.body = body;
  collider.localPose = shape.localPose;
  collider.shape = std::move(shape.shape);
  collider.material = shape.material;
  collider.filter = shape.filter;
  collider.continuous = continuous;
  collider.sensor = shape.sensor;
  collider.userData = shape.userData;
  colliders_.push_back(std::move(collider));
  return colliders_.back().id;
}

geometry::ColliderId World::addCollider(BodyId body, const ShapeDesc& shape) {
  const std::size_t slot = slotOf(body);
  // Checked as createBody checks a shape, on a stand-in body of the same type whose explicit
  // unit mass keeps the resolver from computing one (the body's own mass does not change).
  BodyDesc probe;
  probe.name = names_[slot];
  probe.motionType = state_.motionTypes[slot];
  probe.mass = geometry::SpatialInertia{1.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()};
  probe.shapes.push_back(shape);
  ResolvedBody resolved = resolveBody(probe, settings_);  // throws before anything changes
  ResolvedShape& s = resolved.shapes.front();
  s.localPose.position -= masses_[slot].centerOfMass;  // reference frame -> COM frame
  bool continuous = false;
  for (const geometry::Collider& c : colliders_)
    continuous = continuous || (c.body == body && c.continuous);
  return attachCollider(body, std::move(s), continuous);
}

void World::removeCollider(geometry::ColliderId id) {
  const geometry::Collider* c = findCollider(id);
  if (c == nullptr)
    throw CoulombError("removeCollider: collider " + std::to_string(id.index) +
                       " does not exist (removed?)");
  colliders_.erase(colliders_.begin() + (c - colliders_.data()));
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
  userData_[slot] = 0;
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

void World::removeArticulation(geometry::ArticulationId id) {
  for (const BodyId proxy : articulations_.remove(id)) removeBody(proxy);  // no longer links
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

void World::setJointMotorTarget(geometry::ArticulationId id, const std::string& joint,
                                double target) {
  articulations_.setMotorTarget(id, articulations_.motorOf(id, joint), target);
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
