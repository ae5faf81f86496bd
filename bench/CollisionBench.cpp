// Broad + narrow phase (+ contact cache) time per step on two settled scenes:
//   BoxPile:       1000 unit boxes in 10 x 10 columns of 10, each resting 0.5 mm into the one
//                  below, small deterministic offsets and yaws, on a ground plane;
//   SpheresInBox:  10000 spheres (r = 0.05) on a 22 x 22 lattice, 21 layers, touching, inside a
//                  box made of 5 planes.
// Every step the resting bodies jitter by 1e-5 m / 1e-5 rad, as they do under a solver.
// Counters: candidate pairs, touching pairs (manifolds) and contact points per step.
#include <coulomb/geometry/BroadPhase.hpp>
#include <coulomb/geometry/CollisionPipeline.hpp>

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

namespace {

using namespace coulomb::geometry;

struct Scene {
  std::vector<Collider> colliders;
  std::vector<Pose> rest;  // by body index
};

Collider make(std::uint32_t index, std::shared_ptr<const Shape> shape) {
  Collider c;
  c.id = {index, 0};
  c.body = {index, 0};
  c.shape = std::move(shape);
  return c;
}

Scene boxPile() {
  Scene s;
  s.colliders.push_back(make(0, std::make_shared<const Shape>(Plane{})));
  s.rest.push_back(Pose::identity());
  auto box = std::make_shared<const Shape>(Box{});
  std::uint32_t index = 1;
  for (int x = 0; x < 10; ++x)
    for (int y = 0; y < 10; ++y)
      for (int z = 0; z < 10; ++z) {
        const double yaw = 0.02 * std::sin(1.3 * index);  // ~1 degree
        const Eigen::Vector3d at(1.1 * x + 0.01 * std::cos(0.7 * index),
                                 1.1 * y + 0.01 * std::sin(0.9 * index), 0.5 + z * 0.9995 - 0.0005);
        s.colliders.push_back(make(index, box));
        s.rest.push_back(
            {Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())), at});
        ++index;
      }
  return s;
}

Scene spheresInBox() {
  Scene s;
  const double r = 0.05, spacing = 2 * r - 1e-4;
  const int n = 22, layers = 21;
  const double size = n * spacing;
  const std::vector<Plane> walls{{{0, 0, -1}, 0.0},
                                 {{-1, 0, 0}, 0.0},
                                 {{1, 0, 0}, -size},
                                 {{0, -1, 0}, 0.0},
                                 {{0, 1, 0}, -size}};
  // Each wall's solid half-space lies outside the container: {normal . x <= offset}.
  for (std::size_t w = 0; w < walls.size(); ++w) {
    s.colliders.push_back(make(0, std::make_shared<const Shape>(walls[w])));
    s.colliders.back().id = {static_cast<std::uint32_t>(w), 0};
  }
  s.rest.push_back(Pose::identity());  // body 0: the static container
  auto sphere = std::make_shared<const Shape>(Sphere{r});
  std::uint32_t body = 1;
  for (int z = 0; z < layers; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n && body <= 10000; ++x) {
        Collider c = make(body + 4, sphere);
        c.body = {body, 0};
        s.colliders.push_back(c);
        s.rest.push_back(Pose::translation(
            {r - 5e-5 + x * spacing, r - 5e-5 + y * spacing, r - 5e-5 + z * spacing}));
        ++body;
      }
  return s;
}

void jitter(const Scene& s, std::vector<Pose>& poses, int step) {
  for (std::size_t k = 1; k < poses.size(); ++k) {
    const double a = std::sin(0.37 * (step + 13 * k)), b = std::cos(0.91 * (step + 7 * k));
    poses[k] = {s.rest[k].rotation * Eigen::Quaterniond(Eigen::AngleAxisd(
                                         1e-5 * a, Eigen::Vector3d(b, a, 0.3).normalized())),
                s.rest[k].position + 1e-5 * Eigen::Vector3d(b, a, a * b)};
  }
}

void runPipeline(benchmark::State& state, const Scene& scene) {
  CollisionPipeline pipeline;
  std::vector<Pose> poses = scene.rest;
  const PairPredicate notStaticStatic = [](const Collider& a, const Collider& b) {
    return a.body.index != 0 || b.body.index != 0;
  };
  pipeline.step(scene.colliders, poses, notStaticStatic);  // builds the tree and the cache
  int step = 0;
  for (auto _ : state) {
    jitter(scene, poses, ++step);
    benchmark::DoNotOptimize(pipeline.step(scene.colliders, poses, notStaticStatic).data());
  }
  const CollisionStats& stats = pipeline.diagnostics().stats;
  state.counters["pairs"] = static_cast<double>(stats.candidatePairs);
  state.counters["manifolds"] = static_cast<double>(stats.touchingPairs);
  state.counters["points"] = static_cast<double>(stats.contactPoints);
  state.counters["failures"] = static_cast<double>(pipeline.diagnostics().failures.size());
}

void runBroadPhaseOnly(benchmark::State& state, const Scene& scene) {
  FclScene fcl(0.005);
  BroadPhase broad;
  std::vector<Pose> poses = scene.rest;
  std::vector<CollisionFailure> failures;
  std::vector<char> usable(scene.colliders.size(), 1);
  std::vector<Pose> shapePoses(scene.colliders.size());
  auto place = [&] {
    for (std::size_t i = 0; i < scene.colliders.size(); ++i)
      shapePoses[i] = poses[scene.colliders[i].body.index] * scene.colliders[i].localPose;
  };
  place();
  std::size_t pairs =
      broad.update(scene.colliders, shapePoses, usable, fcl, 0.005, {}, failures).size();
  int step = 0;
  for (auto _ : state) {
    jitter(scene, poses, ++step);
    place();
    pairs = broad.update(scene.colliders, shapePoses, usable, fcl, 0.005, {}, failures).size();
  }
  state.counters["pairs"] = static_cast<double>(pairs);
}

void BM_BoxPile1000_Step(benchmark::State& state) {
  runPipeline(state, boxPile());
}
void BM_BoxPile1000_BroadPhaseOnly(benchmark::State& state) {
  runBroadPhaseOnly(state, boxPile());
}
void BM_Spheres10000InBox_Step(benchmark::State& state) {
  runPipeline(state, spheresInBox());
}
void BM_Spheres10000InBox_BroadPhaseOnly(benchmark::State& state) {
  runBroadPhaseOnly(state, spheresInBox());
}

BENCHMARK(BM_BoxPile1000_Step)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BoxPile1000_BroadPhaseOnly)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Spheres10000InBox_Step)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Spheres10000InBox_BroadPhaseOnly)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
