// Continuous collision (docs/collision.md "Continuous collision"): a thin plank spinning at
// 200 rad/s beside a box turns through it without the flag (the test's control) and is stopped
// by it with the flag; a 5 cm ball at 500 m/s stops at (e = 0) or bounces off (e = 1, at the same
// speed) a 1 cm wall at dt = 1/60; the scene format's key and its error.
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/WorldQueries.hpp>
#include <coulomb/io/SceneLoader.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace coulomb::engine {
namespace {

using Eigen::Vector3d;
using geometry::BodyId;

constexpr double kDt = 1.0 / 60.0;

WorldSettings weightless() {
  WorldSettings settings;
  settings.gravity = Vector3d::Zero();
  settings.timeStep = kDt;
  return settings;
}

geometry::ColliderId colliderOf(const World& world, BodyId body) {
  for (const geometry::Collider& c : world.colliders())
    if (c.body == body) return c.id;
  return {};
}

struct SpinResult {
  Vector3d velocity = Vector3d::Zero();  // [m/s] of the plank's centre after the run
  double spin = 0.0;                     // [rad/s] about z after the run
  double energyRatio = 0.0;              // largest kinetic energy over the initial one
  double deepest = 0.0;                  // [m] largest overlap of plank and box after a step
};

// A 1 m x 2 cm x 2 cm plank along y, turning about z at 200 rad/s (3.3 rad per step); a 10 cm
// box centred 0.35 m along x lies in the path of the plank's half that swings towards +x: the
// box's corner (0.3, -0.05) meets that half after it turned 80 degrees, in the first step.
SpinResult spin(bool continuous) {
  World world(weightless());
  BodyDesc block;
  block.motionType = geometry::MotionType::Static;
  block.pose.position = {0.35, 0, 0};
  block.shapes.push_back({geometry::Box{Vector3d::Constant(0.05)}, {}, {}, {}});
  const BodyId box = world.createBody(block);
  BodyDesc plank;
  plank.pose.rotation = Eigen::AngleAxisd(std::numbers::pi / 2, Vector3d::UnitZ());
  plank.angularVelocity = {0, 0, 200};
  plank.shapes.push_back({geometry::Box{Vector3d(0.5, 0.01, 0.01)}, {}, {}, {}});
  plank.continuousCollision = continuous;
  const BodyId body = world.createBody(plank);
  WorldQueries queries(world);
  const double initial = world.mechanicalEnergy();
  SpinResult result;
  for (int step = 0; step < 30; ++step) {
    world.step();
    result.energyRatio = std::max(result.energyRatio, world.mechanicalEnergy() / initial);
    const double gap =
        queries.closestPoints(colliderOf(world, box), colliderOf(world, body)).distance;
    result.deepest = std::max(result.deepest, -gap);
  }
  result.velocity = world.linearVelocity(body);
  result.spin = world.angularVelocity(body).z();
  return result;
}

TEST(ContinuousCollision, SpinningPlankIsStoppedByTheBoxItWouldTurnThrough) {
  // Control: without continuous collision the plank turns through the box: the speculative row
  // at the closest points (near its centre) barely slows it.
  const SpinResult discrete = spin(false);
  EXPECT_GT(discrete.spin, 150.0);
  // With it, the box's corner strikes the plank's +x half from +y: the plank is thrown towards -y
  // and turns slower (e = 0 on a free rod of length 1 struck across, rho = 0.3 m from its centre:
  // 1 / (1 + 12 rho^2) = 0.47 of its spin stays), it gains no energy, and it never overlaps the
  // box.
  const SpinResult continuous = spin(true);
  EXPECT_LT(continuous.velocity.y(), -10.0);
  EXPECT_LT(continuous.spin, 120.0);
  EXPECT_GT(continuous.spin, 40.0);
  EXPECT_LE(continuous.energyRatio, 1.0 + 1e-9);
  EXPECT_LT(continuous.deepest, 2e-3);
}

struct Shot {
  double farthest = -1e9;   // [m] largest x of the ball's centre over the run
  double finalSpeed = 0.0;  // [m/s] x velocity after the last step
};

// A ball of 5 cm diameter at 500 m/s (8.3 m per step) against a static 1 cm wall at x = 0.
Shot shoot(double restitution, bool continuous) {
  World world(weightless());
  BodyDesc wall;
  wall.motionType = geometry::MotionType::Static;
  wall.shapes.push_back({geometry::Box{Vector3d(0.005, 1, 1)}, {}, {0.5, restitution}, {}});
  world.createBody(wall);
  BodyDesc ball;
  ball.pose.position = {-4.0, 0, 0};
  ball.linearVelocity = {500, 0, 0};
  ball.shapes.push_back({geometry::Sphere{0.025}, {}, {0.5, restitution}, {}});
  ball.continuousCollision = continuous;
  const BodyId id = world.createBody(ball);
  Shot shot;
  for (int step = 0; step < 5; ++step) {
    world.step();
    shot.farthest = std::max(shot.farthest, world.pose(id).position.x());
  }
  shot.finalSpeed = world.linearVelocity(id).x();
  return shot;
}

TEST(ContinuousCollision, FastBallStopsAtOrBouncesOffAThinWall) {
  for (const bool continuous : {false, true}) {
    const Shot stop = shoot(0.0, continuous);
    EXPECT_NEAR(stop.farthest, -0.03, 1e-3) << "the ball's surface at the wall's face";
    EXPECT_NEAR(stop.finalSpeed, 0.0, 1e-6);
    const Shot bounce = shoot(1.0, continuous);
    EXPECT_LT(bounce.farthest, -0.03 + 1e-3);
    EXPECT_NEAR(bounce.finalSpeed, -500.0, 1e-6);
  }
}

TEST(ContinuousCollision, SceneKeyAndItsError) {
  const std::string good = R"({"name": "ccd", "bodies": [
      {"name": "plank", "continuous_collision": true,
       "shapes": [{"type": "box", "half_extents": [0.5, 0.01, 0.01]}]}]})";
  EXPECT_TRUE(io::parseScene(good, "good.json").bodies.at(0).continuousCollision);
  const std::string bad = R"({"name": "ccd", "bodies": [
      {"name": "plank", "continuous_collision": "yes",
       "shapes": [{"type": "box", "half_extents": [0.5, 0.01, 0.01]}]}]})";
  try {
    static_cast<void>(io::parseScene(bad, "bad.json"));
    FAIL() << "accepted a string";
  } catch (const CoulombError& e) {
    EXPECT_NE(std::string(e.what()).find("bodies[0].continuous_collision"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("expected true or false"), std::string::npos);
  }
}

}  // namespace
}  // namespace coulomb::engine
