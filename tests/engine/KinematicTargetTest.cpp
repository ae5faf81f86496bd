// Kinematic bodies driven by target poses (World::setKinematicTarget; docs/embedding.md,
// "Kinematic bodies"): they arrive where told, and their contacts move dynamic bodies as friction
// allows: a platform carries a box without slip below mu g and lets it slip above.
#include <gtest/gtest.h>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/geometry/Quaternion.hpp>

#include <cmath>
#include <numbers>

using namespace coulomb;
using geometry::BodyId;

namespace {

constexpr double kG = 9.81;
constexpr double kH = 0.01;

BodyId addPlatform(engine::World& world, const Eigen::Vector3d& at) {
  engine::BodyDesc desc;
  desc.name = "platform";
  desc.motionType = geometry::MotionType::Kinematic;
  desc.pose.position = at;
  desc.shapes.push_back({geometry::Box{{1.0, 1.0, 0.05}}, {}, {0.6, 0.0}, {}});
  return world.createBody(desc);
}

BodyId addBox(engine::World& world, const Eigen::Vector3d& at) {
  engine::BodyDesc box;
  box.name = "box";
  box.pose.position = at;
  box.shapes.push_back({geometry::Box{Eigen::Vector3d::Constant(0.1)}, {}, {0.6, 0.0}, {}});
  box.mass = geometry::SpatialInertia{1.0, Eigen::Vector3d::Zero(),
                                      Eigen::Matrix3d::Identity() * 0.08 / 12.0};
  return world.createBody(box);
}

}  // namespace

// The body ends each step at its target (position and orientation, to rounding), with a shape
// off its reference origin, and its velocities are those of the move.
TEST(KinematicTarget, ArrivesAtTheTarget) {
  engine::World world;
  engine::BodyDesc desc;
  desc.name = "arm";
  desc.motionType = geometry::MotionType::Kinematic;
  desc.shapes.push_back(
      {geometry::Box{{0.5, 0.05, 0.05}}, geometry::Pose::translation({0.5, 0, 0}), {}, {}});
  const BodyId arm = world.createBody(desc);
  for (int k = 1; k <= 50; ++k) {
    geometry::Pose target;
    target.position = {0.02 * k, 0.0, 0.01 * k};
    target.rotation = geometry::axisRotation(2, 0.05 * k);
    world.setKinematicTarget(arm, target, kH);
    EXPECT_NEAR(world.angularVelocity(arm).z(), 5.0, 1e-9);
    world.step(kH);
    const geometry::Pose& now = world.pose(arm);
    const Eigen::Vector3d com = world.massProperties(arm).centerOfMass;
    EXPECT_LT((now.position - target.apply(com)).norm(), 1e-12) << "step " << k;
    EXPECT_LT(now.rotation.angularDistance(target.rotation), 1e-12) << "step " << k;
  }
}

// A platform oscillating along x, x(t) = A (1 - cos w t), carries a box at rest on it while its
// acceleration A w^2 stays below mu g (mu = 0.6): the box's offset from the platform stays put.
// Above mu g (the control) the box slips.
TEST(KinematicTarget, PlatformCarriesABoxWithoutSlipBelowMuG) {
  auto slip = [](double accelerationOverMuG) {
    engine::World world;
    const Eigen::Vector3d start(0, 0, 0);
    const BodyId platform = addPlatform(world, start);
    const BodyId box = addBox(world, {0, 0, 0.05 + 0.1});
    for (int k = 0; k < 20; ++k) world.step(kH);  // settle on the platform at rest
    const double w = 2.0 * std::numbers::pi;      // one period per second
    const double amplitude = accelerationOverMuG * 0.6 * kG / (w * w);
    const double offset0 = world.pose(box).position.x() - world.pose(platform).position.x();
    double worst = 0.0;
    for (int k = 1; k <= 300; ++k) {
      const double t = k * kH;
      world.setKinematicTarget(
          platform, geometry::Pose::translation({amplitude * (1.0 - std::cos(w * t)), 0, 0}), kH);
      world.step(kH);
      const double offset = world.pose(box).position.x() - world.pose(platform).position.x();
      worst = std::max(worst, std::abs(offset - offset0));
    }
    return worst;
  };
  EXPECT_LT(slip(0.8), 1e-4);  // carried (one step's relative motion at most, h^2 a)
  EXPECT_GT(slip(1.5), 1e-2);  // slides
}

