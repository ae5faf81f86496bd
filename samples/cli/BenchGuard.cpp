#include "BenchGuard.hpp"

#include <coulomb/solvers/SolverRegistry.hpp>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include "Commands.hpp"
#include "SceneRun.hpp"
#include "SolverComparison.hpp"
#include "bench/CorpusSolve.hpp"
#include "conformance/ConformanceCase.hpp"

namespace coulomb::cli {
namespace {

using Json = nlohmann::json;

/// The metrics of one run, by name; runs are cached so that several entries share one.
using Metrics = std::map<std::string, double>;

Metrics runScene(const Json& e, const std::string& at) {
  SceneOverrides overrides;
  overrides.solver = e.at("solver").get<std::string>();
  if (e.contains("steps")) overrides.steps = e.at("steps").get<std::uint64_t>();
  const ComparisonRow row =
      runForComparison(loadScene(e.at("scene").get<std::string>(), overrides));
  if (!row.note.empty()) throw CommandError(at + ": the run did not finish: " + row.note);
  return {{"residual_max", row.residualMax},
          {"max_drift", row.maxDrift},
          {"max_penetration", row.maxPenetration},
          {"abs_energy_change", std::abs(row.energyChange)},
          {"joint_gap", row.maxJointGap}};
}

Metrics runCase(const Json& e) {
  conformance::CaseOptions options;
  options.solver = e.at("solver").get<std::string>();
  options.horizonScale = e.value("scale", 1.0);
  const conformance::CaseRun run =
      conformance::findCase(e.at("case").get<std::string>()).run(options);
  return {{"abs_metric", std::abs(run.metric)}, {"residual_max", run.maxResidual}};
}

Metrics runFc3d(const Json& e, const std::string& corpus, const std::string& at) {
  if (corpus.empty()) throw CommandError(at + ": an fc3d entry needs --corpus DIR");
  const std::filesystem::path path =
      std::filesystem::path(corpus) / (e.at("problem").get<std::string>() + ".fc3d");
  solvers::SolverOptions options;  // no time limit: the result must not depend on the machine
  options.tolerance = e.value("tolerance", 1e-8);
  options.maxIterations = e.value("max_iterations", 0);
  const solvers::SolveOutcome solved =
      samples::solveOnce(samples::readCorpusProblem(path), e.at("solver").get<std::string>(),
                         options, solvers::SolverRegistry::builtIn());
  return {{"residual", solved.report.residual}};
}

}  // namespace

void runBenchGuard(const std::string& thresholdFile, const std::string& corpus, bool update) {
  std::ifstream in(thresholdFile);
  if (!in) throw CommandError("--guard: cannot read '" + thresholdFile + "'");
  Json file;
  try {
    file = Json::parse(in);
  } catch (const Json::exception& e) {
    throw CommandError(thresholdFile + ": not JSON: " + e.what());
  }
  if (!file.contains("entries") || !file["entries"].is_array())
    throw CommandError(thresholdFile + ": no \"entries\" array");
  const auto start = std::chrono::steady_clock::now();
  std::map<std::string, Metrics> cache;
  std::string failures;
  int index = 0;
  for (Json& e : file["entries"]) {
    const std::string at = thresholdFile + ": entries[" + std::to_string(index++) + "]";
    try {
      const std::string kind = e.at("kind").get<std::string>();
      Json key = e;
      for (const char* own : {"metric", "measured", "margin", "floor", "why"}) key.erase(own);
      Metrics& metrics = cache[key.dump()];
      if (metrics.empty()) {
        if (kind == "scene")
          metrics = runScene(e, at);
        else if (kind == "case")
          metrics = runCase(e);
        else if (kind == "fc3d")
          metrics = runFc3d(e, corpus, at);
        else
          throw CommandError(at + ": kind '" + kind + "' is none of scene, case, fc3d");
      }
      const std::string metric = e.at("metric").get<std::string>();
      if (!metrics.count(metric))
        throw CommandError(at + ": no metric '" + metric + "' for " + kind);
      const double value = metrics.at(metric);
      const double measured = e.at("measured").get<double>();
      const double limit = std::max(measured * e.at("margin").get<double>(), e.value("floor", 0.0));
      const bool ok = std::isfinite(value) && value <= limit;
      const std::string what = e.value("scene", e.value("case", e.value("problem", std::string())));
      char line[256];
      std::snprintf(line, sizeof line, "%-5s %-30.30s %-11s %-18s %11.4g  limit %11.4g\n",
                    ok ? "ok" : "WORSE", what.c_str(), e.at("solver").get<std::string>().c_str(),
                    metric.c_str(), value, limit);
      std::cout << line << std::flush;
      if (!ok) failures += "\n  " + at + " (" + what + " " + metric + "): " + line;
      if (update) e["measured"] = value;
    } catch (const Json::exception& ex) {
      throw CommandError(at + ": " + ex.what());
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "guard: " << index << " entries in " << std::lround(seconds * 10) / 10.0 << " s\n";
  if (update) {
    std::ofstream out(thresholdFile);
    out << file.dump(2) << "\n";
    if (!out) throw CommandError("--guard-update: writing '" + thresholdFile + "' failed");
    std::cout << "guard: measured values written to " << thresholdFile << "\n";
    return;
  }
  if (!failures.empty()) throw CommandError("guard: error metrics got worse:" + failures);
}

}  // namespace coulomb::cli
