// Threads (WorldSettings::threads, docs/embedding.md "Threads"): wall time per step of the same
// scene at 1 and N threads in one run, the speed-up as a ratio of medians, and what bounds it:
// the share of the step in the stages that run on the threads (measured at 1 thread, the serial
// fraction's complement p), Amdahl's estimate 1 / ((1 - p) + p / n) for 16 and 64 cores, and the
// largest island's share L of the islands' solve time: islands are the unit of work, and one
// island's sweeps spread over at most its P parts (SolverOptions::sweepPartBlocks; P = 1 for
// islands under twice the part size), so n threads can give at most
// 1 / ((1 - p) + p max(L / min(n, P), 1 / n)) ("islands16", "islands64"; optimistic for a split
// island, whose rows, assembly and the boundary's small colours stay serial). The state hash of
// each run must be the same for every count.
//
//   build/bin/ThreadScaling [--warmup N] [--steps N] [--threads 1,2] SCENE|FILE.json ...
//   e.g. build/bin/ThreadScaling --steps 100 anymal_16 pyramid_20 box_pile_1000
#include <coulomb/engine/World.hpp>
#include <coulomb/io/SceneLoader.hpp>
#include <coulomb/solvers/SweepPartition.hpp>

#include "scenes/SceneOverrides.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <string>
#include <vector>

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Run {
  double medianMs = 0.0;
  double parallelShare = 0.0;       // median of (island + penetration stages) / step
  double largestIslandShare = 0.0;  // median of the largest island's share of the solve time
  double largestIslandParts = 1.0;  // median of the parts its sweeps are split into
  double islands = 0.0;             // median island count
  double residual = 0.0;            // worst common residual of the measured steps
  std::uint64_t hash = 0;
  int threads = 1;
};

Run run(const coulomb::engine::io::Scene& scene, int threads, int warmup, int steps) {
  using namespace coulomb;
  engine::io::Scene copy = scene;
  copy.settings.threads = threads;
  engine::World world = engine::io::buildWorld(copy);
  for (int n = 0; n < warmup; ++n) world.step();
  std::vector<double> ms, share, largest, islands, parts;
  const int partBlocks = world.settings().solve.options.sweepPartBlocks;
  Run r;
  for (int n = 0; n < steps; ++n) {
    const engine::StepReport& report = world.step();
    ms.push_back(1e3 * report.seconds);
    const double parallel =
        report.islandStageSeconds + report.penetrationStageSeconds + report.treeStageSeconds;
    share.push_back(report.seconds > 0.0 ? parallel / report.seconds : 0.0);
    double total = 0.0, biggest = 0.0;
    int biggestParts = 1;
    for (const engine::IslandReport& island : report.islands) {
      const double s = island.solve.seconds + island.penetrationSeconds;
      total += s;
      if (s > biggest) {  // blocks: contacts (3 unknowns) and scalar rows
        const auto contacts = static_cast<int>(island.contacts);
        biggestParts = solvers::SweepPartition::partsFor(
            contacts + std::max(0, island.unknowns - 3 * contacts), partBlocks);
      }
      biggest = std::max(biggest, s);
      r.residual = std::max(r.residual, island.solve.residual);
    }
    largest.push_back(total > 0.0 ? biggest / total : 0.0);
    parts.push_back(biggestParts);
    islands.push_back(static_cast<double>(report.islands.size()));
  }
  r.medianMs = median(ms);
  r.parallelShare = median(share);
  r.largestIslandShare = median(largest);
  r.largestIslandParts = median(parts);
  r.islands = median(islands);
  r.hash = world.stateHash();
  r.threads = world.threads();
  return r;
}

double amdahl(double p, double n) {
  return 1.0 / ((1.0 - p) + p / n);
}
double islandBound(double p, double largest, double parts, double n) {
  return 1.0 / ((1.0 - p) + p * std::max(largest / std::min(n, parts), 1.0 / n));
}

}  // namespace

int main(int argc, char** argv) {
  using namespace coulomb;
  int warmup = 20, steps = 100;
  std::vector<int> counts = {1, 2};
  std::vector<std::string> names;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--warmup" || a == "--steps") && i + 1 < argc) {
      (a == "--warmup" ? warmup : steps) = std::atoi(argv[++i]);
    } else if (a == "--threads" && i + 1 < argc) {
      counts.clear();
      std::stringstream list(argv[++i]);
      for (std::string item; std::getline(list, item, ',');)
        counts.push_back(std::atoi(item.c_str()));
    } else {
      names.push_back(a);
    }
  }
  if (names.empty() || steps <= 0 || warmup < 0 || counts.empty() || counts.front() != 1) {
    std::fprintf(stderr,
                 "usage: ThreadScaling [--warmup N] [--steps N] [--threads 1,2,...] SCENE...\n"
                 "(the first count must be 1: the reference of the ratios)\n");
    return 2;
  }
  std::printf("%-16s %7s %8s %10s %8s %9s %9s %6s %8s %8s %9s %9s %9s %5s  %s\n", "scene",
              "threads", "islands", "median_ms", "speedup", "parallel", "largest", "parts",
              "amdahl16", "amdahl64", "islands16", "islands64", "residual", "same", "hash");
  int failed = 0;
  for (const std::string& name : names) {
    try {
      const engine::io::Scene scene = scenes::resolveScene(name, {});
      const Run serial = run(scene, 1, warmup, steps);
      for (const int count : counts) {
        const Run r = count == 1 ? serial : run(scene, count, warmup, steps);
        const bool same = r.hash == serial.hash;
        failed += same ? 0 : 1;
        const double p = serial.parallelShare, largest = serial.largestIslandShare;
        const double parts = serial.largestIslandParts;
        std::printf(
            "%-16s %7d %8.0f %10.3f %8.2f %9.3f %9.3f %6.0f %8.2f %8.2f %9.2f %9.2f %9.1e %5s  "
            "%016llx\n",
            name.c_str(), r.threads, r.islands, r.medianMs, serial.medianMs / r.medianMs, p,
            largest, parts, amdahl(p, 16), amdahl(p, 64), islandBound(p, largest, parts, 16),
            islandBound(p, largest, parts, 64), r.residual, same ? "yes" : "NO",
            static_cast<unsigned long long>(r.hash));
        std::fflush(stdout);
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
      ++failed;
    }
  }
  return failed == 0 ? 0 : 1;
}