// A platform rising at 1 m/s lifts the box with it; one turning about z turns the box with it.
TEST(KinematicTarget, LiftsAndTurnsWhatRestsOnIt) {
  engine::World world;
  const BodyId platform = addPlatform(world, {0, 0, 0});
  const BodyId box = addBox(world, {0.3, 0, 0.05 + 0.1});
  for (int k = 0; k < 20; ++k) world.step(kH);
  const double gap0 = world.pose(box).position.z() - world.pose(platform).position.z();
  for (int k = 1; k <= 100; ++k) {
    geometry::Pose target;
    target.position = {0, 0, 1.0 * k * kH};
    target.rotation = geometry::axisRotation(2, 0.5 * k * kH);  // 0.5 rad/s: w^2 r << mu g
    world.setKinematicTarget(platform, target, kH);
    world.step(kH);
  }
  const double gap = world.pose(box).position.z() - world.pose(platform).position.z();
  EXPECT_NEAR(gap, gap0, 1e-3);
  const Eigen::Vector3d at = world.pose(box).position;
  EXPECT_NEAR(std::atan2(at.y(), at.x()), 0.5, 1e-2);  // turned with the platform
  EXPECT_NEAR(std::hypot(at.x(), at.y()), 0.3, 1e-3);
}

// A moving kinematic body wakes a sleeping one it runs into and pushes it.
TEST(KinematicTarget, WakesAndPushesSleepingBodies) {
  engine::WorldSettings settings;
  settings.sleep.enabled = true;
  engine::World world(settings);
  engine::BodyDesc floor;
  floor.name = "floor";
  floor.motionType = geometry::MotionType::Static;
  floor.shapes.push_back({geometry::Plane{}, {}, {0.5, 0.0}, {}});
  world.createBody(floor);
  const BodyId box = addBox(world, {0, 0, 0.1});
  for (int k = 0; k < 200; ++k) world.step(kH);
  ASSERT_EQ(world.lastReport().sleepingBodies, 1u);
  engine::BodyDesc pusher;
  pusher.name = "pusher";
  pusher.motionType = geometry::MotionType::Kinematic;
  pusher.pose.position = {-0.5, 0, 0.1};
  pusher.shapes.push_back({geometry::Box{Eigen::Vector3d::Constant(0.1)}, {}, {}, {}});
  const BodyId rod = world.createBody(pusher);
  for (int k = 1; k <= 100; ++k) {
    world.setKinematicTarget(rod, geometry::Pose::translation({-0.5 + 0.5 * k * kH, 0, 0.1}), kH);
    world.step(kH);
  }
  // The pusher's front reached x = -0.4 + 0.5 = 0.1: the box (back face at -0.1) went 0.2 m.
  EXPECT_GT(world.pose(box).position.x(), 0.15);
  EXPECT_EQ(world.lastReport().sleepingBodies, 0u);
}

TEST(KinematicTarget, RefusesWhatItCannotMove) {
  engine::World world;
  const BodyId platform = addPlatform(world, {0, 0, 0});
  const BodyId box = addBox(world, {0, 0, 1});
  EXPECT_THROW(world.setKinematicTarget(box, geometry::Pose{}, kH), engine::CoulombError);
  geometry::Pose bad;
  bad.position.x() = std::nan("");
  EXPECT_THROW(world.setKinematicTarget(platform, bad, kH), engine::CoulombError);
  EXPECT_THROW(world.setKinematicTarget(platform, geometry::Pose{}, 0.0), engine::CoulombError);
  bad = geometry::Pose{};
  bad.rotation.coeffs() *= 2.0;
  EXPECT_THROW(world.setKinematicTarget(platform, bad, kH), engine::CoulombError);
}
