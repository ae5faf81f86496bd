#pragma once
// Sleep: islands whose bodies have all stayed slow for a while stop being integrated and solved
// (they act like static bodies), and wake when an awake body touches them or the user acts on one
// of their bodies. Off by default: every "at rest" test and benchmark runs with it off, so a
// stack must stand by its own physics, never because it was frozen.
#include <coulomb/engine/IslandBuilder.hpp>
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/geometry/ContactManifold.hpp>

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace coulomb::engine {

struct SleepSettings {
  bool enabled = false;  // default off (see above)
  /// [m/s] A body is slow while its COM speed stays below this. Default 0.02 m/s: a quarter of
  /// the speed gravity adds in one 0.01 s step, so a body resting on contacts qualifies and a
  /// body in free fall or sliding does not.
  double linearSpeed = 0.02;
  /// [rad/s] ... and its angular speed below this. Default 0.05 rad/s.
  double angularSpeed = 0.05;
  /// [s] How long every body of an island must stay slow before the island sleeps. Default
  /// 0.5 s: long enough that the turning point of a bounce or a swing does not put it to sleep.
  double timeToSleep = 0.5;

  [[nodiscard]] std::optional<std::string> validate() const;
};

namespace io {
struct SnapshotAccess;  // io/Snapshot.cpp saves and restores the private state
}

class Sleep {
 public:
  /// Wakes every sleeping group touched by an awake dynamic body or a moving kinematic one in
  /// `manifolds` (a body dropped on a sleeping stack wakes the stack; sensors wake nothing). Woken
  /// bodies get the free-flight velocity of this step (gravity h) they missed. Returns the number
  /// of bodies woken.
  std::size_t wakeTouched(const std::vector<geometry::ContactManifold>& manifolds,
                          geometry::BodyState& state, const Eigen::Vector3d& gravity, double h);
  /// Wakes the sleeping group of body `index` (user action: velocity, force, torque).
  void wake(std::size_t index, geometry::BodyState& state);
  /// End of a step: advances the slow timers and puts to sleep each island (and each free body)
  /// whose bodies have all been slow for timeToSleep; their velocities become exactly zero.
  void update(const std::vector<Island>& islands, geometry::BodyState& state,
              const SleepSettings& settings, double h);
  [[nodiscard]] std::size_t sleepingBodies(const geometry::BodyState& state) const;

 private:
  friend struct io::SnapshotAccess;
  void resize(std::size_t n);
  std::vector<double> slowFor_;      // [s] per body: how long it has been slow
  std::vector<std::int32_t> group_;  // per sleeping body: the island (smallest body) it slept with
  std::vector<std::uint8_t> wasAsleep_;  // wakeTouched(): asleep before this step's contacts
};

}  // namespace coulomb::engine
