// WorldSettings::threads (docs/embedding.md, "Threads"): a step's islands run on several
// threads, each writing only its own bodies, rows and contact points, so the state is the same,
// bit for bit, for 1, 2, 4 and 16 threads and for "hardware" (more threads than this machine's
// cores included: the executor runs them as the hardware's count).
#include <gtest/gtest.h>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/StepExecutor.hpp>
#include <coulomb/engine/World.hpp>

#include <algorithm>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "scenes/SceneRegistry.hpp"

using namespace coulomb;

namespace {

std::uint64_t runAndHash(engine::io::Scene scene, int threads, int steps) {
  scene.settings.threads = threads;
  engine::World world = engine::io::buildWorld(scene);
  for (int n = 0; n < steps; ++n) world.step();
  return world.stateHash();
}

// Twelve towers of three boxes 1 m apart, each tilted so that it slides and topples, and twelve
// boxes dropped between them: two dozen islands of different sizes whose contacts merge and split
// as they fall (split impulse on: the penetration stage runs per island too).
engine::io::Scene towers() {
  std::ostringstream json;
  json << R"({"name": "towers", "time_step": 0.01, "materials": {"m": {"friction": 0.5}},
              "bodies": [{"name": "ground", "type": "static",
                          "shapes": [{"type": "plane", "material": "m"}]})";
  for (int t = 0; t < 12; ++t)
    for (int level = 0; level < 4; ++level) {
      const double x = (t % 4) * 1.0, y = (t / 4) * 1.0 + (level == 3 ? 0.5 : 0.0);
      const double z = level == 3 ? 0.6 : 0.1 + 0.21 * level;
      json << R"(, {"name": "b)" << t << '_' << level << R"(", "position": [)" << x + 0.02 * level
           << ", " << y << ", " << z << R"(], "orientation": {"axis": [1, 0.3, 0], "angle": )"
           << 0.05 * (t % 3) + 0.1 * level << R"(}, "density": 500,
              "shapes": [{"type": "box", "half_extents": [0.1, 0.1, 0.1], "material": "m"}]})";
    }
  json << "]}";
  return engine::io::parseScene(json.str(), "towers");
}

int expectedThreads(int requested) {
  if (!engine::StepExecutor::parallel()) return 1;
  const int hardware = engine::StepExecutor::hardwareThreads();
  return requested == 0 ? hardware : std::min(requested, hardware);
}

void expectSameForEveryCount(const engine::io::Scene& scene, int steps) {
  const std::uint64_t serial = runAndHash(scene, 1, steps);
  for (const int threads : {2, 4, 16, 0})
    EXPECT_EQ(runAndHash(scene, threads, steps), serial) << scene.name << ", threads " << threads;
  // The hash sees the state: fewer steps give another one.
  EXPECT_NE(runAndHash(scene, 2, steps - 1), serial) << scene.name;
}

}  // namespace

TEST(ThreadCount, ManyIslandsOfBoxesAreBitIdenticalForEveryCount) {
  expectSameForEveryCount(towers(), 60);
}

TEST(ThreadCount, SixteenRobotsAreBitIdenticalForEveryCount) {
  expectSameForEveryCount(scenes::loadBuiltinScene("anymal_16"), 20);
}

TEST(ThreadCount, AThousandFreeBodiesAreIntegratedInRangesWithTheSameBits) {
  // 1 005 bodies: four ranges of the free bodies' prediction and integration per stage.
  expectSameForEveryCount(scenes::loadBuiltinScene("box_pile_1000"), 10);
}

TEST(ThreadCount, OneLargeIslandIsBitIdenticalForEveryCount) {
  expectSameForEveryCount(scenes::loadBuiltinScene("pyramid_10"), 5);
}

