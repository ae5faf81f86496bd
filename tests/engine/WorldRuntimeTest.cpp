// What an embedding application changes on a live World (docs/embedding.md, "Settings at run
// time" and "Handles and user data"): settings replaced between steps, colliders added to and
// removed from a live body, motors addressed by joint name, user data on joints.
#include <gtest/gtest.h>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/io/Snapshot.hpp>

#include "SimpleBodies.hpp"

#include <cmath>

using namespace coulomb;
using coulomb::testing::addFloor;
using geometry::BodyId;

namespace {

constexpr double kH = 0.01;

}  // namespace

// Gravity and the solve policy change between steps; the free fall follows the new gravity
// exactly (v = v0 + g h per step), and the report names the new solver.
TEST(WorldRuntime, SettingsChangeBetweenSteps) {
  engine::World world;
  addFloor(world);
  engine::BodyDesc ball;
  ball.name = "ball";
  ball.pose.position = {0, 0, 5};
  ball.shapes.push_back({geometry::Sphere{0.1}, {}, {}, {}});
  const BodyId id = world.createBody(ball);
  world.step(kH);
  engine::WorldSettings settings = world.settings();
  settings.gravity = {0, 0, -1.62};  // the Moon
  world.setSettings(settings);
  const double vz = world.linearVelocity(id).z();
  world.step(kH);
  EXPECT_DOUBLE_EQ(world.linearVelocity(id).z(), vz - 1.62 * kH);

  settings.solve.choice = solvers::solverChoice("pgs");
  world.setSettings(settings);
  for (int k = 0; k < 400; ++k) world.step(kH);
  ASSERT_FALSE(world.lastReport().islands.empty());
  EXPECT_EQ(world.lastReport().islands.front().solve.solver, "pgs");
}

// A bad value, an unknown solver or a changed collision setting is refused with its name, and
// nothing changes.
TEST(WorldRuntime, BadSettingsAreRefusedWhole) {
  engine::World world;
  const engine::WorldSettings before = world.settings();
  engine::WorldSettings bad = before;
  bad.gravity = {0, 0, -20};
  bad.timeStep = -1.0;
  EXPECT_THROW(world.setSettings(bad), engine::CoulombError);
  bad = before;
  bad.contact.penetration.solver = "no_such_solver";
  EXPECT_THROW(world.setSettings(bad), engine::CoulombError);
  bad = before;
  bad.collision.speculativeMargin = 0.01;
  try {
    world.setSettings(bad);
    FAIL() << "a changed collision setting was accepted";
  } catch (const engine::CoulombError& e) {
    EXPECT_NE(std::string(e.what()).find("fixed when the World is built"), std::string::npos);
  }
  EXPECT_EQ(world.settings().gravity, before.gravity);
  EXPECT_EQ(world.settings().timeStep, before.timeStep);
}

// Turning sleep off wakes the sleeping bodies.
TEST(WorldRuntime, TurningSleepOffWakesBodies) {
  engine::WorldSettings settings;
  settings.sleep.enabled = true;
  engine::World world(settings);
  addFloor(world);
  engine::BodyDesc box;
  box.name = "box";
  box.pose.position = {0, 0, 0.1};
  box.shapes.push_back({geometry::Box{Eigen::Vector3d::Constant(0.1)}, {}, {}, {}});
  world.createBody(box);
  for (int k = 0; k < 200; ++k) world.step(kH);
  ASSERT_EQ(world.lastReport().sleepingBodies, 1u);
  settings.sleep.enabled = false;
  world.setSettings(settings);
  world.step(kH);
  EXPECT_EQ(world.lastReport().sleepingBodies, 0u);
}

