#pragma once
// One conformance case of docs/scene-specifications.md (issue 8): a built-in scene, a metric and
// its pass criterion, runnable with any solver. The tests (tests/conformance), `coulomb
// conformance` and the table of docs/conformance.md all run the same ConformanceCase, so the
// documented figures are the tested ones.
#include <coulomb/engine/StepReport.hpp>
#include <coulomb/engine/World.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace coulomb::conformance {

struct CaseOptions {
  std::string solver = "auto";  // WorldSettings::solver for every island ("auto", "pgs", ...)
  double horizonScale =
      1.0;  // fraction of the docs/scene-specifications.md duration to run (tests under sanitizers)
};

/// The outcome of one case with one solver.
struct CaseRun {
  bool passed = false;
  double metric = std::numeric_limits<double>::quiet_NaN();  // the case's primary metric
  std::string detail;           // one line: the figures behind the verdict
  std::size_t steps = 0;        // World::step calls
  double msPerStep = 0.0;       // [ms] mean wall clock of World::step
  double maxResidual = 0.0;     // common relative residual, max over islands and steps
  double meanIterations = 0.0;  // solver iterations per island solve
  int maxIterations = 0;
  std::size_t fallbacks = 0;  // fallback attempts over the run
  // World::stateHash after the last step (of the last world the case stepped): equal across
  // identical runs, whatever front end ran them (the CLI, the tests, Python).
  std::uint64_t stateHash = 0;
};

struct ConformanceCase {
  std::string name;        // "sphere_slide", "box_incline/C_flat_22.5deg", ...
  std::string scene;       // built-in scene it runs (samples/scenes/<scene>.json)
  std::string section;     // docs/scene-specifications.md section, e.g. "A1"
  std::string metricName;  // e.g. "direction error [deg]"
  std::string criterion;   // pass criterion in words, e.g. "< 0.1 deg"
  std::function<CaseRun(const CaseOptions&)> run;
};

/// Accumulates the solver figures of a run from each StepReport (time, residual, iterations).
class RunRecorder {
 public:
  /// Steps `world` once, timing it, and records its report. Returns the report.
  const engine::StepReport& step(engine::World& world);
  /// Copies the accumulated figures into `run` (steps, msPerStep, residual, iterations, fallbacks).
  void finish(CaseRun& run) const;

 private:
  std::size_t steps_ = 0;
  double seconds_ = 0.0;
  double maxResidual_ = 0.0;
  double iterationSum_ = 0.0;
  std::size_t solves_ = 0;
  int maxIterations_ = 0;
  std::size_t fallbacks_ = 0;
  std::uint64_t stateHash_ = 0;
  engine::StepReport last_;
};

/// Loads built-in `scene` and sets the solver of `options` for every island.
engine::World buildCaseWorld(const std::string& scene, const CaseOptions& options);

/// Steps in a horizon of `steps` scaled by options.horizonScale (at least 1).
std::size_t scaledSteps(std::size_t steps, const CaseOptions& options);

/// Every case, in docs/scene-specifications.md order. Each group lives in its own file
/// (Friction*.cpp, ...).
const std::vector<ConformanceCase>& allCases();
/// The case called `name`; throws CoulombError listing the names if there is none.
const ConformanceCase& findCase(const std::string& name);

/// The solvers every case is run with for docs/conformance.md (issue 8 item 4): auto, then each
/// solver alone ("pgs!", ...: no fallback).
const std::vector<std::string>& tableSolvers();

// Case groups, one per file; each appends its cases. Add yours here and in ConformanceCase.cpp.
void addFrictionCases(std::vector<ConformanceCase>& cases);   // FrictionCases.cpp
void addImpactCases(std::vector<ConformanceCase>& cases);     // ImpactCases.cpp
void addStructureCases(std::vector<ConformanceCase>& cases);  // StructureCases.cpp
void addLoopCases(std::vector<ConformanceCase>& cases);       // LoopCases.cpp
void addStabilityCases(std::vector<ConformanceCase>& cases);  // StabilityCases.cpp

}  // namespace coulomb::conformance
