// Contact and sensor events (engine/ContactEvents.hpp; docs/embedding.md, "Contact events and
// hooks"): begin / persist / end against the analytic impulses of a dropped box, sensors that
// never push, sleeping pairs that stay touching, and snapshots that carry the touching pairs.
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>
#include <coulomb/io/Snapshot.hpp>

#include "SimpleBodies.hpp"

#include <cmath>

using namespace coulomb;
using coulomb::testing::addCube;
using coulomb::testing::addFloor;
using engine::ContactEventType;
using geometry::BodyId;

namespace {

constexpr double kG = 9.81;
constexpr double kH = 0.01;

int count(const std::vector<engine::ContactEvent>& events, ContactEventType type) {
  int n = 0;
  for (const engine::ContactEvent& e : events) n += e.type == type ? 1 : 0;
  return n;
}

}  // namespace

// A box dropped from rest: one Begin at landing whose approach speed is the free-fall speed
// sqrt(2 g d) (to one step of gravity, g h), then Persist every step carrying the weight's
// impulse m g h once it rests, and never an End; lifted off, one End.
TEST(ContactEvents, DroppedBoxBeginsPersistsAndEnds) {
  engine::World world;
  addFloor(world);
  const double drop = 0.2;  // the box's underside starts 0.2 m above the floor
  const BodyId box = addCube(world, {0, 0, 0.1 + drop}, 0.1, 2.0);
  int begins = 0, landingStep = -1;
  for (int k = 0; k < 300; ++k) {
    world.step(kH);
    const auto& events = world.contactEvents();
    EXPECT_EQ(count(events, ContactEventType::End), 0) << "step " << k;
    if (count(events, ContactEventType::Begin) == 1) {
      ++begins;
      landingStep = k;
      const engine::ContactEvent& e = events.front();
      EXPECT_NEAR(e.approachSpeed, std::sqrt(2.0 * kG * drop), kG * kH) << "step " << k;
      EXPECT_GT(e.normal.z(), 0.99);  // floor (A) to box (B)
      EXPECT_EQ(e.bodyB, box);
      EXPECT_EQ(e.pointCount, 4);
    }
    if (landingStep < 0) {
      EXPECT_TRUE(events.empty()) << "step " << k << ": before landing";
    }
  }
  EXPECT_EQ(begins, 1);
  const auto& resting = world.contactEvents();
  ASSERT_EQ(resting.size(), 1u);
  EXPECT_EQ(resting.front().type, ContactEventType::Persist);
  EXPECT_NEAR(resting.front().normalImpulse, 2.0 * kG * kH, 1e-4 * 2.0 * kG * kH);
  // No friction on a flat floor, within what the solve's tolerance allows a 2 kg box: 1e-6
  // (1 + |q|) m/s, about 2e-6 N s (its answers are within the tolerance, not exact).
  EXPECT_LT(resting.front().tangentImpulse.norm(), 1e-5);

  world.setVelocity(box, {0, 0, 3.0}, Eigen::Vector3d::Zero());  // thrown up, off the floor
  // The step of the throw may still see the pair touching (detection comes before the solve,
  // and a resting box sits within the touching tolerance or deeper, by the solve's tolerance):
  // at most one Persist then, and exactly one End.
  int ends = 0, persists = 0;
  for (int k = 0; k < 5; ++k) {
    world.step(kH);
    for (const engine::ContactEvent& e : world.contactEvents()) {
      EXPECT_EQ(e.bodyB, box);
      if (e.type == ContactEventType::Persist) {
        EXPECT_EQ(k, 0);
        EXPECT_EQ(ends, 0);
        ++persists;
        continue;
      }
      EXPECT_EQ(e.type, ContactEventType::End);
      ++ends;
    }
  }
  EXPECT_LE(persists, 1);
  EXPECT_EQ(ends, 1);
}

// Removing a touching body ends its pairs in the next step (with its now stale ids); the other
// pair persists. Events come in collider-pair order.
TEST(ContactEvents, RemovedBodyEndsItsPairsInPairOrder) {
  engine::World world;
  addFloor(world);
  const BodyId first = addCube(world, {-1, 0, 0.1}, 0.1, 2.0);
  const BodyId second = addCube(world, {1, 0, 0.1}, 0.1, 2.0);
  for (int k = 0; k < 10; ++k) world.step(kH);
  ASSERT_EQ(world.contactEvents().size(), 2u);
  EXPECT_LT(world.contactEvents()[0].colliderB, world.contactEvents()[1].colliderB);
  world.removeBody(first);
  world.step(kH);
  const auto& events = world.contactEvents();
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].type, ContactEventType::End);
  EXPECT_EQ(events[0].bodyB, first);
  EXPECT_FALSE(world.contains(events[0].bodyB));
  EXPECT_EQ(events[1].type, ContactEventType::Persist);
  EXPECT_EQ(events[1].bodyB, second);
}

