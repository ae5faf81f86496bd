// Maximal-coordinate chains (SCENES.md A6: capsule links 0.1 m, 0.1 kg, ball joints, released
// horizontal): ms per step and joint error for 50 and 200 links, per solver and per
// stabilization policy, at dt 0.01 and 0.002. One benchmark iteration = one step; a run is
// exactly 10 s of simulated time, so the counters are the SCENES.md A6 metrics:
//   max_gap     largest anchor separation over all steps and joints [m]
//   drift_end   (E(T) - E0) / S, S = m g L N^2 / 2 (the energy released when hanging straight)
//   corr_iters  mean predicted-state correction solves per step
// docs/tuning.md quotes the figures.
#include <benchmark/benchmark.h>
#include <coulomb/engine/World.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

using namespace coulomb;

namespace {

constexpr double kG = 9.81;
constexpr std::array<const char*, 3> kSolvers = {"pgs!", "bgs!", "ac_newton!"};
constexpr std::array<joints::StabilizationMethod, 2> kPolicies = {
    joints::StabilizationMethod::PredictedState, joints::StabilizationMethod::Baumgarte};

struct Chain {
  engine::World world;
  std::vector<geometry::JointId> joints;
};

Chain buildChain(int links, double h, const std::string& solver,
                 joints::StabilizationMethod policy) {
  engine::WorldSettings settings;
  settings.timeStep = h;
  settings.solver = solver;
  settings.jointStabilization.method = policy;
  Chain chain{engine::World(settings), {}};
  geometry::BodyId parent;
  for (int i = 0; i < links; ++i) {
    engine::BodyDesc link;
    link.name = "link" + std::to_string(i);
    link.pose = geometry::Pose::translation({(i + 0.5) * 0.1, 0, 0});
    link.mass = {0.1, Eigen::Vector3d::Zero(),
                 Eigen::Vector3d(4.857143e-6, 7.557143e-5, 7.557143e-5).asDiagonal()};
    const geometry::BodyId body = chain.world.createBody(link);
    engine::JointDesc joint;
    joint.type = joints::JointType::Ball;
    joint.bodyA = parent;
    joint.bodyB = body;
    joint.frameA.anchor = i == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0.05, 0, 0);
    joint.frameB.anchor = Eigen::Vector3d(-0.05, 0, 0);
    chain.joints.push_back(chain.world.createJoint(joint));
    parent = body;
  }
  return chain;
}

double maxGap(const Chain& chain) {
  double gap = 0.0;
  for (const geometry::JointId id : chain.joints) {
    const joints::JointDef& j = chain.world.joint(id);
    const auto anchor = [&](geometry::BodyId b, const Eigen::Vector3d& local) {
      return b.valid() ? chain.world.pose(b).apply(local) : local;
    };
    gap =
        std::max(gap, (anchor(j.bodyA, j.frameA.anchor) - anchor(j.bodyB, j.frameB.anchor)).norm());
  }
  return gap;
}

// Args: links, solver index, policy index, 1/dt.
void BM_Chain(benchmark::State& state) {
  const int links = static_cast<int>(state.range(0));
  const double h = 1.0 / static_cast<double>(state.range(3));
  const std::string solver = kSolvers[static_cast<std::size_t>(state.range(1))];
  const auto policy = kPolicies[static_cast<std::size_t>(state.range(2))];
  Chain chain = buildChain(links, h, solver, policy);
  double gap = 0.0;
  double correctionSolves = 0.0;
  std::int64_t steps = 0;
  for (auto _ : state) {
    const engine::StepReport report = chain.world.step();
    state.PauseTiming();
    gap = std::max(gap, maxGap(chain));
    correctionSolves += report.joints.correctionIterations;
    ++steps;
    state.ResumeTiming();
  }
  const double released = 0.1 * kG * 0.1 * links * links / 2.0;
  state.counters["max_gap"] = gap;
  state.counters["drift_end"] = chain.world.mechanicalEnergy() / released;
  state.counters["corr_iters"] =
      correctionSolves / static_cast<double>(std::max<std::int64_t>(steps, 1));
  state.SetLabel(std::string(solver) + " " + joints::stabilizationMethodName(policy) + " dt " +
                 std::to_string(h).substr(0, 5));
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
