#pragma once
// The sanity limits of the World-level guard (engine/Quarantine.hpp); part of WorldSettings.
#include <optional>
#include <string>

namespace coulomb::engine {

struct QuarantineSettings {
  /// [m] Largest |COM position|. Default 1e7 m: the ulp of a coordinate there is ~2e-9 m, still
  /// finer than any contact tolerance, and no scene is larger than the Earth.
  double maxPosition = 1e7;
  /// [m/s] Largest COM speed. Default 1e6 m/s: 300 times a rifle bullet; at h = 0.01 s such a
  /// body moves 10 km per step, so no contact can be resolved anyway.
  double maxLinearSpeed = 1e6;
  /// [rad/s] Largest angular speed (also the limit for each joint rate of a tree). Default 1e6.
  double maxAngularSpeed = 1e6;

  [[nodiscard]] std::optional<std::string> validate() const;
};

}  // namespace coulomb::engine
