#include <coulomb/joints/Stabilization.hpp>

#include <cmath>

namespace coulomb::joints {

const char* stabilizationMethodName(StabilizationMethod method) {
  switch (method) {
    case StabilizationMethod::Baumgarte:
      return "baumgarte";
    case StabilizationMethod::PredictedState:
      return "predicted_state";
    case StabilizationMethod::None:
      return "none";
  }
  return "?";
}

std::optional<StabilizationMethod> stabilizationMethodFromName(const std::string& name) {
  for (auto m : {StabilizationMethod::Baumgarte, StabilizationMethod::PredictedState,
                 StabilizationMethod::None})
    if (name == stabilizationMethodName(m)) return m;
  return std::nullopt;
}

const char* energyTargetName(EnergyTarget target) {
  switch (target) {
    case EnergyTarget::None:
      return "none";
    case EnergyTarget::Modified:
      return "modified";
    case EnergyTarget::Exact:
      return "exact";
  }
  return "?";
}

std::optional<EnergyTarget> energyTargetFromName(const std::string& name) {
  for (auto t : {EnergyTarget::None, EnergyTarget::Modified, EnergyTarget::Exact})
    if (name == energyTargetName(t)) return t;
  return std::nullopt;
}

std::optional<std::string> Stabilization::validate() const {
  if (!(baumgarte.beta >= 0.0 && baumgarte.beta <= 1.0))
    return "baumgarte beta must be in [0, 1] (got " + std::to_string(baumgarte.beta) + ")";
  if (!std::isfinite(baumgarte.slop) || baumgarte.slop < 0.0)
    return "baumgarte slop must be finite and >= 0 (got " + std::to_string(baumgarte.slop) + ")";
  if (predictedState.iterations < 1)
    return "predicted-state iterations must be >= 1 (got " +
           std::to_string(predictedState.iterations) + ")";
  if (!std::isfinite(predictedState.tolerance) || predictedState.tolerance <= 0.0)
    return "predicted-state tolerance must be finite and > 0 (got " +
           std::to_string(predictedState.tolerance) + ")";
  return std::nullopt;
}

}  // namespace coulomb::joints
