// Issue 7 item 10: a scene whose solver is forced to fail falls back and says so in the report;
// the answer applied is the fallback's, so the box still rests.
// (World accepts registry names only; a lone \"NAME!\" request without fallback is the
// SolverChooser's syntax, tested in tests/solvers.)
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>
#include <coulomb/solvers/ContactSolver.hpp>

#include "scenes/SceneRegistry.hpp"

#include <memory>

using namespace coulomb;

namespace {

// A registry entry that never solves anything: it returns r = 0 and declares itself stalled.
class AlwaysFailingSolver : public solvers::ContactSolver {
 public:
  [[nodiscard]] std::string name() const override { return "always_fails"; }
  void solvePrepared(const solvers::PreparedProblem&, const solvers::SolveContext&,
                     Eigen::VectorXd& r, solvers::SolverReport& report) const override {
    r.setZero();
    report.status = solvers::SolverStatus::Stalled;
    report.note("fails by design (test)");
  }
};

engine::World restingBoxWithFailingSolver(bool warmStarts) {
  engine::io::Scene scene = scenes::loadBuiltinScene("box_on_plane");
  scene.settings.solve.options.useWarmStart = warmStarts;
  engine::World world = engine::io::buildWorld(scene);
  world.solverRegistry().add({"always_fails", "test: never converges",
                              [] { return std::make_unique<AlwaysFailingSolver>(); }});
  world.setSolver(coulomb::solvers::solverChoice("always_fails"));
  return world;
}

// Runs 100 steps; returns how many island solves fell back (each checked and reported).
std::size_t stepAndCountFallbacks(engine::World& world) {
  std::size_t fallbacks = 0;
  for (int k = 0; k < 100; ++k) {
    const engine::StepReport report = world.step();
    EXPECT_EQ(report.islands.size(), 1u);
    if (report.islands.empty()) break;
    const engine::IslandReport& island = report.islands.front();
    EXPECT_EQ(island.attempts.front().solver, "always_fails") << "step " << k;
    EXPECT_TRUE(island.converged()) << "step " << k << ": " << island.solve.message;
    if (island.attempts.size() < 2) continue;  // the warm start alone met the tolerance
    ++fallbacks;
    EXPECT_EQ(island.attempts.front().status, solvers::SolverStatus::Stalled);
    EXPECT_GT(island.attempts.front().residual, 1e-3);  // r = 0 leaves the weight unsupported
    EXPECT_NE(island.solve.solver, "always_fails");     // the applied answer is a fallback's
    // The report says so without formatting anything per step: every attempt's report, and the
    // plan (formatted only when asked) lists the requested solver and its fallbacks.
    EXPECT_EQ(island.attempts.back().solver, island.solve.solver);
    EXPECT_NE(island.reason().find("attempts: always_fails"), std::string::npos) << island.reason();
    EXPECT_EQ(report.fallbacks(), island.attempts.size() - 1);
  }
  return fallbacks;
}

}  // namespace

TEST(SolverFallback, AFailingSolverFallsBackAndTheReportSaysSo) {
  // Cold solves only: the failing solver runs, and fails, in every step.
  engine::World world = restingBoxWithFailingSolver(false);
  const geometry::BodyId box = world.findBody("box");
  const Eigen::Vector3d start = world.pose(box).position;
  EXPECT_EQ(stepAndCountFallbacks(world), 100u);
  EXPECT_LT((world.pose(box).position - start).norm(), 1e-6);
}

TEST(SolverFallback, WarmStartsFromTheFallbackAreKept) {
  // With warm starts the first step falls back; later steps start from the fallback's impulses,
  // which already meet the tolerance, so the failing solver is not even run.
  engine::World world = restingBoxWithFailingSolver(true);
  const geometry::BodyId box = world.findBody("box");
  const Eigen::Vector3d start = world.pose(box).position;
  EXPECT_GE(stepAndCountFallbacks(world), 1u);
  EXPECT_LT((world.pose(box).position - start).norm(), 1e-6);
}
