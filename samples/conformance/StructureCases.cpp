// Structures that stand only through friction (issue 8 item 1; docs/scene-specifications.md B2,
// B3): the card house stands at mu 0.6 and must collapse at mu 0.2 (static LP: mu_min = 0.3292);
// the 17-voussoir masonry arch stands at mu 0.6 (crown thrust inside the admissible [1022.8,
// 2134.2] N, each abutment carrying W/2 = 3852.378 N) and must collapse at mu 0.2 and 0.1
// (thrust-line LP: mu_min = 0.3086). One built-in scene per friction coefficient
// (scripts/generate_structure_scenes.py).
#include "ConformanceCase.hpp"
#include "RestMeasures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace coulomb::conformance {
namespace {

constexpr std::size_t kSteps = 1000;  // docs/scene-specifications.md B2, B3: 10 s at dt = 0.01
constexpr double kStandDisplacement = 1e-3;  // [m] "stands": max_disp < 1 mm over 10 s
constexpr double kMovedDistance = 1e-3;      // [m] n_moved counts bodies this far from start at T
constexpr double kCardCollapseDrop = 0.05;   // [m] B2 collapsed: top cards 5 cm lower
constexpr double kArchCollapseDrop = 0.1;    // [m] B3 collapsed: keystone 0.1 m lower
// B3 thrust-line LP at mu 0.6 (docs/scene-specifications.md B3): admissible crown thrust and the
// abutment load W/2.
constexpr double kThrustMin = 1022.8;       // [N]
constexpr double kThrustMax = 2134.2;       // [N]
constexpr double kAbutmentLoad = 3852.378;  // [N] W/2
// docs/scene-specifications.md asks each abutment for W/2 to 1e-6, but how the weight splits
// between the two is statically indeterminate: the springers' bottom faces lie on the abutments'
// horizontal tops (x from 0.875 to 1.125 m on each side), both thrusts act at that same height and
// cancel in the moment balance, so V_R x_R = V_L x_L with x_R, x_L anywhere on those faces:
// V_R / W in [0.875, 1.125] / 2, i.e. within 12.5 % of W/2 (the solvers give 1e-6..5e-3). What is
// determinate is checked to 1e-6: the two abutments carry the whole weight, V_L + V_R = W.
constexpr double kSupportTolerance = 1e-6;     // [-] relative, V_L + V_R against W
constexpr double kAbutmentShareBound = 0.125;  // [-] relative, V_R against W/2 (statics, above)
constexpr std::size_t kAveragingSteps = 100;   // "averaged over the last second"

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0, double d = 0.0,
                   double e = 0.0, double f = 0.0, double g = 0.0) {
  char buffer[320];
  std::snprintf(buffer, sizeof buffer, pattern, a, b, c, d, e, f, g);
  return buffer;
}

std::size_t movedBodies(const engine::World& world, const DisplacementTracker& tracker) {
  std::size_t moved = 0;
  for (std::size_t i = 0; i < world.state().size(); ++i)
    if (world.state().isDynamic(i) && tracker.displacement(world, i) > kMovedDistance) ++moved;
  return moved;
}

// B2: metric max_disp when it must stand, top_drop when it must collapse.
CaseRun runCardHouse(const std::string& scene, bool mustStand, const CaseOptions& options) {
  engine::World world = buildCaseWorld(scene, options);
  const std::size_t left = world.findBody("top_left").index;
  const std::size_t right = world.findBody("top_right").index;
  const auto topHeight = [&] {
    return 0.5 * (world.state().poses[left].position.z() + world.state().poses[right].position.z());
  };
  const double topStart = topHeight();
  DisplacementTracker tracker(world);
  RunRecorder recorder;
  bool finite = true;
  const std::size_t steps = scaledSteps(kSteps, options);
  for (std::size_t k = 0; k < steps && finite; ++k) {
    recorder.step(world);
    finite = stateFinite(world);
    tracker.sample(world);
  }
  CaseRun run;
  recorder.finish(run);
  const double dispEnd = tracker.sample(world);
  const double topDrop = topStart - topHeight();
  const bool collapsed = topDrop > kCardCollapseDrop;
  run.metric = mustStand ? tracker.maxDisplacement() : topDrop;
  run.passed = finite && (mustStand ? run.metric < kStandDisplacement : collapsed);
  run.detail = format("max_disp %.3g m, max_disp_end %.3g m, top_drop %.4g m, collapsed %.0f",
                      tracker.maxDisplacement(), dispEnd, topDrop, collapsed ? 1.0 : 0.0);
  run.detail += ", n_moved " + std::to_string(movedBodies(world, tracker));
  if (!finite) run.detail += "; NON-FINITE state";
  return run;
}

// Total contact force [N] on body `slot` from the impulses of the last step (the normal points
// from A to B; the impulse p_N n + p_T1 t1 + p_T2 t2 acts on B, its opposite on A).
Eigen::Vector3d contactForceOn(const engine::World& world, std::size_t slot, double h) {
  Eigen::Vector3d impulse = Eigen::Vector3d::Zero();
  for (const geometry::ContactManifold& m : world.contacts()) {
    const double sign = m.bodyB.index == slot ? 1.0 : (m.bodyA.index == slot ? -1.0 : 0.0);
    if (sign == 0.0) continue;
    for (const geometry::ContactPoint& p : m.activePoints())
      impulse += sign * (p.normalImpulse * m.normal + p.tangentImpulse.x() * m.tangent1 +
                         p.tangentImpulse.y() * m.tangent2);
  }
  return impulse / h;
}

