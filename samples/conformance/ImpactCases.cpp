// Impact and mass-ratio cases of docs/scene-specifications.md: A7 newton_cradle (both impact laws),
// A5 mass_ratio (100kg_on_0.1kg, 1000kg_on_1kg) and B4 mass_tower (light_on_top, heavy_on_top). The
// analytic answers are copied here from docs/scene-specifications.md (tests never read the design
// folder).
#include "ConformanceCase.hpp"

#include "scenes/SceneRegistry.hpp"

#include <coulomb/engine/World.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace coulomb::conformance {
namespace {

using engine::ImpactLaw;

std::string format(const char* pattern, auto... values) {
  std::array<char, 512> text{};
  std::snprintf(text.data(), text.size(), pattern, values...);
  return text.data();
}

engine::World buildWorldWith(const std::string& scene, const CaseOptions& options, ImpactLaw law) {
  engine::io::Scene loaded = scenes::loadBuiltinScene(scene);
  loaded.settings.solve.choice = coulomb::solvers::solverChoice(options.solver);
  loaded.settings.contact.impactLaw = law;
  return engine::io::buildWorld(loaded);
}

// ---- A7 newton_cradle ----------------------------------------------------------------------

// Final x-velocities of the five balls (docs/scene-specifications.md A7 metrics v1..v5), KE ratio,
// off-axis speed.
struct CradleFigures {
  std::array<double, 5> v{};
  double energyRatio = 0.0;  // sum 1/2 m v^2 over the initial 0.5 J
  double offAxis = 0.0;      // [m/s] largest ||(v_y, v_z)||
};

CradleFigures runCradleWorld(const CaseOptions& options, ImpactLaw law, CaseRun& run) {
  engine::World world = buildWorldWith("newton_cradle", options, law);
  RunRecorder recorder;
  const std::size_t steps = scaledSteps(100, options);  // T = 1 s at dt 0.01
  for (std::size_t k = 0; k < steps; ++k) recorder.step(world);
  recorder.finish(run);
  CradleFigures f;
  double energy = 0.0;
  for (std::size_t i = 0; i < 5; ++i) {
    const Eigen::Vector3d v = world.state().linearVelocities[i];
    const Eigen::Vector3d w = world.state().angularVelocities[i];
    f.v[i] = v.x();
    f.offAxis = std::max(f.offAxis, v.tail<2>().norm());
    energy += 0.5 * v.squaredNorm() + 0.5 * 0.001 * w.squaredNorm();  // m 1 kg, I 0.001
  }
  f.energyRatio = energy / 0.5;
  return f;
}

std::string cradleDetail(const CradleFigures& f) {
  return format("v = (%.6g, %.6g, %.6g, %.6g, %.6g) m/s, KE ratio %.9f, off-axis %.2g m/s", f.v[0],
                f.v[1], f.v[2], f.v[3], f.v[4], f.energyRatio, f.offAxis);
}

// Propagating impacts: equal balls exchange velocities, (0, 0, 0, 0, 1). The metric is the share
// of the striker's momentum (1 kg m/s) the last ball leaves with.
CaseRun runCradlePropagating(const CaseOptions& options) {
  CaseRun run;
  const CradleFigures f = runCradleWorld(options, ImpactLaw::Propagating, run);
  run.metric = f.v[4];
  double kept = 0.0;  // largest share kept by balls 1-4
  for (std::size_t i = 0; i < 4; ++i) kept = std::max(kept, std::abs(f.v[i]));
  run.passed = std::isfinite(run.metric) && run.metric >= 0.99 && kept < 0.01;
  run.detail = cradleDetail(f);
  return run;
}

// One simultaneous impact over the four contacts (Newton's law on the LCP): impulses
// (1.6, 1.2, 0.8, 0.4) N s give (-0.6, 0.4, 0.4, 0.4, 0.4) (docs/scene-specifications.md A7, with a
// positive contact margin: the 2.8e-17 m gap between balls 4 and 5 is within the touching
// tolerance).
CaseRun runCradleSimultaneous(const CaseOptions& options) {
  CaseRun run;
  const CradleFigures f = runCradleWorld(options, ImpactLaw::Simultaneous, run);
  constexpr std::array<double, 5> answer{-0.6, 0.4, 0.4, 0.4, 0.4};
  double error = 0.0;
  for (std::size_t i = 0; i < 5; ++i) error = std::max(error, std::abs(f.v[i] - answer[i]));
  run.metric = error;
  run.passed = std::isfinite(error) && error < 1e-6;
  run.detail = cradleDetail(f);
  return run;
}

// ---- A5 mass_ratio and B4 mass_tower: rest and interface loads -----------------------------

// A resting column: ground (slot 0) under boxes in slots 1..n, bottom to top, each 0.2 m tall.
struct Column {
  std::string scene;
  std::size_t steps = 0;      // docs/scene-specifications.md duration at dt 0.01
  std::vector<double> loads;  // [N] analytic normal force under box i (ground first)
};

// [N s] Sum of the normal impulses of the last step between slots a and b (any order).
double interfaceImpulse(const engine::World& world, std::uint32_t a, std::uint32_t b) {
  double sum = 0.0;
  for (const geometry::ContactManifold& m : world.contacts()) {
    const bool pair =
        (m.bodyA.index == a && m.bodyB.index == b) || (m.bodyA.index == b && m.bodyB.index == a);
    if (!pair) continue;
    for (const geometry::ContactPoint& p : m.activePoints()) sum += p.normalImpulse;
  }
  return sum;
}

struct ColumnFigures {
  double maxDisplacement = 0.0;   // [m] any box, any sample (docs/scene-specifications.md max_disp)
  double maxSink = 0.0;           // [m] largest |0.2 - (z_i - z_{i-1})| (box 0: |0.1 - z_0|)
  double maxLoadError = 0.0;      // relative, any interface, any step
  std::vector<double> lastLoads;  // [N] of the last step, ground first
};

ColumnFigures runColumn(const Column& column, const CaseOptions& options, CaseRun& run) {
  engine::World world = buildCaseWorld(column.scene, options);
  const std::size_t boxes = column.loads.size();
  std::vector<Eigen::Vector3d> start(boxes + 1);
  for (std::size_t i = 1; i <= boxes; ++i) start[i] = world.state().poses[i].position;
  RunRecorder recorder;
  ColumnFigures f;
  f.lastLoads.assign(boxes, 0.0);
  const std::size_t steps = scaledSteps(column.steps, options);
  for (std::size_t k = 0; k < steps; ++k) {
    const engine::StepReport& report = recorder.step(world);
    const auto& poses = world.state().poses;
    for (std::size_t i = 1; i <= boxes; ++i) {
      f.maxDisplacement = std::max(f.maxDisplacement, (poses[i].position - start[i]).norm());
      const double below = i == 1 ? 0.0 : poses[i - 1].position.z() + 0.1;
      f.maxSink = std::max(f.maxSink, std::abs(poses[i].position.z() - 0.1 - below));
    }
    for (std::size_t i = 0; i < boxes; ++i) {
      const double load = interfaceImpulse(world, static_cast<std::uint32_t>(i),
                                           static_cast<std::uint32_t>(i + 1)) /
                          report.timeStep;
      f.lastLoads[i] = load;
      const double error = std::abs(load - column.loads[i]) / column.loads[i];
      f.maxLoadError = std::max(f.maxLoadError, std::isfinite(error) ? error : 1e300);
    }
    if (!world.state().poses[boxes].position.allFinite()) break;
  }
  recorder.finish(run);
  return f;
}

std::string columnDetail(const ColumnFigures& f) {
  std::string loads;
  for (const double load : f.lastLoads) loads += (loads.empty() ? "" : ", ") + format("%.9g", load);
  return format("max_disp %.3g m, max sink %.3g m, loads (%s) N, max load error %.3g",
                f.maxDisplacement, f.maxSink, loads.c_str(), f.maxLoadError);
}

// A5: the light box must not be squeezed out; goal sink < 1e-6 m. Metric: the largest sink or
// displacement of either box; the loads are checked to 1e-6 (relative) as well.
CaseRun runMassRatio(const Column& column, const CaseOptions& options) {
  CaseRun run;
  const ColumnFigures f = runColumn(column, options, run);
  run.metric = std::max(f.maxSink, f.maxDisplacement);
  run.passed = std::isfinite(run.metric) && run.metric < 1e-6 && f.maxLoadError < 1e-6;
  run.detail = columnDetail(f);
  return run;
}

// B4: no box moves more than 1 mm in 10 s; per-step normal impulses within 1e-6 (relative).
CaseRun runMassTower(const Column& column, const CaseOptions& options) {
  CaseRun run;
  const ColumnFigures f = runColumn(column, options, run);
  run.metric = f.maxDisplacement;
  run.passed = std::isfinite(run.metric) && run.metric < 1e-3 && f.maxLoadError < 1e-6;
  run.detail = columnDetail(f);
  return run;
}

}  // namespace

