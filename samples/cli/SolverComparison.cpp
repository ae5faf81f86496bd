#include "SolverComparison.hpp"

#include "CommaList.hpp"

#include <cstdio>
#include <sstream>

namespace coulomb::cli {

ComparisonRow comparisonRowOf(const RunMetrics& metrics, const std::string& scene,
                              const std::string& solver, int maxIterations) {
  const SolverTally all = metrics.allSolvers();
  ComparisonRow row;
  row.scene = scene;
  row.solver = solver;
  for (const auto& [name, tally] : metrics.solvers())
    row.used += (row.used.empty() ? "" : "+") + (name.empty() ? std::string("none") : name);
  row.maxIterations = maxIterations;
  row.steps = metrics.steps();
  row.msPerStep = metrics.medianStepMilliseconds();
  row.iterationsMean = all.meanIterations();
  row.iterationsMax = all.iterationsMax;
  row.residualMean = all.meanResidual();
  row.residualMax = all.residualMax;
  row.maxPenetration = metrics.maxPenetration();
  row.maxDrift = metrics.maxDrift();
  row.energyChange = metrics.finalEnergy() - metrics.initialEnergy();
  row.fallbacks = all.fallbacks;
  row.maxJointGap = metrics.maxJointGap();
  row.unconverged = all.unconverged;
  return row;
}

ComparisonRow runForComparison(const engine::io::Scene& scene, double timeCapSeconds) {
  engine::World world = buildWorldFor(scene);
  RunMetrics metrics(world);
  runSteps(world, scene.steps, scene.settings.timeStep, metrics, {}, timeCapSeconds);
  ComparisonRow row = comparisonRowOf(metrics, scene.name, scene.settings.solve.choice.text(),
                                      scene.settings.solve.options.maxIterations);
  std::ostringstream note;
  if (metrics.diverged()) note << "DIVERGED at t=" << world.time() << " s";
  if (metrics.capped())
    note << "capped: simulated " << world.time() << " of "
         << static_cast<double>(scene.steps) * scene.settings.timeStep << " s";
  row.note = note.str();
  return row;
}

std::vector<std::string> splitList(const std::string& text) {
  return samples::splitCommaList(text);
}

void printComparisonHeader(std::ostream& out) {
  char line[512];
  std::snprintf(line, sizeof line, "%-12s %10s %9s %6s %9s %9s %9s %9s %10s %9s %9s %11s  %s\n",
                "solver", "ms/step", "iter_mean", "max", "res_mean", "res_max", "max_pen_m",
                "drift_m", "dE_J", "fallbacks", "unconv", "joint_gap_m", "used / note");
  out << line << std::flush;
}

void printComparisonRow(std::ostream& out, const ComparisonRow& r) {
  char line[512];
  const std::string tail = r.used + (r.note.empty() ? "" : "; " + r.note);
  std::snprintf(line, sizeof line,
                "%-12s %10.4f %9.2f %6d %9.2e %9.2e %9.2e %9.2e %10.3e %9llu %9llu %11.2e  %s\n",
                r.solver.c_str(), r.msPerStep, r.iterationsMean, r.iterationsMax, r.residualMean,
                r.residualMax, r.maxPenetration, r.maxDrift, r.energyChange,
                static_cast<unsigned long long>(r.fallbacks),
                static_cast<unsigned long long>(r.unconverged), r.maxJointGap, tail.c_str());
  out << line << std::flush;
}

void printComparisonTable(std::ostream& out, const std::vector<ComparisonRow>& rows) {
  printComparisonHeader(out);
  for (const ComparisonRow& r : rows) printComparisonRow(out, r);
}

}  // namespace coulomb::cli