// A body with no collider falls through the floor; given a sphere mid-fall it lands and rests at
// its radius, its mass unchanged; the sphere removed, it falls through again and the contact
// ends.
TEST(WorldRuntime, CollidersAddedToAndRemovedFromALiveBody) {
  engine::World world;
  addFloor(world);
  engine::BodyDesc desc;
  desc.name = "probe";
  desc.pose.position = {0, 0, 1.0};
  desc.mass =
      geometry::SpatialInertia{2.0, Eigen::Vector3d::Zero(), 0.01 * Eigen::Matrix3d::Identity()};
  const BodyId body = world.createBody(desc);
  for (int k = 0; k < 20; ++k) world.step(kH);
  engine::ShapeDesc bad{geometry::Sphere{-0.1}, {}, {}, {}};
  EXPECT_THROW(world.addCollider(body, bad), engine::CoulombError);
  EXPECT_EQ(world.colliders().size(), 1u);  // only the floor's plane
  engine::ShapeDesc sphere{geometry::Sphere{0.1}, {}, {}, {}};
  sphere.userData = 3;
  const geometry::ColliderId added = world.addCollider(body, sphere);
  EXPECT_EQ(world.collider(added).userData, 3u);
  EXPECT_EQ(world.collider(added).body, body);
  for (int k = 0; k < 200; ++k) world.step(kH);
  EXPECT_NEAR(world.pose(body).position.z(), 0.1, 1e-3);
  EXPECT_EQ(world.massProperties(body).mass, 2.0);
  world.removeCollider(added);
  EXPECT_THROW(world.removeCollider(added), engine::CoulombError);
  world.step(kH);
  ASSERT_EQ(world.contactEvents().size(), 1u);
  EXPECT_EQ(world.contactEvents().front().type, engine::ContactEventType::End);
  for (int k = 0; k < 50; ++k) world.step(kH);
  EXPECT_LT(world.pose(body).position.z(), -0.1);
}

// A position motor addressed by its joint's name drives that joint to the target; an unknown
// name is refused with the motorised joints listed.
TEST(WorldRuntime, MotorsByJointName) {
  engine::WorldSettings settings;
  settings.gravity.setZero();
  engine::World world(settings);
  engine::ArticulationDesc desc;
  desc.name = "arm";
  for (int i = 0; i < 2; ++i) {
    engine::ArticulationLinkDesc link;
    link.name = "link" + std::to_string(i);
    link.joint = joints::tree::TreeJoint::revolute(
        i == 0 ? "shoulder" : "elbow",
        geometry::Pose::translation({0.0, static_cast<double>(i), 0.0}), Eigen::Vector3d::UnitY());
    link.inertia = geometry::SpatialInertia{1.0, {0.5, 0, 0}, 0.1 * Eigen::Matrix3d::Identity()};
    desc.links.push_back(link);
  }
  desc.motors.push_back({1, engine::JointMotorMode::Position, 0.0, 100.0});
  const auto arm = world.createArticulation(desc);
  world.setJointMotorTarget(arm, "elbow", 0.5);
  for (int k = 0; k < 200; ++k) world.step(kH);
  EXPECT_NEAR(world.articulations().q(arm)[1], 0.5, 1e-4);
  EXPECT_NEAR(world.articulations().q(arm)[0], 0.0, 1e-2);  // reaction on the free shoulder
  try {
    world.setJointMotorTarget(arm, "wrist", 0.1);
    FAIL() << "an unknown joint was accepted";
  } catch (const engine::CoulombError& e) {
    EXPECT_NE(std::string(e.what()).find("'elbow'"), std::string::npos) << e.what();
  }
}

TEST(WorldRuntime, JointsCarryUserData) {
  engine::World world;
  engine::BodyDesc desc;
  desc.name = "bob";
  desc.shapes.push_back({geometry::Sphere{0.1}, {}, {}, {}});
  const BodyId bob = world.createBody(desc);
  engine::JointDesc joint;
  joint.name = "pin";
  joint.type = joints::JointType::Ball;
  joint.bodyB = bob;
  joint.userData = 0xfeedu;
  const geometry::JointId id = world.createJoint(joint);
  EXPECT_EQ(world.joint(id).userData, 0xfeedu);
}

