// The World's embedding hooks: kinematic targets, user data, collider look-up, and the pre-solve
// stage of the step (ContactHooks.hpp; docs/embedding.md, "Contact events and hooks").
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/geometry/Quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace coulomb::engine {

void World::setKinematicTarget(geometry::BodyId id, const geometry::Pose& target, double h) {
  const std::size_t i = slotOf(id);
  const std::string who = "setKinematicTarget: body '" + names_[i] + "'";
  if (state_.motionTypes[i] != geometry::MotionType::Kinematic || articulations_.isLink(i))
    throw CoulombError(who + " is not a kinematic body of its own (links follow their tree)");
  if (!std::isfinite(h) || h <= 0.0)
    throw CoulombError(who + ": h must be finite and > 0 s (got " + std::to_string(h) + ")");
  if (!target.position.allFinite() || !target.rotation.coeffs().allFinite() ||
      std::abs(target.rotation.norm() - 1.0) > 1e-6)
    throw CoulombError(who + ": the target pose must be finite with a unit quaternion");
  const Eigen::Quaterniond rotation = target.rotation.normalized();
  // The body frame is the COM frame with the reference frame's axes (BodyDesc.hpp).
  const Eigen::Vector3d centre = target.position + rotation * masses_[i].centerOfMass;
  const geometry::Pose& now = state_.poses[i];
  // integratePositions moves a kinematic body by x += h v and q <- exp(h w) q
  // (PositionUpdate.cpp), so these arrive at the target to rounding.
  state_.linearVelocities[i] = (centre - now.position) / h;
  state_.angularVelocities[i] = geometry::quaternionLog(rotation * now.rotation.conjugate()) / h;
}

std::uint64_t World::userData(geometry::BodyId id) const {
  return userData_[slotOf(id)];
}

void World::setUserData(geometry::BodyId id, std::uint64_t value) {
  userData_[slotOf(id)] = value;
}

const geometry::Collider* World::findCollider(geometry::ColliderId id) const {
  const auto it = std::lower_bound(
      colliders_.begin(), colliders_.end(), id,
      [](const geometry::Collider& c, geometry::ColliderId key) { return c.id < key; });
  return it != colliders_.end() && it->id == id ? &*it : nullptr;
}

const geometry::Collider& World::collider(geometry::ColliderId id) const {
  if (const geometry::Collider* c = findCollider(id)) return *c;
  throw CoulombError("collider " + std::to_string(id.index) + " does not exist (removed?)");
}

void World::modifyContacts() {
  if (!preSolve_) return;
  for (geometry::ContactManifold& m : collision_.cache().manifolds()) {
    if (m.sensor) continue;
    const geometry::Collider* a = findCollider(m.colliderA);
    const geometry::Collider* b = findCollider(m.colliderB);
    if (a == nullptr || b == nullptr) continue;
    ContactModification change{m, *a, *b, m.friction, m.restitution, m.surfaceVelocity, m.enabled};
    preSolve_(change);
    const bool valid = std::isfinite(change.friction) && change.friction >= 0.0 &&
                       std::isfinite(change.restitution) && change.restitution >= 0.0 &&
                       change.restitution <= 1.0 && change.surfaceVelocity.allFinite();
    m.enabled = change.enabled;
    if (valid) {
      m.friction = change.friction;
      m.restitution = change.restitution;
      m.surfaceVelocity = change.surfaceVelocity;
      continue;
    }
    const std::string key = "pre-solve hook: invalid value";
    if (std::find(warned_.begin(), warned_.end(), key) != warned_.end()) continue;
    warned_.push_back(key);
    std::ostringstream s;
    s << "the pre-solve hook set friction " << change.friction << ", restitution "
      << change.restitution << " or a non-finite surface velocity on the contact of colliders "
      << m.colliderA.index << " and " << m.colliderB.index
      << ": not used (the materials' values stay). Said once.";
    report_.warnings.push_back(s.str());
  }
}

}  // namespace coulomb::engine
