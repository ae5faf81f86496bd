// The "articulations" section of JSON scenes (docs/scene-format.md) and the built-in scenes
// pendulum_reduced (docs/scene-specifications.md B8, reduced variant) and arm_pushing_boxes.
#include <gtest/gtest.h>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/io/SceneLoader.hpp>

#include <cmath>
#include <string>
#include <vector>

using namespace coulomb;

namespace {

const std::string kScenes = std::string(COULOMB_TEST_DATA_DIR) + "/../../samples/scenes/";

std::string errorOf(const std::string& text) {
  try {
    engine::io::buildWorld(engine::io::parseScene(text, "t.json"));
  } catch (const engine::CoulombError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SceneArticulation, ReducedPendulumHasTheEllipticPeriod) {
  const engine::io::Scene scene = engine::io::loadSceneFile(kScenes + "pendulum_reduced.json");
  ASSERT_EQ(scene.articulations.size(), 1u);
  engine::World world = engine::io::buildWorld(scene);
  const geometry::ArticulationId id{0, 0};
  ASSERT_TRUE(world.articulations().contains(id));
  // Sign changes of the bob's x (docs/scene-specifications.md B8 metric): period = t_{i+2} - t_i.
  std::vector<double> crossings;
  double previousX = 1.0, previousT = 0.0;
  for (std::uint64_t k = 0; k < scene.steps; ++k) {
    world.step();
    const double x = std::cos(world.articulations().q(id)[0]);
    if ((x < 0.0) != (previousX < 0.0))
      crossings.push_back(previousT + (world.time() - previousT) * previousX / (previousX - x));
    previousX = x;
    previousT = world.time();
  }
  ASSERT_GE(crossings.size(), 3u);
  double period = 0.0;
  for (std::size_t i = 0; i + 2 < crossings.size(); ++i) period += crossings[i + 2] - crossings[i];
  period /= static_cast<double>(crossings.size() - 2);
  EXPECT_NEAR(period, 2.369025573, 1e-3 * 2.369025573);
  EXPECT_NEAR(crossings.front(), 0.592256, 0.01);
}

TEST(SceneArticulation, ArmPushingBoxesIsOneIslandWithTheBoxes) {
  const engine::io::Scene scene = engine::io::loadSceneFile(kScenes + "arm_pushing_boxes.json");
  engine::World world = engine::io::buildWorld(scene);
  std::vector<Eigen::Vector3d> start;
  for (const char* name : {"box1", "box2", "box3", "box4"})
    start.push_back(world.pose(world.findBody(name)).position);
  std::size_t largestIsland = 0;
  for (int k = 0; k < 150; ++k) {
    const engine::StepReport report = world.step();
    for (const auto& island : report.islands)
      largestIsland = std::max(largestIsland, island.bodies);
  }
  EXPECT_GE(largestIsland, 2u);  // the arm (one unit) and a box it touches
  double moved = 0.0;
  for (const char* name : {"box1", "box2", "box3", "box4"})
    moved = std::max(moved, (world.pose(world.findBody(name)).position -
                             start[static_cast<std::size_t>(name[3] - '1')])
                                .norm());
  EXPECT_GT(moved, 0.05);  // a box was pushed
  for (std::size_t i = 0; i < world.state().size(); ++i)
    EXPECT_TRUE(world.state().poses[i].position.allFinite());
}

TEST(SceneArticulation, ErrorsNameTheJsonPath) {
  const std::string head = R"({"articulations": [{"name": "a", "links": [)";
  EXPECT_NE(errorOf(head + R"({"name": "l", "joint": {"type": "hinge"}}]}]})")
                .find("articulations[0].links[0].joint.type: unknown joint type 'hinge'"),
            std::string::npos);
  EXPECT_NE(errorOf(head + R"({"name": "l", "parent": "nope", "joint": {}}]}]})")
                .find("articulations[0].links[0].parent: unknown link 'nope'"),
            std::string::npos);
  EXPECT_NE(errorOf(head + R"({"name": "l", "joint": {}, "mass": 1, "inertia": [1, 1, 1]}],
                               "q": [0, 1]}]})")
                .find("articulations[0]: articulation 'a'"),
            std::string::npos);
  EXPECT_NE(errorOf(head + R"({"name": "l", "joint": {}, "colour": 1}]}]})")
                .find("articulations[0].links[0]"),
            std::string::npos);
}