void addImpactCases(std::vector<ConformanceCase>& cases) {
  // docs/scene-specifications.md A5: normal forces 981.981 N (ground) and 981.0 N (interface); for
  // 1000 kg on 1 kg the same statics give (1000 + 1) g = 9819.81 N and 1000 g = 9810 N.
  const Column ratio100{"mass_ratio_100kg_on_0_1kg", 500, {981.981, 981.0}};
  const Column ratio1000{"mass_ratio_1000kg_on_1kg", 500, {9819.81, 9810.0}};
  // docs/scene-specifications.md B4 (ground, 1|2, 2|3, 3|4).
  const Column light{"mass_tower_light_on_top", 1000, {10898.91, 1088.91, 107.91, 9.81}};
  const Column heavy{"mass_tower_heavy_on_top", 1000, {10898.91, 10889.10, 10791.00, 9810.00}};
  const std::string ratioCriterion = "sink and drift < 1e-6 m, loads within 1e-6";
  const std::string towerCriterion = "max_disp < 1 mm, per-step loads within 1e-6";

  cases.push_back({"newton_cradle", "newton_cradle", "A7", "last ball's momentum share",
                   ">= 0.99, balls 1-4 < 0.01 (propagating law)", runCradlePropagating});
  cases.push_back({"newton_cradle/simultaneous", "newton_cradle", "A7",
                   "|v - (-0.6, 0.4, 0.4, 0.4, 0.4)| [m/s]", "< 1e-6 (simultaneous law)",
                   runCradleSimultaneous});
  cases.push_back({"mass_ratio/100kg_on_0.1kg", ratio100.scene, "A5", "sink/drift [m]",
                   ratioCriterion,
                   [ratio100](const CaseOptions& o) { return runMassRatio(ratio100, o); }});
  cases.push_back({"mass_ratio/1000kg_on_1kg", ratio1000.scene, "A5", "sink/drift [m]",
                   ratioCriterion,
                   [ratio1000](const CaseOptions& o) { return runMassRatio(ratio1000, o); }});
  cases.push_back({"mass_tower/light_on_top", light.scene, "B4", "max_disp [m]", towerCriterion,
                   [light](const CaseOptions& o) { return runMassTower(light, o); }});
  cases.push_back({"mass_tower/heavy_on_top", heavy.scene, "B4", "max_disp [m]", towerCriterion,
                   [heavy](const CaseOptions& o) { return runMassTower(heavy, o); }});
}

}  // namespace coulomb::conformance
