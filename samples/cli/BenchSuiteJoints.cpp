// `coulomb bench` parts on joints: joints (the docs/scene-specifications.md A6 ball chain of 10,
// 50, 200 links per solver and stabilization policy: ms/step, joint gap, energy change) and aba
// (ABA on serial snakes of growing length: time per call, |M qdd + h - tau|).
#include <coulomb/joints/tree/TreeDynamics.hpp>

#include <array>
#include <chrono>
#include <iostream>

#include "BenchSuite.hpp"
#include "SceneRun.hpp"
#include "SolverComparison.hpp"
#include "bench/AbaChain.hpp"
#include "bench/CorpusSolve.hpp"
#include "bench/JointChain.hpp"

namespace coulomb::cli {

double benchNow() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void runJointsPart(const SuiteOptions& o, std::vector<BenchRecord>& out) {
  const bool quick = o.size == BenchSize::Quick;
  const std::vector<int> lengths = quick ? std::vector<int>{10, 50} : std::vector<int>{10, 50, 200};
  const std::vector<std::string> solverNames =
      o.solvers ? *o.solvers : std::vector<std::string>{"pgs!", "bgs!", "ac_newton!"};
  constexpr std::array<joints::StabilizationMethod, 2> kPolicies = {
      joints::StabilizationMethod::PredictedState, joints::StabilizationMethod::Baumgarte};
  const double h = 0.01;  // docs/scene-specifications.md A6
  const std::uint64_t steps = o.steps ? *o.steps : (quick ? 100 : 1000);
  BenchProgress progress(
      std::cerr, "joints",
      lengths.size() * solverNames.size() * kPolicies.size() * static_cast<std::size_t>(o.repeats));
  for (const int links : lengths)
    for (const std::string& solver : solverNames)
      for (const joints::StabilizationMethod policy : kPolicies) {
        const std::string name = "chain_" + std::to_string(links);
        std::vector<double> times;
        ComparisonRow row;
        for (int r = 0; r < o.repeats; ++r) {
          progress.next(name + " " + solver + " " + joints::stabilizationMethodName(policy) +
                        " repeat " + std::to_string(r + 1) + "/" + std::to_string(o.repeats));
          samples::BallChain chain = samples::buildBallChain(links, h, solver, policy);
          RunMetrics metrics(chain.world);
          runSteps(chain.world, steps, h, metrics, {}, o.timeCap);
          row = comparisonRowOf(metrics, name, solver, 0);  // deterministic: only times differ
          times.push_back(row.msPerStep);
          if (metrics.capped())
            row.note = "capped: simulated " + std::to_string(chain.world.time()) + " s";
        }
        row.energyChange /=
            samples::chainReleasedEnergy(links);  // docs/scene-specifications.md A6: per S
        BenchRecord rec = recordOf("joints", row, joints::stabilizationMethodName(policy), links,
                                   o.repeats, samples::median(times));
        rec.maxDrift = BenchRecord::kNaN;  // a falling chain: its displacement is no drift
        out.push_back(rec);
      }
}

void runAbaPart(const SuiteOptions& o, std::vector<BenchRecord>& out) {
  const std::vector<int> lengths = o.size == BenchSize::Quick
                                       ? std::vector<int>{10, 100, 1000}
                                       : std::vector<int>{10, 30, 100, 300, 1000};
  BenchProgress progress(std::cerr, "aba", lengths.size());
  for (const int links : lengths) {
    progress.next("serial chain " + std::to_string(links) + " links");
    const joints::tree::Articulation tree = samples::serialChain(links);
    const Eigen::VectorXd q = samples::wave(tree.nq(), 0.1), qd = samples::wave(tree.nv(), 0.2),
                          tau = samples::wave(tree.nv(), 0.3);
    const int calls = std::max(1, 20000 / links);  // ~20 000 link visits per timing
    std::vector<double> times;
    double sink = 0.0;
    for (int r = 0; r < std::max(o.repeats, 3); ++r) {
      const double start = benchNow();
      for (int k = 0; k < calls; ++k) sink += joints::tree::forwardDynamics(tree, q, qd, tau)(0);
      times.push_back((benchNow() - start) * 1e3 / calls);
    }
    const double residual = samples::abaResidual(tree);
    constexpr double kNaN = BenchRecord::kNaN;
    out.push_back({.part = "aba",
                   .item = "serial_chain_" + std::to_string(links),
                   .solver = "",
                   .variant = std::to_string(calls) + " calls per timing",
                   .size = links,
                   .repeats = static_cast<int>(times.size()),
                   .ms = samples::median(times),
                   .iterationsMean = kNaN,
                   .iterationsMax = kNaN,
                   .residualMean = residual,
                   .residualMax = residual,
                   .maxDrift = kNaN,
                   .energyChange = kNaN,
                   .jointGap = kNaN,
                   .nu = kNaN,
                   .status = std::isfinite(sink) ? "ok" : "non-finite",  // keeps the calls
                   .note = ""});
  }
}

}  // namespace coulomb::cli
