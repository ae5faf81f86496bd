#pragma once
// One timed run of a scene, shared by `coulomb run`, `coulomb compare` and `coulomb bench`:
// the scene with the command line's overrides, the World built from it, and the measurements
// every command reports (RunMetrics below). Timing follows docs/scene-specifications.md section 0:
// each World::step is timed alone (steady clock, metric code excluded) and ms/step is the median
// after min(20, steps/10) warm-up steps.
#include <coulomb/engine/StepReport.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/io/SceneLoader.hpp>

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "scenes/SceneOverrides.hpp"

namespace coulomb::cli {

using SceneOverrides = scenes::SceneOverrides;  // samples/scenes/SceneOverrides.hpp

/// The scene `nameOrPath` (built-in name or JSON file) with the overrides applied. A solver
/// override replaces the world's solver and clears every body's own `solver`, so that every
/// island uses it. Throws CommandError naming the scene, the option and the problem.
engine::io::Scene loadScene(const std::string& nameOrPath, const SceneOverrides& overrides);

/// buildWorld with CoulombError turned into CommandError.
engine::World buildWorldFor(const engine::io::Scene& scene);

/// Per-solver tally of island solves, keyed by the solver whose answer was applied.
struct SolverTally {
  std::uint64_t islands = 0;
  std::uint64_t iterationsSum = 0;
  int iterationsMax = 0;
  double residualSum = 0.0;
  double residualMax = 0.0;
  std::uint64_t fallbacks = 0;    // extra attempts in islands this solver answered
  std::uint64_t unconverged = 0;  // islands whose applied answer did not converge
  double solveSeconds = 0.0;      // summed wall clock of the applied attempts

  [[nodiscard]] double meanIterations() const;
  [[nodiscard]] double meanResidual() const;
};

/// The measurements of a run. observe() is called after building (step report absent) and after
/// every step; nothing in it is timed.
class RunMetrics {
 public:
  explicit RunMetrics(const engine::World& world);

  void observe(const engine::World& world, const engine::StepReport& report, double stepSeconds);

  [[nodiscard]] double medianStepMilliseconds()
      const;  // docs/scene-specifications.md section 0 rule
  [[nodiscard]] double meanStepMilliseconds() const;
  [[nodiscard]] const std::map<std::string, SolverTally>& solvers() const { return solvers_; }
  [[nodiscard]] SolverTally allSolvers() const;  // the tallies merged
  /// Largest penetration depth of any manifold point over the run [m] (depths of the collision
  /// stage of each step, i.e. at the start-of-step poses; 0 if nothing ever overlapped).
  [[nodiscard]] double maxPenetration() const { return maxPenetration_; }
  /// Largest displacement |p(t) - p(0)| of any dynamic body's COM over the samples [m]: in a
  /// scene that should rest this is the drift (it includes start-up sag).
  [[nodiscard]] double maxDrift() const { return maxDrift_; }
  [[nodiscard]] double initialEnergy() const { return initialEnergy_; }
  [[nodiscard]] double finalEnergy() const { return finalEnergy_; }
  /// Largest increase of the mechanical energy from one step to the next [J] (0 if it never grew).
  [[nodiscard]] double maxEnergyIncrease() const { return maxEnergyIncrease_; }
  /// Largest joint anchor gap / slider offset after any step [m] and largest axis misalignment
  /// [~rad] (StepReport::joints): the joint drift of the run; 0 without joints.
  [[nodiscard]] double maxJointGap() const { return maxJointGap_; }
  [[nodiscard]] double maxJointAngle() const { return maxJointAngle_; }
  /// Steps whose predicted-state correction stopped above its tolerance.
  [[nodiscard]] std::uint64_t jointCorrectionFailures() const { return jointCorrectionFailures_; }
  [[nodiscard]] std::uint64_t steps() const { return steps_; }
  [[nodiscard]] std::uint64_t maxContactPoints() const { return maxContactPoints_; }
  [[nodiscard]] std::uint64_t collisionFailures() const { return collisionFailures_; }
  [[nodiscard]] bool diverged() const { return diverged_; }
  void markDiverged() { diverged_ = true; }
  [[nodiscard]] bool capped() const { return capped_; }
  void markCapped() { capped_ = true; }
  [[nodiscard]] double summedStepSeconds() const;

 private:
  std::vector<Eigen::Vector3d> startPositions_;  // per slot (dynamic bodies)
  std::vector<double> stepSeconds_;
  std::map<std::string, SolverTally> solvers_;
  double maxPenetration_ = 0.0;
  double maxDrift_ = 0.0;
  double initialEnergy_ = 0.0;
  double finalEnergy_ = 0.0;
  double maxEnergyIncrease_ = 0.0;
  double maxJointGap_ = 0.0;
  double maxJointAngle_ = 0.0;
  std::uint64_t jointCorrectionFailures_ = 0;
  std::uint64_t steps_ = 0;
  std::uint64_t maxContactPoints_ = 0;
  std::uint64_t collisionFailures_ = 0;
  bool diverged_ = false;
  bool capped_ = false;
};

/// Steps `world` `steps` times, timing each World::step alone; calls `afterStep` (untimed) after
/// every step. Stops early when the state diverges (docs/scene-specifications.md section 0:
/// non-finite, |x| > 1000 m, |v| > 1000 m/s); RunMetrics::diverged() then says so. Also stops when
/// the summed step time exceeds `timeCapSeconds` (docs/scene-specifications.md section 0 time cap);
/// RunMetrics::capped() then says so.
void runSteps(engine::World& world, std::uint64_t steps, double timeStep, RunMetrics& metrics,
              const std::function<void(const engine::StepReport&)>& afterStep = {},
              double timeCapSeconds = std::numeric_limits<double>::infinity());

/// True if some dynamic body is non-finite or beyond 1000 m or 1000 m/s
/// (docs/scene-specifications.md section 0).
bool hasDiverged(const engine::World& world);

}  // namespace coulomb::cli
