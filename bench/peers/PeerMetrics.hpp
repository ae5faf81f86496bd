#pragma once
// The metrics of docs/conformance.md part A, computed the same way for every engine from the
// sampled states (sample k at t = k dt, k = 0 is the state after building).
#include "PeerEngine.hpp"

#include <string>
#include <vector>

namespace coulomb::peers {

struct Metric {
  std::string name;
  double value;
};

using Trajectory = std::vector<std::vector<BodySample>>;

/// The scene's metrics (docs/conformance.md A2-A7; the stacks also get `max_disp`, the largest COM
/// displacement of any body, as the drift of bodies that should rest). Samples missing because a
/// run stopped early give NaN where the metric needs them.
std::vector<Metric> sceneMetrics(const PeerScene& scene, const Trajectory& samples);

/// The one or two metrics the summary table shows for the scene, with their ideal value.
std::vector<std::string> keyMetrics(const std::string& scene);

}  // namespace coulomb::peers
