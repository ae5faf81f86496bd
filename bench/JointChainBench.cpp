// Maximal-coordinate chains (docs/conformance.md A6: capsule links 0.1 m, 0.1 kg, ball joints,
// released horizontal): ms per step and joint error for 50 and 200 links, per solver and per
// stabilization policy, at dt 0.01 and 0.002. One benchmark iteration = one step; a run is
// exactly 10 s of simulated time, so the counters are the docs/conformance.md A6 metrics:
//   max_gap     largest anchor separation over all steps and joints [m]
//   drift_end   (E(T) - E0) / S, S = m g L N^2 / 2 (the energy released when hanging straight)
//   drift_max, drift_min   largest and smallest (E(t) - E0) / S over the run
//   corr_iters  mean predicted-state correction solves per step
// The third and fourth policies are predicted_state with the energy projection
// (PredictedStateSettings::energy = modified, and exact: the symmetric step with E kept).
// docs/tuning.md quotes the figures.
#include <benchmark/benchmark.h>
#include <coulomb/engine/World.hpp>

#include <bench/JointChain.hpp>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

using namespace coulomb;

namespace {

constexpr std::array<const char*, 3> kSolvers = {"pgs!", "bgs!", "ac_newton!"};
struct Policy {
  joints::StabilizationMethod method;
  joints::EnergyTarget energy;
};
constexpr std::array<Policy, 4> kPolicies = {
    Policy{joints::StabilizationMethod::PredictedState, joints::EnergyTarget::None},
    Policy{joints::StabilizationMethod::Baumgarte, joints::EnergyTarget::None},
    Policy{joints::StabilizationMethod::PredictedState, joints::EnergyTarget::Modified},
    Policy{joints::StabilizationMethod::PredictedState, joints::EnergyTarget::Exact}};

// Args: links, solver index, policy index, 1/dt.
void BM_Chain(benchmark::State& state) {
  const int links = static_cast<int>(state.range(0));
  const double h = 1.0 / static_cast<double>(state.range(3));
  const std::string solver = kSolvers[static_cast<std::size_t>(state.range(1))];
  const auto policy = kPolicies[static_cast<std::size_t>(state.range(2))];
  samples::BallChain chain =
      samples::buildBallChain(links, h, solver, policy.method, policy.energy);
  double gap = 0.0;
  double correctionSolves = 0.0;
  const double startEnergy = chain.world.mechanicalEnergy();
  double driftMax = 0.0, driftMin = 0.0;
  std::int64_t steps = 0;
  for (auto _ : state) {
    const engine::StepReport& report = chain.world.step();
    state.PauseTiming();
    gap = std::max(gap, samples::maxAnchorGap(chain));
    const double drift = chain.world.mechanicalEnergy() - startEnergy;
    driftMax = std::max(driftMax, drift);
    driftMin = std::min(driftMin, drift);
    correctionSolves += report.joints.correctionIterations;
    ++steps;
    state.ResumeTiming();
  }
  const double released = samples::chainReleasedEnergy(links);
  state.counters["max_gap"] = gap;
  state.counters["drift_end"] = (chain.world.mechanicalEnergy() - startEnergy) / released;
  state.counters["drift_max"] = driftMax / released;
  state.counters["drift_min"] = driftMin / released;
  state.counters["corr_iters"] =
      correctionSolves / static_cast<double>(std::max<std::int64_t>(steps, 1));
  state.SetLabel(std::string(solver) + " " + joints::stabilizationMethodName(policy.method) +
                 (policy.energy == joints::EnergyTarget::None
                      ? std::string()
                      : std::string(" energy ") + joints::energyTargetName(policy.energy)) +
                 " dt " + std::to_string(h).substr(0, 5));
}

template <int StepsPerSecond>
void chainArguments(benchmark::internal::Benchmark* b) {
  for (const int links : {10, 50, 200})
    for (int solver = 0; solver < static_cast<int>(kSolvers.size()); ++solver)
      for (int policy = 0; policy < static_cast<int>(kPolicies.size()); ++policy)
        b->Args({links, solver, policy, StepsPerSecond});
}

}  // namespace

// Exactly 10 s of simulated time per run: 1000 steps at dt 0.01, 5000 at dt 0.002.
BENCHMARK(BM_Chain)->Apply(chainArguments<100>)->Iterations(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Chain)->Apply(chainArguments<500>)->Iterations(5000)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