// An articulation removed between steps: its id and its links' ids become stale, the joints on
// its links go with it, its slot is never reused, the rest of the world steps on, and a snapshot
// of the world with the hole restores bit for bit.
TEST(WorldRuntime, ArticulationsAreRemovable) {
  // Three one-link arms, and a bob pinned to the middle arm's link.
  auto build = [](engine::World& world, std::vector<geometry::ArticulationId>& arms) {
    addFloor(world);
    for (int a = 0; a < 3; ++a) {
      engine::ArticulationDesc desc;
      desc.name = "arm" + std::to_string(a);
      desc.userData = 100u + a;
      engine::ArticulationLinkDesc link;
      link.name = "link";
      link.joint = joints::tree::TreeJoint::revolute(
          "hinge", geometry::Pose::translation({2.0 * a, 0.0, 1.0}), Eigen::Vector3d::UnitY());
      link.inertia = geometry::SpatialInertia{1.0, {0.5, 0, 0}, 0.1 * Eigen::Matrix3d::Identity()};
      desc.links.push_back(link);
      arms.push_back(world.createArticulation(desc));
    }
    engine::BodyDesc bob;
    bob.name = "bob";
    bob.pose.position = {2.0, 0.0, 0.0};
    bob.shapes.push_back({geometry::Sphere{0.05}, {}, {}, {}});
    engine::JointDesc pin;
    pin.name = "pin";
    pin.bodyA = world.articulations().linkBody(arms[1], 0);
    pin.bodyB = world.createBody(bob);
    pin.frameA.anchor = {1.0, 0.0, 0.0};
    return world.createJoint(pin);
  };
  engine::World world;
  std::vector<geometry::ArticulationId> arms;
  const geometry::JointId joint = build(world, arms);
  EXPECT_EQ(world.userData(arms[1]), 101u);
  const BodyId proxy = world.articulations().linkBody(arms[1], 0);
  for (int k = 0; k < 10; ++k) world.step(kH);

  world.removeArticulation(arms[1]);
  EXPECT_FALSE(world.articulations().contains(arms[1]));
  EXPECT_FALSE(world.contains(proxy));
  EXPECT_FALSE(world.contains(joint));
  EXPECT_THROW(world.removeArticulation(arms[1]), engine::CoulombError);
  EXPECT_THROW(static_cast<void>(world.userData(arms[1])), engine::CoulombError);
  EXPECT_EQ(world.articulations().count(), 2u);
  engine::ArticulationDesc again;
  again.name = "again";
  engine::ArticulationLinkDesc link;
  link.name = "link";
  link.joint = joints::tree::TreeJoint::revolute("hinge", geometry::Pose::translation({9, 0, 1}),
                                                 Eigen::Vector3d::UnitY());
  link.inertia = geometry::SpatialInertia{1.0, {0.5, 0, 0}, 0.1 * Eigen::Matrix3d::Identity()};
  again.links.push_back(link);
  const geometry::ArticulationId fresh = world.createArticulation(again);
  EXPECT_NE(fresh, arms[1]);
  for (int k = 0; k < 50; ++k) world.step(kH);
  // The others swung on: released horizontal, each has turned under gravity.
  EXPECT_GT(std::abs(world.articulations().q(arms[0])[0]), 0.5);
  EXPECT_GT(std::abs(world.articulations().q(arms[2])[0]), 0.5);
  EXPECT_EQ(world.articulations().q(arms[0])[0], world.articulations().q(arms[2])[0]);
  EXPECT_TRUE(world.pose(world.articulations().linkBody(arms[2], 0)).position.allFinite());

  // The same history in a second world, then the first one's snapshot: bit for bit.
  engine::World twin;
  std::vector<geometry::ArticulationId> twinArms;
  build(twin, twinArms);
  twin.removeArticulation(twinArms[1]);
  twin.createArticulation(again);
  engine::io::restoreSnapshot(twin, engine::io::saveSnapshot(world));
  world.step(kH);
  twin.step(kH);
  EXPECT_EQ(twin.stateHash(), world.stateHash());
}
