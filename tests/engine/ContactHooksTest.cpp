// The pre-solve hook and the pair filter (engine/ContactHooks.hpp; docs/embedding.md, "Contact
// events and hooks"), each against an analytic answer and a control run without it: a one-way
// platform, a conveyor belt, friction and restitution changed per contact, a refused value, and
// a custom pair filter.
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>

#include "SimpleBodies.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

using namespace coulomb;
using coulomb::testing::addBall;
using coulomb::testing::addFloor;
using geometry::BodyId;

namespace {

constexpr double kG = 9.81;
constexpr double kH = 0.01;

// The normal of a modification pointing from `from`'s collider to the other one.
Eigen::Vector3d normalFrom(const engine::ContactModification& c, BodyId from) {
  return c.manifold.bodyA == from ? c.manifold.normal : Eigen::Vector3d(-c.manifold.normal);
}

}  // namespace

// Box2D's one-way platform: a ball thrown up from below passes through a thin platform and
// lands on it; without the hook it bounces off the underside and never gets above it.
TEST(ContactHooks, OneWayPlatformLetsBallsUpAndCarriesThem) {
  auto run = [](bool oneWay) {
    engine::World world;
    engine::BodyDesc desc;
    desc.name = "platform";
    desc.motionType = geometry::MotionType::Static;
    desc.pose.position = {0, 0, 1.0};
    desc.shapes.push_back({geometry::Box{{1.0, 1.0, 0.025}}, {}, {0.5, 0.0}, {}});
    const BodyId platform = world.createBody(desc);
    const BodyId ball = addBall(world, {0, 0, 0.5});
    world.setVelocity(ball, {0, 0, 6.0}, Eigen::Vector3d::Zero());  // apex 0.5 + 1.83 m
    if (oneWay)  // only pushes up: the normal from the platform to the other body is up
      world.setPreSolveHook([platform](engine::ContactModification& c) {
        if (normalFrom(c, platform).z() < 0.7) c.enabled = false;
      });
    double highest = 0.0;
    for (int k = 0; k < 300; ++k) {
      world.step(kH);
      highest = std::max(highest, world.pose(ball).position.z());
    }
    return std::pair(highest, world.pose(ball).position.z());
  };
  const auto [freeApex, freeEnd] = run(true);
  EXPECT_GT(freeApex, 2.0);                 // passed through
  EXPECT_NEAR(freeEnd, 1.025 + 0.1, 2e-3);  // resting on top (slop 0.5 mm)
  const auto [blockedApex, blockedEnd] = run(false);
  EXPECT_LT(blockedApex, 1.0);  // the control: stopped by the underside
  EXPECT_LT(blockedEnd, 1.0);
}

// A conveyor: the floor's surface moves at 1 m/s along x. A box put on it accelerates at mu g
// until it moves with the belt, then rides at exactly the belt's speed: v(t) = min(mu g t, 1).
TEST(ContactHooks, ConveyorSurfaceVelocityCarriesABox) {
  engine::World world;
  const BodyId floor = addFloor(world);
  const BodyId box = coulomb::testing::addCube(world, {0, 0, 0.1});
  const Eigen::Vector3d belt(1.0, 0.0, 0.0);
  world.setPreSolveHook([floor, belt](engine::ContactModification& c) {
    // surfaceVelocity is B's surface relative to A's.
    c.surfaceVelocity = c.manifold.bodyA == floor ? Eigen::Vector3d(-belt) : belt;
  });
  const double mu = 0.5;
  for (int k = 1; k <= 100; ++k) {
    world.step(kH);
    const double expected = std::min(mu * kG * k * kH, 1.0);
    ASSERT_NEAR(world.linearVelocity(box).x(), expected, mu * kG * kH + 1e-9) << "step " << k;
  }
  EXPECT_NEAR(world.linearVelocity(box).x(), 1.0, 1e-6);
  EXPECT_NEAR(world.linearVelocity(box).y(), 0.0, 1e-9);
  EXPECT_LT(world.angularVelocity(box).norm(), 1e-4);  // rides flat
}

