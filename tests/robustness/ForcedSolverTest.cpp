// A solver forced on every island with NAME! (no fallback) must never do harm silently (issue 24
// item 4): an answer worse than its start is not applied (SolverOptions::neverWorseThanStart, on
// in the World), lemke! keeps stacks and mass ratios at rest, and a forced solver that cannot run
// on an island is reported once in StepReport::warnings (the CLI prints them).
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>

#include "RobustnessScenes.hpp"
#include "scenes/SceneRegistry.hpp"

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

using namespace coulomb;

namespace {

#ifdef COULOMB_SANITIZE
constexpr int kSteps = 20;  // the sanitizers are 5-10x slower
#else
constexpr int kSteps = 60;
#endif

engine::World forced(const std::string& scene, const std::string& solver) {
  engine::World world = engine::io::buildWorld(scenes::loadBuiltinScene(scene));
  world.setSolver(solvers::SolverChoice::only(solver));
  return world;
}

std::vector<Eigen::Vector3d> positions(const engine::World& world) {
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i < world.state().size(); ++i)
    out.push_back(world.state().poses[i].position);
  return out;
}

double largestDisplacement(const engine::World& world, const std::vector<Eigen::Vector3d>& start) {
  double out = 0.0;
  for (std::size_t i = 0; i < start.size(); ++i)
    out = std::max(out, (world.state().poses[i].position - start[i]).norm());
  return out;
}

// Returns a huge answer inside the cone, as lemke did on a basis cut short by the pivot limit.
class WildSolver final : public solvers::ContactSolver {
 public:
  [[nodiscard]] std::string name() const override { return "wild"; }
  void solvePrepared(const solvers::PreparedProblem& /*problem*/,
                     const solvers::SolveContext& /*context*/, Eigen::VectorXd& r,
                     solvers::SolverReport& report) const override {
    r.setZero();
    for (int i = 0; i + 2 < r.size(); i += 3) r[i] = 1e4;  // normal impulses only: in the cone
    report.status = solvers::SolverStatus::Stalled;
  }
};

}  // namespace

// Before: lemke! applied answers with common residuals up to 857 (pivot limit 200 = the World's
// iteration cap, degenerate paths ending on rays) and shot the light box 736 m.
TEST(ForcedSolver, LemkeKeepsAMassRatioAtRest) {
  for (const char* scene : {"mass_ratio_100kg_on_0_1kg", "mass_tower_light_on_top"}) {
    engine::World world = forced(scene, "lemke");
    const std::vector<Eigen::Vector3d> start = positions(world);
    double worst = 0.0;
    for (int n = 0; n < kSteps; ++n) {
      const engine::StepReport& report = world.step();
      EXPECT_TRUE(report.quarantined.empty()) << scene;
      for (const engine::IslandReport& island : report.islands)
        worst = std::max(worst, island.solve.residual);
    }
    EXPECT_LT(worst, 1e-6) << scene;
    EXPECT_LT(largestDisplacement(world, start), 1e-6) << scene;
  }
}

// Before: a 10-box tower at dt = 0.01 under lemke! diverged (bodies beyond 1000 m by step 53).
TEST(ForcedSolver, LemkeKeepsATowerStandingAtALargeStep) {
  engine::World world = forced("box_stack_10", "lemke");
  const std::vector<Eigen::Vector3d> start = positions(world);
  for (int n = 0; n < kSteps / 2; ++n) {
    const engine::StepReport& report = world.step(0.01);
    EXPECT_TRUE(report.quarantined.empty());
    for (const engine::IslandReport& island : report.islands)
      EXPECT_LT(island.solve.residual, 1e-5) << "step " << n;
  }
  EXPECT_LT(largestDisplacement(world, start), 1e-6);
}

// The safeguard itself, with a solver that always answers garbage (1e4 N s on an 8 kg box: 1250
// m/s): its answer is never applied, the start (r = 0 here, the warm start being 0) is, so the box
// is never pushed: it only falls under gravity; the island is not reported converged.
TEST(ForcedSolver, AnAnswerWorseThanItsStartIsNotApplied) {
  engine::World world;
  world.solverRegistry().add(
      {"wild", "answers 1e4 on every normal", [] { return std::make_unique<WildSolver>(); }});
  world.createBody(robustness::ground());
  const geometry::BodyId box = world.createBody(robustness::box("box", {0.0, 0.0, 0.1}));
  world.setSolver(solvers::SolverChoice::only("wild"));
  const int steps = 20;
  for (int n = 0; n < steps; ++n) {
    const engine::StepReport& report = world.step();
    EXPECT_TRUE(report.quarantined.empty());
    ASSERT_EQ(report.islands.size(), 1u);
    EXPECT_FALSE(report.islands[0].converged());
    EXPECT_NE(report.islands[0].solve.message.find("the start is returned"), std::string::npos)
        << report.islands[0].solve.message;
  }
  EXPECT_TRUE(robustness::stateIsFinite(world));
  EXPECT_LE(world.pose(box).position.z(), 0.1 + 1e-9);             // never pushed up
  EXPECT_LE(world.linearVelocity(box).norm(), 9.81 * 0.2 + 1e-6);  // free fall at most
}

// pyramid_10 is one island of 400 contacts at first: 4000 LCP unknowns, over lemke's cap. Every
// such solve is not applicable and applies nothing; the World says so once.
TEST(ForcedSolver, AForcedSolverThatCannotRunIsReportedOnce) {
  engine::World world = forced("pyramid_10", "lemke");
  const engine::StepReport& first = world.step();
  ASSERT_EQ(first.warnings.size(), 1u);
  const std::string& warning = first.warnings[0];
  EXPECT_NE(warning.find("'lemke!' cannot run"), std::string::npos) << warning;
  EXPECT_NE(warning.find("maxLcpSize"), std::string::npos) << warning;
  ASSERT_FALSE(first.islands.empty());
  EXPECT_EQ(first.islands[0].status, solvers::SolverStatus::NotApplicable);
  for (int n = 0; n < 3; ++n) {
    const engine::StepReport& report = world.step();
    EXPECT_TRUE(report.warnings.empty()) << "said once, not every step";
    EXPECT_EQ(report.islands[0].status, solvers::SolverStatus::NotApplicable);
  }
}
