// The game-like embedding sample (samples/embedding), headless: what a game built on the
// embedding API must be able to rely on, each against an analytic answer or an invariant.
#include <gtest/gtest.h>

#include <cmath>

#include "Game.hpp"

using namespace coulomb;

namespace {

constexpr double kG = 9.81;

struct Played {
  samples::GameBodies bodies;
  World world;
  samples::GameDirector director;
  explicit Played(int frames) : world(samples::makeGameWorld(bodies)), director(bodies) {
    director.run(world, frames);
  }
};

}  // namespace

// Every shot fired at the standing tower hits it (no tunnelling at 0.67 m per step through
// 0.4 m boxes), the first at the muzzle speed less what gravity turned downwards (<= g t over
// 6 m), and the tower comes down.
TEST(EmbeddingGame, ShotsHitTheTowerAndKnockItOver) {
  Played game(300);
  const samples::GameStats& s = game.director.stats();
  EXPECT_EQ(s.shots, 4);
  EXPECT_GE(s.towerHits, 1);
  EXPECT_NEAR(s.firstHitSpeed, 40.0, kG * 6.0 / 40.0 + 0.1);
  const double topDrop = 0.2 * 11 - game.world.pose(game.bodies.tower.back()).position.z();
  EXPECT_GT(topDrop, 0.3) << "the top box (centre at 2.2 m) fell";
}

// The sensor sees what the shots knock behind the tower, never pushes (no contact event of its
// body), and never reports more exits than entries.
TEST(EmbeddingGame, SensorCountsWhatEnters) {
  Played game(300);
  const samples::GameStats& s = game.director.stats();
  EXPECT_GE(s.sensorEntries, 1);
  EXPECT_GE(s.sensorBegins, s.sensorEntries);
  EXPECT_LE(s.sensorExits, s.sensorBegins);
  EXPECT_EQ(s.zoneContacts, 0);
}

// The jumper passes up through the one-way platform and comes to rest on top of it:
// z = 1.2 + 0.03 + 0.15 (to the penetration slop).
TEST(EmbeddingGame, JumperLandsOnTheOneWayPlatform) {
  Played game(300);
  EXPECT_NEAR(game.world.pose(game.bodies.jumper).position.z(), 1.38, 2e-3);
  EXPECT_LT(game.world.linearVelocity(game.bodies.jumper).norm(), 1e-2);
}

// The lift follows its path exactly and carries the crate at a constant height above it; a ray
// straight down over the lift picks the crate.
TEST(EmbeddingGame, LiftCarriesTheCrateAndTheRayPicksIt) {
  Played game(300);
  const double t = game.world.time();
  EXPECT_NEAR(game.world.pose(game.bodies.lift).position.z(), samples::GameDirector::liftHeight(t),
              1e-12);
  const double above = game.world.pose(game.bodies.crate).position.z() -
                       game.world.pose(game.bodies.lift).position.z();
  EXPECT_NEAR(above, 0.05 + 0.2, 2e-3);
  EXPECT_EQ(samples::GameDirector::pick(game.world, {3.0, -3.0, 5.0}, {0, 0, -1}), "crate");
  EXPECT_EQ(samples::GameDirector::pick(game.world, {0, 0, 50.0}, {0, 0, 1}), std::nullopt);
}

// The same game twice gives the same state, bit for bit.
TEST(EmbeddingGame, IsDeterministic) {
  Played a(200), b(200);
  EXPECT_EQ(a.world.stateHash(), b.world.stateHash());
  EXPECT_EQ(a.director.stats().towerHits, b.director.stats().towerHits);
}
