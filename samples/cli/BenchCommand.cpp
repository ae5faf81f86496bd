// `coulomb bench`: ms/step with the common residual per scene and solver (medians over repeats),
// and a speed-vs-residual sweep (iteration caps 5...200) of pgs, bgs and ac_newton on the 55-box
// pyramid; CSV and Markdown (docs/benchmarks.md is made from its output); progress on stderr.
#include <algorithm>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "Commands.hpp"
#include "RunOutputs.hpp"
#include "SceneRun.hpp"
#include "SolverComparison.hpp"

namespace coulomb::cli {
namespace {

struct BenchOptions {
  std::string scenes = "box_stack_20,pyramid_10,pyramid_20,box_pile_1000";
  std::string solvers = "auto,pgs,bgs,ac_newton";
  int repeats = 3;
  std::optional<std::uint64_t> steps;
  double timeCap = 10.0;
  std::string sweepScene = "pyramid_10";
  std::string sweepSolvers = "pgs!,bgs!,ac_newton!";
  std::string sweepIterations = "5,10,20,50,100,200";
  double sweepTolerance = 1e-12;
  bool noSweep = false;
  std::string csvPath;
  std::string markdownPath;
};

struct BenchRow {
  std::string kind;  // "scene" or "sweep"
  int repeats = 0;
  ComparisonRow figures;  // msPerStep = median over the repeats
};

BenchRow measure(const std::string& kind, const engine::io::Scene& scene, int repeats,
                 double timeCap) {
  std::vector<ComparisonRow> runs;
  for (int r = 0; r < repeats; ++r) {
    std::cerr << "  " << kind << " " << scene.name << " " << scene.settings.solver;
    if (kind == "sweep") std::cerr << " max_iter " << scene.settings.solverOptions.maxIterations;
    std::cerr << " repeat " << r + 1 << "/" << repeats << std::flush;
    runs.push_back(runForComparison(scene, timeCap));
    std::cerr << ": " << runs.back().msPerStep << " ms/step\n";
  }
  std::vector<double> times;
  for (const ComparisonRow& run : runs) times.push_back(run.msPerStep);
  std::sort(times.begin(), times.end());
  const std::size_t n = times.size();
  BenchRow row{kind, repeats, runs.front()};  // the runs are deterministic: same figures
  row.figures.msPerStep = n % 2 == 1 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]);
  return row;
}

void writeCsv(const std::string& path, const std::vector<BenchRow>& rows) {
  std::ofstream out = openOutputFile(path, "results");
  out << std::setprecision(6)
      << "kind,scene,solver,used,max_iterations,repeats,steps,ms_per_step,iterations_mean,"
         "iterations_max,residual_mean,residual_max,max_penetration,max_drift,energy_change,"
         "fallbacks,unconverged,note\n";
  for (const BenchRow& b : rows) {
    const ComparisonRow& r = b.figures;
    out << b.kind << ',' << r.scene << ',' << r.solver << ',' << r.used << ',' << r.maxIterations
        << ',' << b.repeats << ',' << r.steps << ',' << r.msPerStep << ',' << r.iterationsMean
        << ',' << r.iterationsMax << ',' << r.residualMean << ',' << r.residualMax << ','
        << r.maxPenetration << ',' << r.maxDrift << ',' << r.energyChange << ',' << r.fallbacks
        << ',' << r.unconverged << ',' << r.note << '\n';
  }
  if (!out) throw CommandError("writing '" + path + "' failed");
}

void writeMarkdown(const std::string& path, const std::vector<BenchRow>& rows) {
  std::ofstream out = openOutputFile(path, "Markdown");
  out << std::setprecision(3);
  out << "| scene | solver | ms/step | iterations mean / max | residual mean / max | "
         "max drift (m) | max penetration (m) | energy change (J) | fallbacks | note |\n"
      << "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const BenchRow& b : rows) {
    if (b.kind != "scene") continue;
    const ComparisonRow& r = b.figures;
    out << "| " << r.scene << " | " << r.solver << (r.used != r.solver ? " (" + r.used + ")" : "")
        << " | " << r.msPerStep << " | " << r.iterationsMean << " / " << r.iterationsMax << " | "
        << r.residualMean << " / " << r.residualMax << " | " << r.maxDrift << " | "
        << r.maxPenetration << " | " << r.energyChange << " | " << r.fallbacks << " | " << r.note
        << " |\n";
  }
  bool sweepHeader = false;
  for (const BenchRow& b : rows) {
    if (b.kind != "sweep") continue;
    const ComparisonRow& r = b.figures;
    if (!sweepHeader) {
      out << "\n| scene | solver | max iterations | ms/step | residual mean / max | max drift (m) "
             "| note |\n|---|---|---|---|---|---|---|\n";
      sweepHeader = true;
    }
    out << "| " << r.scene << " | " << r.solver << " | " << r.maxIterations << " | " << r.msPerStep
        << " | " << r.residualMean << " / " << r.residualMax << " | " << r.maxDrift << " | "
        << r.note << " |\n";
  }
  if (!out) throw CommandError("writing '" + path + "' failed");
}