// A ball falls through a static sensor box: one overlap Begin and one End, and the fall is the
// free fall of a world without the sensor, bit for bit (a sensor never pushes).
TEST(ContactEvents, SensorCountsWhatEntersAndNeverPushes) {
  auto build = [](engine::World& world, bool withSensor) {
    if (withSensor) {
      engine::BodyDesc zone;
      zone.name = "zone";
      zone.motionType = geometry::MotionType::Static;
      engine::ShapeDesc volume{geometry::Box{{0.5, 0.5, 0.25}}, {}, {}, {}};
      volume.sensor = true;
      volume.userData = 42;
      zone.shapes.push_back(volume);
      world.createBody(zone);
    }
    engine::BodyDesc ball;
    ball.name = "ball";
    ball.pose.position = {0, 0, 1.0};
    ball.shapes.push_back({geometry::Sphere{0.05}, {}, {}, {}});
    return world.createBody(ball);
  };
  engine::World with, without;
  const BodyId ball = build(with, true);
  const BodyId control = build(without, false);
  int begins = 0, ends = 0, beginStep = -1, endStep = -1;
  for (int k = 0; k < 80; ++k) {
    with.step(kH);
    without.step(kH);
    EXPECT_TRUE(with.contactEvents().empty());
    for (const engine::SensorEvent& e : with.sensorEvents()) {
      EXPECT_EQ(e.visitorBody, ball);
      EXPECT_EQ(with.collider(e.sensor).userData, 42u);
      EXPECT_TRUE(with.collider(e.sensor).sensor);
      (e.begin ? begins : ends) += 1;
      (e.begin ? beginStep : endStep) = k;
    }
    ASSERT_EQ(with.pose(ball).position, without.pose(control).position) << "step " << k;
  }
  EXPECT_EQ(begins, 1);
  EXPECT_EQ(ends, 1);
  // The ball's bottom reaches the zone's top (z = 0.25) after falling 0.7 m, and its top leaves
  // the bottom (z = -0.25) after 1.3 m: t = sqrt(2 d / g), to within a step.
  EXPECT_NEAR((beginStep + 1) * kH, std::sqrt(2.0 * 0.7 / kG), 1.5 * kH);
  EXPECT_NEAR((endStep + 1) * kH, std::sqrt(2.0 * 1.3 / kG), 1.5 * kH);
}

// A box that falls asleep on the floor keeps touching silently: no End while it sleeps, and
// when it is woken the pair persists (no second Begin).
TEST(ContactEvents, SleepingPairsKeepTouching) {
  engine::WorldSettings settings;
  settings.sleep.enabled = true;
  engine::World world(settings);
  addFloor(world);
  const BodyId box = addCube(world, {0, 0, 0.1}, 0.1, 2.0);
  int begins = 0, ends = 0;
  auto tally = [&] {
    begins += count(world.contactEvents(), ContactEventType::Begin);
    ends += count(world.contactEvents(), ContactEventType::End);
  };
  for (int k = 0; k < 200; ++k) {
    world.step(kH);
    tally();
  }
  ASSERT_EQ(world.lastReport().sleepingBodies, 1u);
  EXPECT_TRUE(world.contactEvents().empty());  // asleep: nothing to report
  world.applyForce(box, {1.0, 0, 0});          // wakes it
  world.step(kH);
  tally();
  EXPECT_EQ(begins, 1);
  EXPECT_EQ(ends, 0);
  ASSERT_EQ(world.contactEvents().size(), 1u);
  EXPECT_EQ(world.contactEvents().front().type, ContactEventType::Persist);
}

// A snapshot carries the touching pairs: a restored world reports Persist where the original
// does, not a second Begin.
TEST(ContactEvents, SnapshotCarriesTheTouchingPairs) {
  auto build = [](engine::World& world) {
    addFloor(world);
    addCube(world, {0, 0, 0.1}, 0.1, 2.0);
  };
  engine::World original;
  build(original);
  for (int k = 0; k < 20; ++k) original.step(kH);
  const std::vector<std::uint8_t> bytes = engine::io::saveSnapshot(original);
  engine::World restored;
  build(restored);
  engine::io::restoreSnapshot(restored, bytes);
  original.step(kH);
  restored.step(kH);
  ASSERT_EQ(restored.contactEvents().size(), 1u);
  EXPECT_EQ(restored.contactEvents().front().type, ContactEventType::Persist);
  EXPECT_EQ(restored.contactEvents().front().normalImpulse,
            original.contactEvents().front().normalImpulse);
}
