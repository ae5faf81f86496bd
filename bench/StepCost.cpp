// Cost of a World step on built-in scenes or .json scene files: wall time per step (median, p99, max, mean), the first
// step alone, heap allocations per step (malloc calls, counted in this program only) and the
// solver figures of the same steps (iterations, worst common residual), so speed is never read
// without error; the final state hash tells whether two builds computed the same trajectory.
// Ratios between two builds are only meaningful within one run on one machine.
//
//   build/bin/StepCost [--warmup N] [--steps N] [--continuous] SCENE...
//   e.g. build/bin/StepCost --steps 300 box_incline_A_stick pyramid_10 chain_10
// --continuous runs every scene a second time with continuous collision on every dynamic body
// (BodyDesc::continuousCollision; row "SCENE+ccd"): its cost as a ratio within one run.
#include <coulomb/engine/World.hpp>
#include <coulomb/io/SceneLoader.hpp>

#include "scenes/SceneRegistry.hpp"
#include "support/HeapCounter.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  using namespace coulomb;
  int warmup = 20, steps = 200;
  bool continuous = false;
  std::vector<std::string> names;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--warmup" || a == "--steps") && i + 1 < argc)
      (a == "--warmup" ? warmup : steps) = std::atoi(argv[++i]);
    else if (a == "--continuous")
      continuous = true;
    else
      names.push_back(a);
  }
  if (names.empty() || steps <= 0 || warmup < 0) {
    std::fprintf(stderr, "usage: StepCost [--warmup N] [--steps N] [--continuous] SCENE...\n");
    return 2;
  }
  if (continuous) {  // each scene twice, as SCENE and SCENE+ccd
    std::vector<std::string> both;
    for (const std::string& name : names) {
      both.push_back(name);
      both.push_back(name + "+ccd");
    }
    names = both;
  }
  std::printf("%-28s %9s %9s %9s %9s %9s %10s %10s %6s %9s  hash\n", "scene", "first_ms",
              "median_ms", "p99_ms", "max_ms", "mean_ms", "allocs", "bytes", "its", "residual");
  std::fflush(stdout);
  int failed = 0;
  for (const std::string& name : names) {
    std::optional<engine::io::Scene> loaded;
    std::optional<engine::World> built;
    try {  // an unknown scene or a broken file: its error, then the next scene
      const bool ccd = name.ends_with("+ccd");
      loaded = scenes::resolveScene(ccd ? name.substr(0, name.size() - 4) : name);
      for (engine::BodyDesc& body : loaded->bodies)
        body.continuousCollision = ccd && body.motionType == geometry::MotionType::Dynamic;
      built.emplace(engine::io::buildWorld(*loaded));
    } catch (const std::exception& error) {
      std::fprintf(stderr, "StepCost: %s\n", error.what());
      ++failed;
      continue;
    }
    const engine::io::Scene& scene = *loaded;
    engine::World& world = *built;
    const double h = scene.settings.timeStep;
    std::vector<double> ms;
    double first = 0.0;
    std::uint64_t allocs = 0, bytes = 0;
    long iterations = 0;
    double worst = 0.0;
    for (int k = 0; k < warmup + steps; ++k) {
      const std::uint64_t a0 = support::heapAllocations(), b0 = support::heapBytes();
      const auto t0 = std::chrono::steady_clock::now();
      const engine::StepReport& report = world.step(h);  // the World's own: no copy
      const double t =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      if (k == 0) first = t;
      if (k < warmup) continue;
      ms.push_back(t);
      allocs += support::heapAllocations() - a0;
      bytes += support::heapBytes() - b0;
      for (const engine::IslandReport& island : report.islands) {
        for (const solvers::SolverReport& attempt : island.attempts)
          iterations += attempt.iterations;
        worst = std::max(worst, island.solve.residual);
      }
    }
    std::vector<double> sorted = ms;
    std::sort(sorted.begin(), sorted.end());
    double mean = 0.0;
    for (const double t : ms) mean += t / static_cast<double>(ms.size());
    const auto at = [&](double f) {
      return sorted[std::min(sorted.size() - 1, static_cast<std::size_t>(f * sorted.size()))];
    };
    std::printf("%-28s %9.4f %9.4f %9.4f %9.4f %9.4f %10.1f %10.0f %6.1f %9.2e  %016llx\n",
                name.c_str(), first, at(0.5), at(0.99), sorted.back(), mean,
                static_cast<double>(allocs) / steps, static_cast<double>(bytes) / steps,
                static_cast<double>(iterations) / steps, worst,
                static_cast<unsigned long long>(world.stateHash()));
    std::fflush(stdout);
  }
  return failed == 0 ? 0 : 1;
}