TEST(ThreadCount, OneIslandsSplitSweepsAreBitIdenticalForEveryCount) {
  // pyramid_10's 400 contacts in parts of 64 blocks: 6 parts and a coloured boundary, so its
  // sweeps run on the threads (SolverOptions::sweepPartBlocks; the World's default splits from
  // 4 096 blocks on). The split is another order than the block order: another trajectory.
  engine::io::Scene scene = scenes::loadBuiltinScene("pyramid_10");
  scene.settings.solve.options.stickingStart = false;  // else few steps sweep at all
  const std::uint64_t blockOrder = runAndHash(scene, 1, 20);
  scene.settings.solve.options.sweepPartBlocks = 64;
  expectSameForEveryCount(scene, 20);
  EXPECT_NE(runAndHash(scene, 1, 20), blockOrder);
}

TEST(ThreadCount, SplitSweepsInsideParallelIslandsAreBitIdentical) {
  // Parts of 4 blocks split every island of 8 blocks or more: the sweeps' tasks nest in the
  // islands' (oneTBB runs them in the same arena).
  engine::io::Scene scene = towers();
  scene.settings.solve.options.sweepPartBlocks = 4;
  scene.settings.solve.choice = solvers::solverChoice("pgs!");  // every island swept
  expectSameForEveryCount(scene, 60);
  const std::uint64_t split = runAndHash(scene, 1, 60);
  scene.settings.solve.options.sweepPartBlocks = 0;
  EXPECT_NE(runAndHash(scene, 1, 60), split);  // the sweeps were split
}

TEST(ThreadCount, JointsContactsAndTreesTogetherAreBitIdentical) {
  for (const char* name : {"rope_bridge", "arm_pushing_boxes", "kuka_swing_into_boxes"})
    expectSameForEveryCount(scenes::loadBuiltinScene(name), 30);
}

TEST(ThreadCount, TheWorldSaysHowManyThreadsItUses) {
  engine::io::Scene scene = scenes::loadBuiltinScene("box_on_plane");
  for (const int requested : {1, 2, 16, 0}) {
    scene.settings.threads = requested;
    const engine::World world = engine::io::buildWorld(scene);
    EXPECT_EQ(world.threads(), expectedThreads(requested)) << requested;
  }
  engine::World world = engine::io::buildWorld(scene);
  engine::WorldSettings settings = world.settings();
  settings.threads = 2;
  world.setSettings(settings);  // changed at run time
  EXPECT_EQ(world.threads(), expectedThreads(2));
}

TEST(ThreadCount, ABadCountIsRefusedWithItsValue) {
  engine::WorldSettings settings;
  settings.threads = -1;
  ASSERT_TRUE(settings.validate().has_value());
  EXPECT_NE(settings.validate()->find("threads"), std::string::npos);
  EXPECT_NE(settings.validate()->find("-1"), std::string::npos);
  settings.threads = engine::WorldSettings::kMaxThreads + 1;
  EXPECT_TRUE(settings.validate().has_value());
  EXPECT_THROW(engine::World world(settings), engine::CoulombError);
}

TEST(ThreadCount, TheProblemObserverSeesEveryIslandInOrderOnTheCallingThread) {
  engine::io::Scene scene = towers();
  scene.settings.threads = 2;
  engine::World world = engine::io::buildWorld(scene);
  std::vector<std::int32_t> seen;
  world.setProblemObserver([&](std::int32_t island, const solvers::ContactProblem&) {
    seen.push_back(island);  // no lock: called on this thread only
  });
  for (int n = 0; n < 30; ++n) {
    seen.clear();
    const engine::StepReport& report = world.step();
    ASSERT_EQ(seen.size(), report.islands.size());
    for (std::size_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k], report.islands[k].island);
  }
  EXPECT_GT(seen.size(), 6u);  // the scene has many islands
}

TEST(ThreadCount, AScenesThreadsKeyIsReadAndChecked) {
  const auto parse = [](const std::string& threads) {
    return engine::io::parseScene(R"({"name": "t", "bodies": [], "threads": )" + threads + "}",
                                  "t.json");
  };
  EXPECT_EQ(parse("3").settings.threads, 3);
  EXPECT_EQ(parse(R"("hardware")").settings.threads, 0);
  for (const char* bad : {"0", "-2", R"("all")", "1.5", "100000"}) {
    try {
      (void)parse(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const engine::CoulombError& e) {
      EXPECT_NE(std::string(e.what()).find("threads"), std::string::npos) << e.what();
    }
  }
}