// B3: metric max_disp when it must stand (with thrust and abutment load), crown_drop otherwise.
CaseRun runArch(const std::string& scene, bool mustStand, const CaseOptions& options) {
  engine::World world = buildCaseWorld(scene, options);
  const std::size_t keystone = world.findBody("voussoir8").index;
  const std::size_t abutment = world.findBody("abutment_right").index;
  const std::size_t otherAbutment = world.findBody("abutment_left").index;
  const double crownStart = world.state().poses[keystone].position.z();
  DisplacementTracker tracker(world);
  RunRecorder recorder;
  bool finite = true;
  const std::size_t steps = scaledSteps(kSteps, options);
  const std::size_t averageFrom = steps > kAveragingSteps ? steps - kAveragingSteps : 0;
  Eigen::Vector3d forceSum = Eigen::Vector3d::Zero(), otherForceSum = Eigen::Vector3d::Zero();
  std::size_t forceSamples = 0;
  for (std::size_t k = 0; k < steps && finite; ++k) {
    recorder.step(world);
    finite = stateFinite(world);
    tracker.sample(world);
    if (k >= averageFrom) {
      forceSum += contactForceOn(world, abutment, world.settings().timeStep);
      otherForceSum += contactForceOn(world, otherAbutment, world.settings().timeStep);
      ++forceSamples;
    }
  }
  CaseRun run;
  recorder.finish(run);
  const Eigen::Vector3d force =
      forceSum / static_cast<double>(std::max<std::size_t>(1, forceSamples));
  const double thrust = std::abs(force.x());
  const Eigen::Vector3d otherForce =
      otherForceSum / static_cast<double>(std::max<std::size_t>(1, forceSamples));
  const double loadError = std::abs(-force.z() - kAbutmentLoad) / kAbutmentLoad;
  const double supportError =
      std::abs(-force.z() - otherForce.z() - 2.0 * kAbutmentLoad) / (2.0 * kAbutmentLoad);
  const double crownDrop = crownStart - world.state().poses[keystone].position.z();
  const bool collapsed = crownDrop > kArchCollapseDrop;
  run.metric = mustStand ? tracker.maxDisplacement() : crownDrop;
  run.passed =
      finite && (mustStand ? run.metric < kStandDisplacement && thrust >= kThrustMin &&
                                 thrust <= kThrustMax && loadError <= kAbutmentShareBound &&
                                 supportError <= kSupportTolerance
                           : collapsed);
  run.detail = format(
      "max_disp %.3g m, crown_drop %.4g m, thrust %.6g N, abutment vertical %.9g N (off W/2 by "
      "%.2g), both abutments off W by %.2g, collapsed %.0f",
      tracker.maxDisplacement(), crownDrop, thrust, -force.z(), loadError, supportError,
      collapsed ? 1.0 : 0.0);
  run.detail += ", n_moved " + std::to_string(movedBodies(world, tracker));
  if (!finite) run.detail += "; NON-FINITE state";
  return run;
}

ConformanceCase cardHouse(const std::string& mu, const std::string& tag, bool mustStand) {
  const std::string scene = "card_house_mu" + tag;
  return {"card_house/mu=" + mu,
          scene,
          "B2",
          mustStand ? "max_disp [m] (10 s)" : "top_drop [m] (10 s)",
          mustStand ? "< 1e-3 m (stands; mu_min 0.3292)" : "> 0.05 m (collapses; mu_min 0.3292)",
          [scene, mustStand](const CaseOptions& options) {
            return runCardHouse(scene, mustStand, options);
          }};
}

ConformanceCase masonryArch(const std::string& mu, const std::string& tag, bool mustStand) {
  const std::string scene = "masonry_arch_mu" + tag;
  return {
      "masonry_arch/mu=" + mu,
      scene,
      "B3",
      mustStand ? "max_disp [m] (10 s)" : "crown_drop [m] (10 s)",
      mustStand
          ? "< 1e-3 m, thrust in [1022.8, 2134.2] N, both abutments W = 7704.756 N to 1e-6, each "
            "W/2 within the statics bound 12.5 %"
          : "> 0.1 m (collapses; mu_min 0.3086)",
      [scene, mustStand](const CaseOptions& options) {
        return runArch(scene, mustStand, options);
      }};
}

}  // namespace

void addStructureCases(std::vector<ConformanceCase>& cases) {
  cases.push_back(cardHouse("0.6", "0_6", true));
  cases.push_back(cardHouse("0.2", "0_2", false));
  cases.push_back(masonryArch("0.6", "0_6", true));
  cases.push_back(masonryArch("0.2", "0_2", false));
  cases.push_back(masonryArch("0.1", "0_1", false));
}

}  // namespace coulomb::conformance
