#pragma once
// One scene run once per solver, reduced to one row of figures: what `coulomb compare` prints
// and `coulomb bench` repeats. Definitions (docs/benchmarks.md "What the columns mean"):
//   ms/step      median World::step time after min(20, steps/10) warm-up steps
//   (docs/scene-specifications.md s. 0) iterations   of the answer applied to each island (mean,
//   max over island solves) residual     common relative residual e_rel of that answer (mean, max
//   over island solves) penetration  largest manifold depth over the run [m] drift        largest
//   |p(t) - p(0)| of any dynamic body's COM over the run [m]: for a scene
//                that should rest, how far it did not
//   energy       E(T) - E(0), E = kinetic + gravitational potential of the dynamic bodies [J]
//   fallbacks    extra solver attempts over the run (the plan's fallbacks)
//   joint_gap    largest joint anchor gap / slider offset after any step [m] (0 without joints)
#include <cstdint>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "SceneRun.hpp"

namespace coulomb::cli {

struct ComparisonRow {
  std::string scene;
  std::string solver;  // as requested ("auto", "pgs", "pgs!", ...)
  std::string used;    // solvers whose answers were applied, "+"-separated
  int maxIterations = 0;
  std::uint64_t steps = 0;
  double msPerStep = 0.0;
  double iterationsMean = 0.0;
  int iterationsMax = 0;
  double residualMean = 0.0;
  double residualMax = 0.0;
  double maxPenetration = 0.0;
  double maxDrift = 0.0;
  double energyChange = 0.0;
  std::uint64_t fallbacks = 0;
  double maxJointGap = 0.0;
  std::uint64_t unconverged = 0;  // island solves whose applied answer did not converge
  std::string note;               // "diverged at t=..", "capped: simulated X of Y s"
};

/// Runs `scene` (already loaded, with its overrides) to the end or the time cap.
ComparisonRow runForComparison(const engine::io::Scene& scene,
                               double timeCapSeconds = std::numeric_limits<double>::infinity());

/// The figures of a finished run (no note): what runForComparison reports, for runs built
/// without a scene (the bench suite's chains).
ComparisonRow comparisonRowOf(const RunMetrics& metrics, const std::string& scene,
                              const std::string& solver, int maxIterations);

/// "a,b,c" -> {"a", "b", "c"}; empty items are dropped.
std::vector<std::string> splitList(const std::string& text);

/// A fixed-width table: the header line, then one line per row (flushed, so rows appear as
/// their runs end).
void printComparisonHeader(std::ostream& out);
void printComparisonRow(std::ostream& out, const ComparisonRow& row);
void printComparisonTable(std::ostream& out, const std::vector<ComparisonRow>& rows);

}  // namespace coulomb::cli
