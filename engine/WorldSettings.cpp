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
  } else if (auto bad = solve.validate(nullptr)) {
    out << *bad;
  } else if (assembly.sparseRowLimit < 0) {
    out << "assembly sparse row limit must be >= 0 (got " << assembly.sparseRowLimit << ")";
  } else if (contact.penetration.iterations < 1 || !(contact.penetration.tolerance > 0.0)) {
    out << "penetration iterations must be >= 1 and tolerance > 0";
  } else if (contact.penetration.solver.empty()) {
    out << "penetration solver must name a solver (see `coulomb solvers`)";
  } else if (!std::isfinite(contact.restitutionThreshold) || contact.restitutionThreshold < 0.0) {
    out << "restitution threshold must be finite and >= 0 m/s (got " << contact.restitutionThreshold
        << ")";
  } else if (!std::isfinite(contact.touchingTolerance) || contact.touchingTolerance < 0.0) {
    out << "touching tolerance must be finite and >= 0 m (got " << contact.touchingTolerance << ")";
  } else if (contact.maxImpactSweeps < 1) {
    out << "max impact sweeps must be >= 1 (got " << contact.maxImpactSweeps << ")";
  } else if (!(contact.penetration.beta >= 0.0 && contact.penetration.beta <= 1.0)) {
    out << "penetration beta must be in [0, 1] (got " << contact.penetration.beta << ")";
  } else if (!std::isfinite(contact.penetration.slop) || contact.penetration.slop < 0.0) {
    out << "penetration slop must be finite and >= 0 m (got " << contact.penetration.slop << ")";
  } else if (!std::isfinite(collision.speculativeMargin) || collision.speculativeMargin < 0.0) {
    out << "speculative margin must be finite and >= 0 m (got " << collision.speculativeMargin
        << ")";
  } else if (!std::isfinite(collision.speculativeSweep) || collision.speculativeSweep < 0.0) {
    out << "speculative sweep must be finite and >= 0 (got " << collision.speculativeSweep << ")";
  } else if (auto bad = jointStabilization.validate()) {
    out << "joint stabilization: " << *bad;
  } else if (auto badSleep = sleep.validate()) {
    out << *badSleep;
  } else if (auto badGuard = quarantine.validate()) {
    out << *badGuard;
  } else if (threads < 0 || threads > kMaxThreads) {
    out << "threads must be 0 (every hardware thread) or 1.." << kMaxThreads << " (got " << threads
        << ")";
  } else {
    return std::nullopt;
  }
  return out.str();
}

}  // namespace coulomb::engine
