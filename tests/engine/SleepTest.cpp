// Sleep: resting islands sleep, wake on contact and on user action; off by default.
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>

using namespace coulomb;
using geometry::BodyId;

namespace {

engine::World makeWorld(bool sleep) {
  engine::WorldSettings settings;
  settings.sleep.enabled = sleep;
  return engine::World(settings);
}

void addGround(engine::World& world) {
  engine::BodyDesc ground;
  ground.motionType = geometry::MotionType::Static;
  ground.shapes.push_back({geometry::Plane{}, {}, {0.5, 0.0}, {}});
  world.createBody(ground);
}

BodyId addBox(engine::World& world, const Eigen::Vector3d& position) {
  engine::BodyDesc box;
  box.pose.position = position;
  box.shapes.push_back({geometry::Box{Eigen::Vector3d::Constant(0.1)}, {}, {0.5, 0.0}, {}});
  box.mass = geometry::SpatialInertia{1.0, Eigen::Vector3d::Zero(),
                                      Eigen::Matrix3d::Identity() * 8.0 * 0.01 / 12.0};
  return world.createBody(box);
}

}  // namespace

TEST(Sleep, OffByDefault) {
  engine::World world;
  addGround(world);
  addBox(world, {0, 0, 0.1});
  for (int k = 0; k < 200; ++k) EXPECT_EQ(world.step(0.01).sleepingBodies, 0u);
  EXPECT_FALSE(engine::WorldSettings{}.sleep.enabled);
}

TEST(Sleep, RestingStackSleepsAndCostsNoSolve) {
  engine::World world = makeWorld(true);
  addGround(world);
  const BodyId bottom = addBox(world, {0, 0, 0.1});
  addBox(world, {0, 0, 0.3});
  engine::StepReport report;
  for (int k = 0; k < 100; ++k) report = world.step(0.01);
  EXPECT_EQ(report.sleepingBodies, 2u);
  report = world.step(0.01);
  EXPECT_TRUE(report.islands.empty());  // nothing to solve while asleep
  EXPECT_EQ(world.linearVelocity(bottom), Eigen::Vector3d::Zero());
  const Eigen::Vector3d before = world.pose(bottom).position;
  for (int k = 0; k < 100; ++k) world.step(0.01);
  EXPECT_EQ(world.pose(bottom).position, before);  // exactly still
}

TEST(Sleep, FallingBodyDoesNotSleepAtItsApex) {
  engine::World world = makeWorld(true);
  const BodyId ball = addBox(world, {0, 0, 5.0});
  world.setVelocity(ball, {0, 0, 0.05}, Eigen::Vector3d::Zero());  // slow near the apex
  for (int k = 0; k < 60; ++k) EXPECT_EQ(world.step(0.01).sleepingBodies, 0u);
}

TEST(Sleep, AwakeBodyLandingOnASleepingStackWakesIt) {
  engine::World world = makeWorld(true);
  addGround(world);
  const BodyId bottom = addBox(world, {0, 0, 0.1});
  for (int k = 0; k < 100; ++k) world.step(0.01);
  ASSERT_EQ(world.step(0.01).sleepingBodies, 1u);
  const BodyId dropped = addBox(world, {0, 0, 0.5});
  bool woke = false;
  for (int k = 0; k < 100 && !woke; ++k) woke = world.step(0.01).sleepingBodies == 0;
  EXPECT_TRUE(woke);
  for (int k = 0; k < 200; ++k) world.step(0.01);
  EXPECT_NEAR(world.pose(dropped).position.z(), 0.3, 2e-3);  // rests on the woken box
  EXPECT_NEAR(world.pose(bottom).position.z(), 0.1, 2e-3);
}

TEST(Sleep, UserActionWakesTheIsland) {
  engine::World world = makeWorld(true);
  addGround(world);
  const BodyId box = addBox(world, {0, 0, 0.1});
  for (int k = 0; k < 100; ++k) world.step(0.01);
  ASSERT_EQ(world.step(0.01).sleepingBodies, 1u);
  world.setVelocity(box, {1.0, 0, 0}, Eigen::Vector3d::Zero());
  world.step(0.01);
  EXPECT_GT(world.pose(box).position.x(), 0.005);
}

TEST(Sleep, InvalidSettingsAreRejected) {
  engine::WorldSettings settings;
  settings.sleep.timeToSleep = -1.0;
  ASSERT_TRUE(settings.validate().has_value());
  EXPECT_NE(settings.validate()->find("sleep time"), std::string::npos);
}
