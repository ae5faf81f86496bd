#include <coulomb/engine/BodyBuilder.hpp>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/integrators/FreeMotion.hpp>
#include <coulomb/integrators/PositionUpdate.hpp>

#include <algorithm>
#include <cmath>

namespace coulomb::engine {

using geometry::BodyId;

World::World(WorldSettings settings) : settings_(std::move(settings)) {
  if (auto problem = settings_.validate()) throw CoulombError("world settings: " + *problem);
}

BodyId World::createBody(const BodyDesc& desc) {
  ResolvedBody body = resolveBody(desc, settings_);  // throws before anything is changed
  std::size_t slot = state_.size();
  if (!freeSlots_.empty()) {
    const auto lowest = std::min_element(freeSlots_.begin(), freeSlots_.end());
    slot = *lowest;
    freeSlots_.erase(lowest);
  } else {
    generations_.push_back(0);
    names_.emplace_back();
    masses_.emplace_back();
  }
  state_.assign(slot, desc.motionType, body.comPose, desc.linearVelocity, desc.angularVelocity,
                body.massProperties.mass, body.massProperties.inertiaAboutCom);
  names_[slot] = desc.name;
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
  std::erase_if(colliders_, [&](const geometry::Collider& c) { return c.body == id; });
  state_.clear(slot);
  names_[slot].clear();
  masses_[slot] = {};
  ++generations_[slot];
  freeSlots_.push_back(static_cast<std::uint32_t>(slot));
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
  state_.linearVelocities[i] = linear;
  state_.angularVelocities[i] = angular;
}

void World::applyForce(BodyId id, const Eigen::Vector3d& force) {
  const std::size_t i = slotOf(id);
  if (!force.allFinite()) throw CoulombError("applyForce: force must be finite");
  state_.forces[i] += force;
}

void World::applyForceAtPoint(BodyId id, const Eigen::Vector3d& force,
                              const Eigen::Vector3d& worldPoint) {
  const std::size_t i = slotOf(id);
  if (!force.allFinite() || !worldPoint.allFinite())
    throw CoulombError("applyForceAtPoint: force and point must be finite");
  state_.forces[i] += force;
  state_.torques[i] += (worldPoint - state_.poses[i].position).cross(force);
}

void World::applyTorque(BodyId id, const Eigen::Vector3d& torque) {
  const std::size_t i = slotOf(id);
  if (!torque.allFinite()) throw CoulombError("applyTorque: torque must be finite");
  state_.torques[i] += torque;
}

void World::setGravity(const Eigen::Vector3d& gravity) {
  if (!gravity.allFinite()) throw CoulombError("setGravity: gravity must be finite");
  settings_.gravity = gravity;
}

std::uint64_t World::stateHash() const {
  return geometry::stateHash(state_);
}

StepReport World::step(double h) {
  if (!std::isfinite(h) || h <= 0.0)
    throw CoulombError("step: h must be finite and > 0 s (got " + std::to_string(h) + ")");
  StepReport report;
  report.stepIndex = stepCount_;
  report.timeStep = h;
  for (std::size_t i = 0; i < state_.size(); ++i) {
    if (state_.isDynamic(i)) ++report.dynamicBodies;
    if (state_.alive[i] != 0 && state_.motionTypes[i] == geometry::MotionType::Kinematic)
      ++report.kinematicBodies;
  }
  integrators::predictFreeVelocities(state_, settings_.gravity, h);  // v*
  // Later stages (ARCHITECTURE.md section 2): broad phase, narrow phase, manifolds, islands,
  // row emission, assembly, solve with fallback, impulse application (v* -> v+).
  integrators::integratePositions(state_, h);  // q+ from v+
  state_.clearForces();
  ++stepCount_;
  time_ += h;
  report.time = time_;
  return report;
}

}  // namespace coulomb::engine
