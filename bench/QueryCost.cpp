// Cost of the scene queries (engine/WorldQueries.hpp) on a built-in scene after N steps: queries
// per second of ray casts (closest hit and all hits), sphere casts, sphere overlaps and AABB
// queries, and the cost of bringing the query scene in line with the World after one more step
// (sync), each the median of 5 rounds, with the share of queries that hit something, so a fast
// figure of queries that hit nothing is never read as a result. Ratios between builds are only
// meaningful within one run on one machine.
//
//   build/bin/QueryCost [--steps N] [--queries N] SCENE...
//   e.g. build/bin/QueryCost --steps 100 box_pile_1000
#include <coulomb/engine/WorldQueries.hpp>
#include <coulomb/io/SceneLoader.hpp>

#include "scenes/SceneRegistry.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
using coulomb::geometry::Aabb;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Queries per second of `query(k)` for k in [0, count), median of 5 rounds; `hits` counts how
// many of one round returned something.
double rate(int count, const std::function<bool(int)>& query, int& hits) {
  std::vector<double> perSecond;
  for (int round = 0; round < 5; ++round) {
    hits = 0;
    const auto t0 = Clock::now();
    for (int k = 0; k < count; ++k) hits += query(k) ? 1 : 0;
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    perSecond.push_back(count / s);
  }
  return median(perSecond);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace coulomb;
  int steps = 100, count = 20000;
  std::vector<std::string> names;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--steps" || a == "--queries") && i + 1 < argc)
      (a == "--steps" ? steps : count) = std::atoi(argv[++i]);
    else
      names.push_back(a);
  }
  if (names.empty() || steps < 0 || count <= 0) {
    std::fprintf(stderr, "usage: QueryCost [--steps N] [--queries N] SCENE...\n");
    return 2;
  }
  std::printf("%-18s %9s %8s %12s %6s %12s %6s %12s %6s %12s %6s %12s %6s %9s\n", "scene",
              "colliders", "steps", "rays/s", "hit%", "rayAll/s", "hits", "sphcast/s", "hit%",
              "overlap/s", "hit%", "aabb/s", "hit%", "sync_us");
  int failed = 0;
  for (const std::string& name : names) {
    std::optional<engine::World> built;
    try {
      built.emplace(engine::io::buildWorld(scenes::loadBuiltinScene(name)));
    } catch (const std::exception& error) {
      std::fprintf(stderr, "QueryCost: %s\n", error.what());
      ++failed;
      continue;
    }
    engine::World& world = *built;
    for (int k = 0; k < steps; ++k) world.step();
    // Where the bodies are: queries aim into their bounding box.
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
    for (std::size_t k = 0; k < world.state().size(); ++k) {
      if (world.state().motionTypes[k] != geometry::MotionType::Dynamic) continue;
      lo = lo.cwiseMin(world.state().poses[k].position);
      hi = hi.cwiseMax(world.state().poses[k].position);
    }
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(0, 1);
    auto inside = [&] {
      return Eigen::Vector3d(lo + (hi - lo).cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng))));
    };
    std::vector<Eigen::Vector3d> from(count), to(count), at(count);
    for (int k = 0; k < count; ++k) {
      at[k] = inside();
      from[k] = at[k] + Eigen::Vector3d(0, 0, 2.0 + (hi.z() - lo.z()));  // from above the bodies
      to[k] = inside() - from[k];
    }
    engine::WorldQueries queries(world);
    const geometry::SceneQuery& scene = queries.synced();
    int rayHits = 0, allHits = 0, castHits = 0, overlapHits = 0, aabbHits = 0;
    const double rays = rate(
        count, [&](int k) { return scene.castRay(from[k], to[k]).has_value(); }, rayHits);
    long totalAll = 0;
    const double rayAll = rate(
        count,
        [&](int k) {
          const auto hits = scene.castRayAll(from[k], to[k]);
          totalAll += static_cast<long>(hits.size());
          return !hits.empty();
        },
        allHits);
    const auto ball = std::make_shared<const geometry::Shape>(geometry::Sphere{0.05});
    const int casts = std::max(1, count / 10);
    const double sphereCasts = rate(
        casts,
        [&](int k) {
          return scene.castShape(ball, geometry::Pose::translation(from[k]), to[k]).has_value();
        },
        castHits);
    const auto probe = std::make_shared<const geometry::Shape>(geometry::Sphere{0.25});
    const double overlaps = rate(
        casts,
        [&](int k) { return !scene.overlap(probe, geometry::Pose::translation(at[k])).empty(); },
        overlapHits);
    const double boxes = rate(
        count,
        [&](int k) {
          const Eigen::Vector3d half = Eigen::Vector3d::Constant(0.25);
          return !scene.queryAabb(Aabb{at[k] - half, at[k] + half}).empty();
        },
        aabbHits);
    std::vector<double> syncUs;
    for (int k = 0; k < 5; ++k) {
      world.step();
      const auto t0 = Clock::now();
      static_cast<void>(queries.synced());
      syncUs.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
    }
    std::printf(
        "%-18s %9zu %8d %12.0f %6.1f %12.0f %6.1f %12.0f %6.1f %12.0f %6.1f %12.0f %6.1f %9.1f\n",
        name.c_str(), world.colliders().size(), steps, rays, 100.0 * rayHits / count, rayAll,
        static_cast<double>(totalAll) / (5.0 * count), sphereCasts, 100.0 * castHits / casts,
        overlaps, 100.0 * overlapHits / casts, boxes, 100.0 * aabbHits / count, median(syncUs));
    std::fflush(stdout);
  }
  return failed == 0 ? 0 : 1;
}
