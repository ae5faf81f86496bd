// Cost of the tree integrators (WorldSettings::treeIntegrator, docs/tuning.md "Tree integrators")
// on the 10- and 50-link chains of docs/scene-specifications.md A6 built as one articulation
// (spherical joints, released horizontal): one iteration = 1 000 World steps of 0.01 s (10 s).
// Args: links, integrator (0 RungeKutta, 1 SemiImplicitEuler). Counters: ms per step, the energy
// error at the end as a fraction of the released energy (Euler diverges: its error is the point).
#include <coulomb/engine/World.hpp>
#include <coulomb/joints/tree/TreeKinematics.hpp>

#include <benchmark/benchmark.h>

#include <chrono>
#include <string>

#include "bench/ShapeFixtures.hpp"

namespace {

using namespace coulomb;

void BM_ReleasedChain(benchmark::State& state) {
  const int links = static_cast<int>(state.range(0));
  engine::WorldSettings settings;
  settings.treeIntegrator = state.range(1) == 0 ? engine::TreeIntegrator::RungeKutta
                                                : engine::TreeIntegrator::SemiImplicitEuler;
  double released = 0.0;
  for (int i = 0; i < links; ++i) released += 0.1 * 9.81 * (0.05 + 0.1 * i);
  double error = 0.0, seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    engine::World world(settings);
    const geometry::ArticulationId id = world.createArticulation(samples::releasedChain(links));
    for (int k = 0; k < 1000; ++k) world.step(0.01);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto& stage = world.articulations();
    const auto kinematics = joints::tree::forwardKinematics(stage.model(id), stage.q(id));
    error = (joints::tree::kineticEnergy(stage.model(id), kinematics, stage.qd(id)) +
             joints::tree::potentialEnergy(stage.model(id), kinematics)) /
            released;
  }
  state.counters["ms_per_step"] = seconds;  // 1 000 steps: seconds in all = ms per step
  state.counters["energy_error"] = error;
}

}  // namespace

BENCHMARK(BM_ReleasedChain)
    ->Args({10, 0})
    ->Args({10, 1})
    ->Args({50, 0})
    ->Args({50, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

BENCHMARK_MAIN();
