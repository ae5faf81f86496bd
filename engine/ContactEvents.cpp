#include <coulomb/engine/ContactEvents.hpp>

#include <algorithm>

namespace coulomb::engine {
namespace {

using geometry::Collider;
using geometry::ColliderId;
using geometry::ContactManifold;

const Collider* find(const std::vector<Collider>& colliders, ColliderId id) {
  const auto it = std::lower_bound(colliders.begin(), colliders.end(), id,
                                   [](const Collider& c, ColliderId key) { return c.id < key; });
  return it != colliders.end() && it->id == id ? &*it : nullptr;
}

bool touches(const ContactManifold& m, double tolerance) {
  for (const geometry::ContactPoint& p : m.activePoints())
    if (p.depth >= -tolerance || (!m.sensor && p.normalImpulse > 0.0)) return true;
  return false;
}

// True when the pair is not detected this step because neither body can move it (asleep,
// static, or kinematic at rest): it keeps the state it had.
bool frozen(const geometry::BodyState& state, geometry::BodyId body) {
  const std::size_t i = body.index;
  if (i >= state.size() || state.alive[i] == 0) return false;
  switch (state.motionTypes[i]) {
    case geometry::MotionType::Static:
      return true;
    case geometry::MotionType::Kinematic:
      return !state.isMovingKinematic(i);
    default:
      return state.asleep[i] != 0;
  }
}

// A sensor pair's event, the sensor first (`Touch` is ContactEvents' record of a pair).
template <class Touch>
SensorEvent sensorEvent(const Touch& touch, bool begin) {
  const bool aIsSensor = touch.sensor == 1;
  return {begin, aIsSensor ? touch.colliderA : touch.colliderB,
          aIsSensor ? touch.colliderB : touch.colliderA, aIsSensor ? touch.bodyA : touch.bodyB,
          aIsSensor ? touch.bodyB : touch.bodyA};
}

}  // namespace

void ContactEvents::begin(const ContactManifold& m, const Touch& touch, bool persist) {
  if (touch.sensor != 0) {
    if (!persist) sensors_.push_back(sensorEvent(touch, true));
    return;
  }
  ContactEvent& e = contacts_.emplace_back();
  e.type = persist ? ContactEventType::Persist : ContactEventType::Begin;
  e.colliderA = m.colliderA;
  e.colliderB = m.colliderB;
  e.bodyA = m.bodyA;
  e.bodyB = m.bodyB;
  e.normal = m.normal;
  e.pointCount = m.pointCount;
  for (int k = 0; k < m.pointCount; ++k) {
    const geometry::ContactPoint& p = m.points[static_cast<std::size_t>(k)];
    e.points[static_cast<std::size_t>(k)] = {p.position, p.depth, p.normalImpulse};
    e.normalImpulse += p.normalImpulse;
    e.tangentImpulse += p.tangentImpulse.x() * m.tangent1 + p.tangentImpulse.y() * m.tangent2;
    e.approachSpeed = std::max(e.approachSpeed, -p.approachVelocity);
  }
}

void ContactEvents::end(const Touch& touch) {
  if (touch.sensor != 0) {
    sensors_.push_back(sensorEvent(touch, false));
    return;
  }
  ContactEvent& e = contacts_.emplace_back();
  e.type = ContactEventType::End;
  e.colliderA = touch.colliderA;
  e.colliderB = touch.colliderB;
  e.bodyA = touch.bodyA;
  e.bodyB = touch.bodyB;
}

void ContactEvents::update(const std::vector<ContactManifold>& manifolds,
                           const std::vector<Collider>& colliders, const geometry::BodyState& state,
                           double touchingTolerance) {
  std::swap(previous_, touching_);
  touching_.clear();
  contacts_.clear();
  sensors_.clear();
  auto key = [](const Touch& t) { return std::pair(t.colliderA, t.colliderB); };
  std::size_t j = 0;  // into previous_
  // A pair of the last step that is not in this one: still touching if it was not looked at
  // (frozen bodies, colliders still there), else it ended.
  auto settle = [&](const Touch& old) {
    const bool kept = frozen(state, old.bodyA) && frozen(state, old.bodyB) &&
                      find(colliders, old.colliderA) != nullptr &&
                      find(colliders, old.colliderB) != nullptr;
    if (kept)
      touching_.push_back(old);
    else
      end(old);
  };
  for (const ContactManifold& m : manifolds) {
    if (!m.enabled || !touches(m, touchingTolerance)) continue;
    Touch touch{m.colliderA, m.colliderB, m.bodyA, m.bodyB, 0};
    if (m.sensor) {
      const Collider* a = find(colliders, m.colliderA);
      touch.sensor = a != nullptr && a->sensor ? 1 : 2;
    }
    while (j < previous_.size() && key(previous_[j]) < key(touch)) settle(previous_[j++]);
    const bool persist = j < previous_.size() && key(previous_[j]) == key(touch);
    if (persist) ++j;
    begin(m, touch, persist);
    touching_.push_back(touch);
  }
  while (j < previous_.size()) settle(previous_[j++]);
}

}  // namespace coulomb::engine
