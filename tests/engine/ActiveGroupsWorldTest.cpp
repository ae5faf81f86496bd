// Islands solved by their groups of acting contacts in the World (docs/solvers.md "Islands by
// their groups of acting contacts"): two boxes resting side by side 2 mm apart are one island
// (their faces are within the 5 mm speculative margin, so the pair has a contact row), but the
// row between them does not act (q_N = gap / h > 0 while they rest) and the island is solved as
// two groups. Each group is a box on the floor, whose answer is exact; the row between them stays
// at zero, the residual of the whole island is the groups', and the boxes stay where they are.
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>
#include <coulomb/io/SceneLoader.hpp>

#include <string>

using namespace coulomb;

namespace {

constexpr const char* kTwoBoxes = R"({
  "name": "two_boxes_apart",
  "time_step": 0.01,
  "materials": {"scene": {"friction": 0.5, "restitution": 0.0}},
  "bodies": [
    {"name": "floor", "type": "static", "shapes": [{"type": "plane", "material": "scene"}]},
    {"name": "left", "position": [0, 0, 0.1], "mass": 1.0, "inertia": [0.0066667, 0.0066667, 0.0066667],
     "shapes": [{"type": "box", "half_extents": [0.1, 0.1, 0.1], "material": "scene"}]},
    {"name": "right", "position": [0.202, 0, 0.1], "mass": 1.0, "inertia": [0.0066667, 0.0066667, 0.0066667],
     "shapes": [{"type": "box", "half_extents": [0.1, 0.1, 0.1], "material": "scene"}]}
  ]
})";

}  // namespace

TEST(ActiveGroupsWorld, BoxesSideBySideAreSolvedAsTwoGroups) {
  const engine::io::Scene scene = engine::io::parseScene(kTwoBoxes, "two_boxes_apart");
  engine::World world = engine::io::buildWorld(scene);
  const Eigen::Vector3d left = world.pose(world.findBody("left")).position;
  int byGroups = 0;
  for (int k = 0; k < 100; ++k) {
    const engine::StepReport& report = world.step(scene.settings.timeStep);
    ASSERT_EQ(report.islands.size(), 1u) << "step " << k;
    const engine::IslandReport& island = report.islands.front();
    EXPECT_EQ(island.status, solvers::SolverStatus::Converged) << "step " << k;
    EXPECT_LE(island.solve.residual, scene.settings.solve.options.tolerance) << "step " << k;
    if (island.solve.solver == "groups") {
      ++byGroups;
      EXPECT_NE(island.solve.message.find("2 groups"), std::string::npos) << island.solve.message;
      EXPECT_EQ(island.reason().rfind("solved by its groups of acting contacts", 0), 0u)
          << island.reason();
    }
  }
  EXPECT_GT(byGroups, 50);
  EXPECT_LT((world.pose(world.findBody("left")).position - left).norm(), 1e-6);
}
