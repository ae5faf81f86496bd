// A column of ten turned, tilted boxes at rest (column 0 of box_pile_1000, tests/data/scenes:
// 40 contacts, 120 unknowns, nu = 2, so the automatic rules give it to ac_newton). A warm start
// taken as it is holds no box against the motion since it was computed: on this column its
// residual grows x1.3 per step, and by the time it reaches the tolerance the column is no longer
// stickable (its least-norm stop leaves the cones), so Newton took 100-500 iterations every
// 10-20 steps (7 273 in steps 100-600). Started afresh once the warm start's residual is past
// half-way (in orders of magnitude) from round-off to the tolerance, it needs none
// (docs/solvers.md "Sticking start").
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>
#include <coulomb/io/SceneLoader.hpp>

#include <algorithm>
#include <string>
#include <vector>

using namespace coulomb;

TEST(DriftingColumn, ARestingColumnOfTurnedBoxesIsStuckAgainBeforeItDrifts) {
  const engine::io::Scene scene =
      engine::io::loadSceneFile(COULOMB_TEST_DATA_DIR "/scenes/pile_column.json");
  engine::World world = engine::io::buildWorld(scene);
  std::vector<geometry::BodyId> boxes;
  for (int i = 0; i < 10; ++i) boxes.push_back(world.findBody("box" + std::to_string(100 * i)));
  const double h = scene.settings.timeStep;
  for (int step = 0; step < 100; ++step) world.step(h);  // they fall and land
  std::vector<Eigen::Vector3d> rest;
  for (const geometry::BodyId box : boxes) rest.push_back(world.pose(box).position);
  int iterations = 0, starts = 0;
  double worst = 0.0;
  for (int step = 100; step < 600; ++step) {
    const engine::StepReport& report = world.step(h);
    ASSERT_EQ(report.islands.size(), 1u) << step;
    const engine::IslandReport& island = report.islands.front();
    ASSERT_EQ(island.status, solvers::SolverStatus::Converged) << step;
    worst = std::max(worst, island.solve.residual);
    for (const solvers::SolverReport& attempt : island.attempts) iterations += attempt.iterations;
    if (island.solve.message.find("sticking start") != std::string::npos) ++starts;
  }
  // Measured: 0 iterations, 25 fresh starts (one every 20 steps), the largest residual 1.5e-11,
  // the boxes still within 1e-12 m of where they were at step 100.
  EXPECT_LE(iterations, 50);
  EXPECT_GT(starts, 5);
  EXPECT_LE(worst, 1e-8);
  for (std::size_t i = 0; i < boxes.size(); ++i)
    EXPECT_LT((world.pose(boxes[i]).position - rest[i]).norm(), 1e-9) << "box " << 100 * i;
}
