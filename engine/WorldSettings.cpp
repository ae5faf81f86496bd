#include <coulomb/engine/WorldSettings.hpp>

#include <cmath>
#include <sstream>

namespace coulomb::engine {

std::optional<std::string> WorldSettings::validate() const {
  std::ostringstream out;
  if (!gravity.allFinite()) {
    out << "gravity must be finite (got " << gravity.transpose() << ")";
  } else if (!std::isfinite(timeStep) || timeStep <= 0.0) {
    out << "time_step must be finite and > 0 s (got " << timeStep << ")";
  } else if (!std::isfinite(defaultDensity) || defaultDensity <= 0.0) {
    out << "default density must be finite and > 0 kg/m^3 (got " << defaultDensity << ")";
  } else if (!std::isfinite(unitQuaternionTolerance) || unitQuaternionTolerance < 0.0) {
    out << "unit quaternion tolerance must be finite and >= 0 (got " << unitQuaternionTolerance
        << ")";
  } else {
    return std::nullopt;
  }
  return out.str();
}

}  // namespace coulomb::engine
