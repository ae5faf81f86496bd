// The "solver" section of a JSON scene and a body's "solver" override (docs/scene-format.md).
#include <gtest/gtest.h>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/io/SceneLoader.hpp>

#include <string>

using namespace coulomb;

namespace {

engine::io::Scene parse(const std::string& solverSection, const std::string& bodyExtra = "") {
  const std::string text = R"({"solver": )" + solverSection + R"(, "bodies": [
      {"name": "ground", "type": "static", "shapes": [{"type": "plane"}]},
      {"name": "box", "position": [0, 0, 0.1], )" +
                           bodyExtra +
                           R"( "shapes": [{"type": "box", "half_extents": [0.1, 0.1, 0.1]}]}]})";
  return engine::io::parseScene(text, "scene.json");
}

std::string errorOf(const std::string& solverSection, const std::string& bodyExtra = "") {
  try {
    parse(solverSection, bodyExtra);
  } catch (const engine::CoulombError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(SceneSolverSection, EmptySectionKeepsEveryDefault) {
  const engine::io::Scene scene = parse("{}");
  const engine::WorldSettings defaults;
  EXPECT_EQ(scene.settings.solve.choice.text(), "auto");
  EXPECT_EQ(scene.settings.solve.options.tolerance, defaults.solve.options.tolerance);
  EXPECT_EQ(scene.settings.solve.options.maxIterations, defaults.solve.options.maxIterations);
  EXPECT_EQ(scene.settings.contact.penetration.slop, defaults.contact.penetration.slop);
  EXPECT_EQ(scene.settings.collision.speculativeMargin, defaults.collision.speculativeMargin);
}

TEST(SceneSolverSection, EveryKeyReachesTheWorldSettings) {
  const engine::io::Scene scene = parse(R"({
      "name": "pgs", "tolerance": 1e-4, "max_iterations": 50, "time_limit": 0.5,
      "warm_start": false, "restitution_threshold": 0.1, "speculative_contacts": false,
      "speculative_margin": 0.01, "promote_fallbacks": false, "sweep_part_blocks": 500,
      "sticking_start": false,
      "penetration": {"method": "baumgarte", "beta": 0.3, "slop": 0.001, "iterations": 7,
                      "solver": "bgs", "tolerance": 1e-5}})",
                                        R"("solver": "ac_newton",)");
  const engine::WorldSettings& s = scene.settings;
  EXPECT_EQ(s.solve.choice, coulomb::solvers::SolverChoice::preferred("pgs"));
  EXPECT_EQ(s.solve.options.tolerance, 1e-4);
  EXPECT_EQ(s.solve.options.maxIterations, 50);
  EXPECT_EQ(s.solve.options.timeLimitSeconds, 0.5);
  EXPECT_FALSE(s.solve.options.useWarmStart);
  EXPECT_EQ(s.solve.options.sweepPartBlocks, 500);
  EXPECT_FALSE(s.solve.options.stickingStart);
  EXPECT_TRUE(engine::WorldSettings{}.solve.options.stickingStart);
  EXPECT_EQ(engine::WorldSettings{}.solve.options.sweepPartBlocks,
            coulomb::solvers::SolvePolicy::kSweepPartBlocks);
  EXPECT_FALSE(s.solve.promotion.enabled);
  EXPECT_FALSE(engine::WorldSettings{}.solve.promotion.enabled);  // off by default since nncg
  EXPECT_EQ(s.contact.restitutionThreshold, 0.1);
  EXPECT_FALSE(s.contact.speculativeContacts);
  EXPECT_EQ(s.collision.speculativeMargin, 0.01);
  EXPECT_EQ(s.contact.penetration.method, engine::PenetrationMethod::Baumgarte);
  EXPECT_EQ(s.contact.penetration.beta, 0.3);
  EXPECT_EQ(s.contact.penetration.slop, 0.001);
  EXPECT_EQ(s.contact.penetration.iterations, 7);
  EXPECT_EQ(s.contact.penetration.solver, "bgs");
  EXPECT_EQ(s.contact.penetration.tolerance, 1e-5);
  EXPECT_EQ(scene.bodies[1].solver, coulomb::solvers::SolverChoice::preferred("ac_newton"));
  EXPECT_FALSE(scene.bodies[0].solver.has_value());
}

TEST(SceneSolverSection, TheWorldUsesTheSceneSolverAndTheBodyOverride) {
  engine::io::Scene scene = parse(R"({"name": "bgs"})");
  engine::World world = engine::io::buildWorld(scene);
  EXPECT_EQ(world.step().islands.front().attempts.front().solver, "bgs");
  scene = parse(R"({"name": "bgs"})", R"("solver": "pgs",)");
  engine::World overridden = engine::io::buildWorld(scene);
  EXPECT_EQ(overridden.step().islands.front().attempts.front().solver, "pgs");
}

TEST(SceneSolverSection, ChainsAndLoneSolversAreAccepted) {
  EXPECT_EQ(parse(R"({"name": "pgs!"})").settings.solve.choice,
            coulomb::solvers::SolverChoice::only("pgs"));
  EXPECT_EQ(parse(R"({"name": "bgs,ac_newton"})").settings.solve.choice,
            coulomb::solvers::SolverChoice::chain({"bgs", "ac_newton"}));
  EXPECT_EQ(parse(R"({"name": "bgs,ac_newton"})").settings.solve.choice.text(), "bgs,ac_newton");
}

// The text form is parsed once, at the edge, with one set of rules: a '!' only ends a lone name
// (World used to accept "pgs!,bgs" and fail at solve time).
TEST(SceneSolverSection, MalformedChainsAreRefusedAtTheEdge) {
  EXPECT_NE(errorOf(R"({"name": "pgs!,bgs"})").find("solver.name: '!' only ends"),
            std::string::npos)
      << errorOf(R"({"name": "pgs!,bgs"})");
  EXPECT_NE(errorOf(R"({"name": "pgs,,bgs"})").find("empty solver name"), std::string::npos);
  EXPECT_NE(errorOf(R"({"penetration": {"solver": "nope"}})").find("unknown solver 'nope'"),
            std::string::npos);
}

TEST(SceneSolverSection, BadValuesNameTheJsonPath) {
  EXPECT_NE(errorOf(R"({"name": "pgz"})").find("solver.name: unknown solver 'pgz'; did you mean"),
            std::string::npos)
      << errorOf(R"({"name": "pgz"})");
  EXPECT_NE(errorOf("{}", R"("solver": "ac_newtn",)").find("bodies[1].solver: unknown solver"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"tolerence": 1e-3})").find("did you mean 'tolerance'"), std::string::npos);
  EXPECT_NE(errorOf(R"({"tolerance": -1})").find("solver.tolerance"), std::string::npos);
  EXPECT_NE(errorOf(R"({"penetration": {"beta": 2}})").find("solver.penetration.beta: must be in"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"penetration": {"method": "split_impulses"}})")
                .find("did you mean 'split_impulse'"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"warm_start": 1})").find("solver.warm_start: expected true or false"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"speculative_margin": -0.1})").find("must be >= 0"), std::string::npos);
  EXPECT_NE(errorOf(R"({"sweep_part_blocks": -5})").find("solver.sweep_part_blocks"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"promote_fallbacks": "yes"})")
                .find("solver.promote_fallbacks: expected true or false"),
            std::string::npos);
}