std::vector<int> parseIterations(const std::string& text) {
  std::vector<int> caps;
  for (const std::string& item : splitList(text)) {
    std::size_t used = 0;
    int value = 0;
    try {
      value = std::stoi(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || value <= 0)
      throw CommandError("--sweep-iterations: '" + item + "' is not a positive integer");
    caps.push_back(value);
  }
  return caps;
}

void bench(const BenchOptions& o) {
  if (o.repeats < 1) throw CommandError("--repeats must be >= 1");
  SceneOverrides base;
  base.steps = o.steps;
  // Every scene and solver is loaded and built first: a bad name fails before hours of running.
  std::vector<engine::io::Scene> sceneRuns;
  for (const std::string& sceneName : splitList(o.scenes))
    for (const std::string& solver : splitList(o.solvers)) {
      SceneOverrides overrides = base;
      overrides.solver = solver;
      sceneRuns.push_back(loadScene(sceneName, overrides));
      buildWorldFor(sceneRuns.back());
    }
  std::vector<engine::io::Scene> sweepRuns;
  if (!o.noSweep)
    for (const std::string& solver : splitList(o.sweepSolvers))
      for (const int cap : parseIterations(o.sweepIterations)) {
        SceneOverrides overrides = base;
        overrides.solver = solver;
        overrides.maxIterations = cap;
        overrides.tolerance = o.sweepTolerance;
        sweepRuns.push_back(loadScene(o.sweepScene, overrides));
        if (cap == parseIterations(o.sweepIterations).front()) buildWorldFor(sweepRuns.back());
      }
  std::vector<BenchRow> rows;
  for (const engine::io::Scene& scene : sceneRuns)
    rows.push_back(measure("scene", scene, o.repeats, o.timeCap));
  for (const engine::io::Scene& scene : sweepRuns)
    rows.push_back(measure("sweep", scene, o.repeats, o.timeCap));

  std::vector<ComparisonRow> table;
  for (const BenchRow& b : rows) table.push_back(b.figures);
  printComparisonTable(std::cout, table);
  if (!o.csvPath.empty()) writeCsv(o.csvPath, rows);
  if (!o.markdownPath.empty()) writeMarkdown(o.markdownPath, rows);
}

}  // namespace

void registerBenchCommand(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* command = app.add_subcommand(
      "bench",
      "Per scene and solver: ms/step (median over repeats) with the common residual; then a "
      "speed-vs-residual sweep over iteration caps. Progress on stderr");
  command->add_option("--scenes", o->scenes, "Comma-separated scenes")->capture_default_str();
  command->add_option("--solvers", o->solvers, "Comma-separated solvers")->capture_default_str();
  command->add_option("--repeats", o->repeats, "Runs per row; ms/step is their median")
      ->capture_default_str();
  command->add_option("--steps", o->steps, "Steps per run (default: each scene's)");
  command
      ->add_option("--time-cap", o->timeCap,
                   "Stop a run when its summed step time exceeds this [s] (SCENES.md section 0)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command->add_option("--sweep-scene", o->sweepScene, "Scene of the sweep")->capture_default_str();
  command->add_option("--sweep-solvers", o->sweepSolvers, "Solvers of the sweep (NAME! = alone)")
      ->capture_default_str();
  command->add_option("--sweep-iterations", o->sweepIterations, "Iteration caps of the sweep")
      ->capture_default_str();
  command
      ->add_option("--sweep-tol", o->sweepTolerance,
                   "Tolerance in the sweep (tiny, so that each solve spends its cap)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command->add_flag("--no-sweep", o->noSweep, "Skip the sweep");
  command->add_option("--out", o->csvPath, "Write the rows as CSV");
  command->add_option("--markdown", o->markdownPath, "Write the rows as Markdown tables");
  command->callback([o] { bench(*o); });
}

}  // namespace coulomb::cli
