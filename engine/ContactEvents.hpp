#pragma once
// Contact and sensor events of a step (Jolt's ContactListener added/persisted/removed, Box2D
// v3's contact begin/end and sensor events), read after World::step without touching the
// contact cache (docs/embedding.md, "Contact events and hooks"). A contact pair *touches* when
// one of its points is within ContactSettings::touchingTolerance of touching or the solve
// pushed on it (a speculative point that closed during the step); a sensor pair *overlaps* when
// one of its points touches. Events come in collider-pair order: deterministic.
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/geometry/Collider.hpp>
#include <coulomb/geometry/ContactManifold.hpp>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace coulomb::engine {

namespace io {
struct SnapshotAccess;  // io/Snapshot.cpp saves and restores the touching pairs
}

enum class ContactEventType : std::uint8_t {
  Begin,    // the pair touches this step and did not in the last
  Persist,  // touches in both
  End,      // touched in the last step, not in this one (or a collider was removed)
};

struct ContactEventPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // world, at the start of the step
  double depth = 0.0;                                  // [m] > 0 overlapping, < 0 gap
  double normalImpulse = 0.0;                          // [N s] this step's, at this point
};

struct ContactEvent {
  ContactEventType type = ContactEventType::Begin;
  geometry::ColliderId colliderA;  // colliderA < colliderB
  geometry::ColliderId colliderB;
  geometry::BodyId bodyA;  // stale after removeBody (End events of removed bodies)
  geometry::BodyId bodyB;
  // Begin and Persist only (zero for End):
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit, from A to B
  std::array<ContactEventPoint, geometry::ContactManifold::kMaxPoints> points{};
  int pointCount = 0;
  double normalImpulse = 0.0;  // [N s] total over the points (divide by h for the mean force)
  Eigen::Vector3d tangentImpulse = Eigen::Vector3d::Zero();  // [N s] total friction impulse on B
  /// [m/s] Fastest approach of the pair's points before the solve, max(0, -n . (v_B - v_A)) at
  /// the predicted velocities: what an impact sound or damage model wants.
  double approachSpeed = 0.0;
};

struct SensorEvent {
  bool begin = true;  // true: the visitor started overlapping the sensor; false: stopped
  geometry::ColliderId sensor;
  geometry::ColliderId visitor;
  geometry::BodyId sensorBody;
  geometry::BodyId visitorBody;
};

/// Keeps the touching pairs from step to step and turns their changes into events. Pairs of
/// bodies that are all asleep or not moving (static, kinematic at rest) are not detected while
/// they stay so; they keep touching silently (no Persist, no End) until one wakes.
class ContactEvents {
 public:
  /// After the solve of a step: `manifolds` sorted by collider pair (the contact cache's),
  /// `colliders` sorted by id (the World's).
  void update(const std::vector<geometry::ContactManifold>& manifolds,
              const std::vector<geometry::Collider>& colliders, const geometry::BodyState& state,
              double touchingTolerance);
  [[nodiscard]] const std::vector<ContactEvent>& contacts() const { return contacts_; }
  [[nodiscard]] const std::vector<SensorEvent>& sensors() const { return sensors_; }

 private:
  friend struct io::SnapshotAccess;
  struct Touch {
    geometry::ColliderId colliderA;
    geometry::ColliderId colliderB;
    geometry::BodyId bodyA;
    geometry::BodyId bodyB;
    std::uint8_t sensor = 0;  // 0: a contact; 1: A is the sensor; 2: B is
  };
  void begin(const geometry::ContactManifold& m, const Touch& touch, bool persist);
  void end(const Touch& touch);

  std::vector<Touch> touching_;  // sorted by (colliderA, colliderB)
  std::vector<Touch> previous_;  // the last step's, while update() runs
  std::vector<ContactEvent> contacts_;
  std::vector<SensorEvent> sensors_;
};

}  // namespace coulomb::engine
