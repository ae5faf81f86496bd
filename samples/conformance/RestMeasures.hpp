#pragma once
// Measurements shared by the structure and stability cases (docs/scene-specifications.md A3, A4,
// B1-B3): how far the dynamic bodies moved from their start, the total mechanical energy, the
// lowest point of any dynamic shape. They read World::state() only, so they never change a run.
#include <coulomb/engine/World.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace coulomb::conformance {

/// Tracks ||p - p0|| of every dynamic body's COM (docs/scene-specifications.md `max_disp`), from
/// the construction.
class DisplacementTracker {
 public:
  explicit DisplacementTracker(const engine::World& world);
  /// Samples the current state (call after each step); returns the largest displacement now.
  double sample(const engine::World& world);
  [[nodiscard]] double maxDisplacement() const { return max_; }  // [m] over every sample
  /// [m] displacement of slot `index` now (after the last sample).
  [[nodiscard]] double displacement(const engine::World& world, std::size_t index) const;
  [[nodiscard]] const Eigen::Vector3d& start(std::size_t index) const { return start_[index]; }

 private:
  std::vector<Eigen::Vector3d> start_;
  double max_ = 0.0;
};

/// [J] kinetic energy of the dynamic bodies.
double kineticEnergy(const engine::World& world);
/// [m] lowest z of any shape of a dynamic body (box corners, hull vertices, sphere, capsule).
double lowestDynamicPoint(const engine::World& world);
/// True if every body's pose and velocities are finite.
bool stateFinite(const engine::World& world);

}  // namespace coulomb::conformance
