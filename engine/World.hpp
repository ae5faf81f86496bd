#pragma once
// The World owns the body state, the colliders and the settings, and advances them in time.
// step() reads as the data flow of ARCHITECTURE.md section 2 with the stages that exist so far.
#include <coulomb/engine/BodyDesc.hpp>
#include <coulomb/engine/StepReport.hpp>
#include <coulomb/engine/WorldSettings.hpp>
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/geometry/Collider.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace coulomb::engine {

class World {
 public:
  /// Throws CoulombError if a setting is invalid.
  explicit World(WorldSettings settings = {});

  /// Validates `desc` and adds the body with its colliders. On invalid input throws CoulombError
  /// naming the value (e.g. "body 'ball': mass must be finite and > 0 (got -1)") and adds nothing.
  geometry::BodyId createBody(const BodyDesc& desc);
  /// Removes the body and its colliders; its id (and any copy of it) becomes stale.
  void removeBody(geometry::BodyId id);
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

  /// Advances by h [s] (finite, > 0; else CoulombError) or by settings().timeStep.
  StepReport step(double h);
  StepReport step() { return step(settings_.timeStep); }

  [[nodiscard]] const geometry::BodyState& state() const { return state_; }
  [[nodiscard]] const std::vector<geometry::Collider>& colliders() const { return colliders_; }
  [[nodiscard]] const WorldSettings& settings() const { return settings_; }
  void setGravity(const Eigen::Vector3d& gravity);
  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] std::uint64_t stepCount() const { return stepCount_; }
  /// Hash of every body's pose and velocities (bit patterns): equal across identical runs.
  [[nodiscard]] std::uint64_t stateHash() const;
  /// The id of the body in slot `index` (for iterating over state() arrays), or an invalid id.
  [[nodiscard]] geometry::BodyId idAt(std::size_t index) const;

 private:
  std::size_t slotOf(geometry::BodyId id) const;  // throws for a stale id

  WorldSettings settings_;
  geometry::BodyState state_;
  std::vector<std::uint32_t> generations_;        // per slot
  std::vector<std::uint32_t> freeSlots_;          // reused lowest-first (deterministic)
  std::vector<std::string> names_;                // per slot
  std::vector<geometry::SpatialInertia> masses_;  // per slot: mass, COM in the reference frame
  std::vector<geometry::Collider> colliders_;
  std::uint32_t colliderCounter_ = 0;
  double time_ = 0.0;
  std::uint64_t stepCount_ = 0;
};

}  // namespace coulomb::engine
