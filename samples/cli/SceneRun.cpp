#include "SceneRun.hpp"

#include <coulomb/engine/CoulombError.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>

#include "Commands.hpp"
#include "scenes/SceneOverrides.hpp"

namespace coulomb::cli {

engine::io::Scene loadScene(const std::string& nameOrPath, const SceneOverrides& overrides) {
  try {
    return scenes::resolveScene(nameOrPath, overrides);
  } catch (const engine::CoulombError& e) {
    throw CommandError(e.what());
  }
}

engine::World buildWorldFor(const engine::io::Scene& scene) {
  try {
    return engine::io::buildWorld(scene);
  } catch (const engine::CoulombError& e) {
    throw CommandError(std::string(e.what()) + " (scene " + scene.source + ")");
  }
}

double SolverTally::meanIterations() const {
  return islands > 0 ? static_cast<double>(iterationsSum) / static_cast<double>(islands) : 0.0;
}

double SolverTally::meanResidual() const {
  return islands > 0 ? residualSum / static_cast<double>(islands) : 0.0;
}

bool hasDiverged(const engine::World& world) {
  constexpr double kLimit = 1000.0;  // [m] and [m/s], docs/scene-specifications.md section 0
  const geometry::BodyState& s = world.state();
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!s.isDynamic(i)) continue;
    const Eigen::Vector3d& p = s.poses[i].position;
    const Eigen::Vector3d& v = s.linearVelocities[i];
    const Eigen::Vector3d& w = s.angularVelocities[i];
    if (!p.allFinite() || !v.allFinite() || !w.allFinite()) return true;
    if (p.norm() > kLimit || v.norm() > kLimit) return true;
  }
  return false;
}

RunMetrics::RunMetrics(const engine::World& world) {
  const geometry::BodyState& s = world.state();
  startPositions_.resize(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) startPositions_[i] = s.poses[i].position;
  initialEnergy_ = finalEnergy_ = world.mechanicalEnergy();
}

void RunMetrics::observe(const engine::World& world, const engine::StepReport& report,
                         double stepSeconds) {
  ++steps_;
  stepSeconds_.push_back(stepSeconds);
  for (const engine::IslandReport& island : report.islands) {
    SolverTally& tally = solvers_[island.solve.solver];
    ++tally.islands;
    tally.iterationsSum += static_cast<std::uint64_t>(std::max(0, island.solve.iterations));
    tally.iterationsMax = std::max(tally.iterationsMax, island.solve.iterations);
    if (std::isfinite(island.solve.residual)) {
      tally.residualSum += island.solve.residual;
      tally.residualMax = std::max(tally.residualMax, island.solve.residual);
    }
    tally.fallbacks += island.attempts.empty() ? 0 : island.attempts.size() - 1;
    if (!island.converged()) ++tally.unconverged;
    tally.solveSeconds += island.solve.seconds;
  }
  std::uint64_t points = 0;
  for (const geometry::ContactManifold& m : world.contacts()) {
    for (const geometry::ContactPoint& p : m.activePoints())
      maxPenetration_ = std::max(maxPenetration_, p.depth);
    points += static_cast<std::uint64_t>(m.pointCount);
  }
  maxContactPoints_ = std::max(maxContactPoints_, points);
  collisionFailures_ += report.collisionFailures.size();
  maxJointGap_ = std::max(maxJointGap_, report.joints.maxLinearError);
  maxJointAngle_ = std::max(maxJointAngle_, report.joints.maxAngularError);
  if (!report.joints.correctionConverged) ++jointCorrectionFailures_;
  const geometry::BodyState& s = world.state();
  for (std::size_t i = 0; i < s.size() && i < startPositions_.size(); ++i)
    if (s.isDynamic(i))
      maxDrift_ = std::max(maxDrift_, (s.poses[i].position - startPositions_[i]).norm());
  const double energy = world.mechanicalEnergy();
  maxEnergyIncrease_ = std::max(maxEnergyIncrease_, energy - finalEnergy_);
  finalEnergy_ = energy;
}

double RunMetrics::medianStepMilliseconds() const {
  if (stepSeconds_.empty()) return 0.0;
  const std::size_t warmUp = std::min<std::size_t>(20, stepSeconds_.size() / 10);
  std::vector<double> timed(stepSeconds_.begin() + static_cast<std::ptrdiff_t>(warmUp),
                            stepSeconds_.end());
  const auto middle = timed.begin() + static_cast<std::ptrdiff_t>(timed.size() / 2);
  std::nth_element(timed.begin(), middle, timed.end());
  double median = *middle;
  if (timed.size() % 2 == 0) median = 0.5 * (median + *std::max_element(timed.begin(), middle));
  return 1e3 * median;
}

double RunMetrics::meanStepMilliseconds() const {
  if (stepSeconds_.empty()) return 0.0;
  return 1e3 * summedStepSeconds() / static_cast<double>(stepSeconds_.size());
}

double RunMetrics::summedStepSeconds() const {
  double sum = 0.0;
  for (const double s : stepSeconds_) sum += s;
  return sum;
}

SolverTally RunMetrics::allSolvers() const {
  SolverTally all;
  for (const auto& [name, t] : solvers_) {
    all.islands += t.islands;
    all.iterationsSum += t.iterationsSum;
    all.iterationsMax = std::max(all.iterationsMax, t.iterationsMax);
    all.residualSum += t.residualSum;
    all.residualMax = std::max(all.residualMax, t.residualMax);
    all.fallbacks += t.fallbacks;
    all.unconverged += t.unconverged;
    all.solveSeconds += t.solveSeconds;
  }
  return all;
}

void runSteps(engine::World& world, std::uint64_t steps, double timeStep, RunMetrics& metrics,
              const std::function<void(const engine::StepReport&)>& afterStep,
              double timeCapSeconds) {
  double summed = 0.0;
  for (std::uint64_t n = 0; n < steps; ++n) {
    const auto start = std::chrono::steady_clock::now();
    const engine::StepReport& report = world.step(timeStep);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    summed += seconds;
    metrics.observe(world, report, seconds);
    for (const std::string& warning : report.warnings) std::cerr << "warning: " << warning << '\n';
    if (afterStep) afterStep(report);
    if (hasDiverged(world)) {
      metrics.markDiverged();
      return;
    }
    if (summed > timeCapSeconds && n + 1 < steps) {
      metrics.markCapped();
      return;
    }
  }
}

}  // namespace coulomb::cli
