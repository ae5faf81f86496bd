// `coulomb bench` parts on built-in scenes: scenes (each scene x solver, medians over repeats),
// sweep (iteration caps of each solver alone: the work-precision curve of a scene) and nu
// (ac_newton alone: iterations of every island solve against its nu, docs/solver-derivations.md
// (9.1), the analogue of AC11 figure 10 on our scenes).
#include <coulomb/geometry/BodyState.hpp>

#include <cmath>
#include <map>
#include <sstream>
#include <utility>

#include "BenchSuite.hpp"
#include "Commands.hpp"
#include "SceneRun.hpp"
#include "SolverComparison.hpp"
#include "bench/CorpusSolve.hpp"
#include "scenes/SceneRegistry.hpp"

namespace coulomb::cli {
namespace {

bool quick(const SuiteOptions& o) {
  return o.size == BenchSize::Quick;
}

std::vector<std::string> defaultScenes(const SuiteOptions& o) {
  if (o.scenes) return *o.scenes;
  std::vector<std::string> names{"box_stack_10", "box_stack_20", "pyramid_10"};
  if (quick(o)) return names;
  names.push_back("pyramid_20");
  for (const scenes::BuiltinScene& s : scenes::builtinScenes())  // box_pile_* variants
    if (s.name.starts_with("box_pile")) names.emplace_back(s.name);
  return names;
}

std::vector<std::string> defaultSolvers(const SuiteOptions& o) {
  return o.solvers ? *o.solvers : std::vector<std::string>{"auto", "pgs", "bgs", "ac_newton"};
}

/// Quick runs stop after 200 steps unless --steps says otherwise.
std::optional<std::uint64_t> stepsFor(const SuiteOptions& o, std::uint64_t quickSteps) {
  if (o.steps) return o.steps;
  if (quick(o)) return quickSteps;
  return std::nullopt;
}

int dynamicBodies(const engine::io::Scene& scene) {
  int n = 0;
  for (const engine::BodyDesc& b : scene.bodies) n += b.motionType == geometry::MotionType::Dynamic;
  return n;
}

BenchRecord measureScene(const std::string& part, const engine::io::Scene& scene,
                         const SuiteOptions& o, BenchProgress& progress) {
  std::vector<double> times;
  ComparisonRow row;
  for (int r = 0; r < o.repeats; ++r) {
    std::ostringstream label;
    label << scene.name << " " << scene.settings.solve.choice.text();
    if (part == "sweep") label << " max_iter " << scene.settings.solve.options.maxIterations;
    label << " repeat " << r + 1 << "/" << o.repeats;
    progress.next(label.str());
    row = runForComparison(scene, o.timeCap);  // deterministic: only the time differs
    times.push_back(row.msPerStep);
  }
  const std::string variant =
      part == "sweep" ? "max_iter=" + std::to_string(row.maxIterations) : std::string();
  return recordOf(part, row, variant, dynamicBodies(scene), o.repeats, samples::median(times));
}

/// Checks that every run builds (bad input fails before hours of running), then measures them.
void measureAll(const std::string& part, const std::vector<engine::io::Scene>& runs,
                const SuiteOptions& o, std::vector<BenchRecord>& out) {
  for (const engine::io::Scene& scene : runs) buildWorldFor(scene);
  BenchProgress progress(std::cerr, part, runs.size() * static_cast<std::size_t>(o.repeats));
  for (const engine::io::Scene& scene : runs) out.push_back(measureScene(part, scene, o, progress));
}

}  // namespace

void runScenesPart(const SuiteOptions& o, std::vector<BenchRecord>& out) {
  SceneOverrides base;
  base.steps = stepsFor(o, 200);
  std::vector<engine::io::Scene> runs;
  for (const std::string& name : defaultScenes(o))
    for (const std::string& solver : defaultSolvers(o)) {
      SceneOverrides overrides = base;
      overrides.solver = solver;
      runs.push_back(loadScene(name, overrides));
    }
  measureAll("scenes", runs, o, out);
}

void runSweepPart(const SuiteOptions& o, std::vector<BenchRecord>& out) {
  const std::vector<std::string> sceneNames =
      o.scenes ? *o.scenes
               : (quick(o) ? std::vector<std::string>{"pyramid_10"}
                           : std::vector<std::string>{"box_stack_20", "pyramid_10"});
  const std::vector<int> caps = !o.sweepIterations.empty() ? o.sweepIterations
                                : quick(o)                 ? std::vector<int>{5, 20, 100}
                                           : std::vector<int>{5, 10, 20, 50, 100, 200};
  SceneOverrides base;
  base.steps = stepsFor(o, 200);
  base.tolerance = o.sweepTolerance;  // tiny, so that every solve spends its cap
  std::vector<engine::io::Scene> runs;
  for (const std::string& name : sceneNames)
    for (const std::string& solver : defaultSolvers(o)) {
      if (solver == "auto") continue;  // the sweep is of each solver alone
      for (const int cap : caps) {
        SceneOverrides overrides = base;
        overrides.solver = solver.ends_with("!") ? solver : solver + "!";
        overrides.maxIterations = cap;
        runs.push_back(loadScene(name, overrides));
      }
    }
  measureAll("sweep", runs, o, out);
}

void runNuScenesPart(const SuiteOptions& o, std::vector<BenchRecord>& out) {
  const std::vector<std::string> sceneNames =
      o.scenes   ? *o.scenes
      : quick(o) ? std::vector<std::string>{"box_stack_20", "pyramid_10", "card_house_mu0_6"}
                 : std::vector<std::string>{"box_stack_10",
                                            "box_stack_20",
                                            "pyramid_10",
                                            "card_house_mu0_6",
                                            "masonry_arch_mu0_6",
                                            "mass_tower_heavy_on_top",
                                            "mass_ratio_1000kg_on_1kg",
                                            "box_pile_1000"};
  SceneOverrides base;
  base.steps = o.steps ? o.steps : std::optional<std::uint64_t>(quick(o) ? 50 : 200);
  base.solver = "ac_newton!";  // alone: its own iterations, no fallback
  std::vector<engine::io::Scene> runs;
  for (const std::string& name : sceneNames) runs.push_back(loadScene(name, base));
  BenchProgress progress(std::cerr, "nu", runs.size());
  for (const engine::io::Scene& scene : runs) {
    progress.next(scene.name + " ac_newton!");
    engine::World world = buildWorldFor(scene);
    RunMetrics metrics(world);
    // Island solves binned by nu = 3 n / m (to 0.01): count, iterations mean / max, residual max.
    struct Bin {
      int solves = 0, unconverged = 0;
      double iterations = 0, iterationsMax = 0, residualMax = 0;
    };
    std::map<long, Bin> bins;
    runSteps(
        world, scene.steps, scene.settings.timeStep, metrics,
        [&](const engine::StepReport& report) {
          for (const engine::IslandReport& island : report.islands) {
            if (island.contacts == 0 || island.degreesOfFreedom <= 0) continue;
            const double nu = 3.0 * static_cast<double>(island.contacts) / island.degreesOfFreedom;
            Bin& bin = bins[std::lround(nu * 100)];
            ++bin.solves;
            bin.unconverged += !island.converged();
            bin.iterations += island.solve.iterations;
            bin.iterationsMax = std::max<double>(bin.iterationsMax, island.solve.iterations);
            bin.residualMax = std::max(bin.residualMax, island.solve.residual);
          }
        },
        o.timeCap);
    for (const auto& [key, bin] : bins) {
      out.push_back(
          {.part = "nu",
           .item = scene.name,
           .solver = "ac_newton!",
           .variant = "scene",
           .size = dynamicBodies(scene),
           .repeats = bin.solves,
           .ms = BenchRecord::kNaN,
           .iterationsMean = bin.iterations / bin.solves,
           .iterationsMax = bin.iterationsMax,
           .residualMean = BenchRecord::kNaN,
           .residualMax = bin.residualMax,
           .maxDrift = BenchRecord::kNaN,
           .energyChange = BenchRecord::kNaN,
           .jointGap = BenchRecord::kNaN,
           .nu = static_cast<double>(key) / 100.0,
           .status = std::to_string(bin.solves - bin.unconverged) + "/" +
                     std::to_string(bin.solves) + " converged",
           .note = metrics.capped() ? "capped at " + std::to_string(world.time()) + " s" : ""});
    }
  }
}

}  // namespace coulomb::cli