// Friction and restitution per contact: a box sliding at 2 m/s keeps its speed with friction
// set to 0 and decelerates at 0.2 g with 0.2; a ball dropped on an inelastic floor bounces like
// one whose material has e = 1 (bit for bit), back to about its height.
TEST(ContactHooks, FrictionAndRestitutionPerContact) {
  for (const double mu : {0.0, 0.2}) {
    engine::World world;
    addFloor(world);
    const BodyId box = coulomb::testing::addCube(world, {0, 0, 0.1});
    world.setVelocity(box, {2.0, 0, 0}, Eigen::Vector3d::Zero());
    world.setPreSolveHook([mu](engine::ContactModification& c) { c.friction = mu; });
    for (int k = 0; k < 20; ++k) world.step(kH);
    EXPECT_NEAR(world.linearVelocity(box).x(), 2.0 - mu * kG * 20 * kH, 1e-6) << "mu " << mu;
  }
  engine::World world, elastic;
  addFloor(world);
  const BodyId ball = addBall(world, {0, 0, 1.1});
  world.setPreSolveHook([](engine::ContactModification& c) { c.restitution = 1.0; });
  engine::BodyDesc floor;
  floor.name = "floor";
  floor.motionType = geometry::MotionType::Static;
  floor.shapes.push_back({geometry::Plane{}, {}, {0.5, 1.0}, {}});
  elastic.createBody(floor);
  const BodyId control = addBall(elastic, {0, 0, 1.1});
  double secondApex = 0.0;
  bool bounced = false;
  for (int k = 0; k < 120; ++k) {
    world.step(kH);
    elastic.step(kH);
    ASSERT_EQ(world.pose(ball).position, elastic.pose(control).position) << "step " << k;
    bounced = bounced || world.linearVelocity(ball).z() > 0.0;
    if (bounced) secondApex = std::max(secondApex, world.pose(ball).position.z());
  }
  // Back up to about its height (the velocity-level step reflects v* = v + g h: +4 % here).
  EXPECT_NEAR(secondApex, 1.1, 0.06);
}

// A hook that sets an invalid value is not obeyed: the material's friction stays, the report
// says so once, and nothing in the state becomes NaN.
TEST(ContactHooks, InvalidValuesAreRefusedWithAWarning) {
  engine::World world;
  addFloor(world);
  const BodyId box = coulomb::testing::addCube(world, {0, 0, 0.1});
  world.setVelocity(box, {2.0, 0, 0}, Eigen::Vector3d::Zero());
  world.setPreSolveHook([](engine::ContactModification& c) {
    c.friction = std::numeric_limits<double>::quiet_NaN();
  });
  bool warned = false;
  for (int k = 0; k < 20; ++k)
    for (const std::string& w : world.step(kH).warnings)
      warned = warned || w.find("pre-solve hook") != std::string::npos;
  EXPECT_TRUE(warned);
  EXPECT_NEAR(world.linearVelocity(box).x(), 2.0 - 0.5 * kG * 20 * kH, 1e-6);
  EXPECT_TRUE(world.pose(box).position.allFinite());
}

// A custom pair filter (on the colliders' user data) lets one ball fall through the floor while
// the other rests; the refused pair has no events.
TEST(ContactHooks, PairFilterRefusesChosenPairs) {
  engine::World world;
  addFloor(world);
  engine::BodyDesc ghost;
  ghost.name = "ghost";
  ghost.pose.position = {1, 0, 0.1};
  engine::ShapeDesc sphere{geometry::Sphere{0.1}, {}, {}, {}};
  sphere.userData = 7;
  ghost.shapes.push_back(sphere);
  const BodyId falls = world.createBody(ghost);
  const BodyId rests = addBall(world, {-1, 0, 0.1});
  world.setContactFilter([](const geometry::Collider& a, const geometry::Collider& b) {
    return a.userData != 7 && b.userData != 7;
  });
  for (int k = 0; k < 50; ++k) {
    world.step(kH);
    for (const engine::ContactEvent& e : world.contactEvents()) EXPECT_NE(e.bodyB, falls);
  }
  EXPECT_LT(world.pose(falls).position.z(), -1.0);
  EXPECT_NEAR(world.pose(rests).position.z(), 0.1, 1e-3);
}
