#pragma once
// A game-like scene built on the public API alone (<coulomb/coulomb.hpp>, docs/embedding.md): a
// tower of boxes shot by heavy spheres with continuous collision, a one-way platform (pre-solve
// hook) a ball jumps through and lands on, a sensor behind the tower that counts what enters it, a
// kinematic lift that carries a crate, and a ray-cast pick. The World holds no pointer to the game
// (its hooks capture body ids), so the viewer can rebuild it; the GameDirector drives it frame by
// frame.
#include <coulomb/coulomb.hpp>

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace coulomb::samples {

struct GameBodies {
  BodyId platform;  // one-way, static
  BodyId zone;      // the sensor's body, static
  BodyId lift;      // kinematic
  BodyId crate;     // rides the lift
  BodyId jumper;    // jumps through the platform
  std::vector<BodyId> tower;
};

struct GameSettings {
  double frameTime = 1.0 / 60.0;  // [s] one step per frame
  double shotInterval = 0.75;     // [s] between spheres
  double shotSpeed = 40.0;        // [m/s] 0.67 m per frame: more than a box per step
  int maxShots = 4;
};

/// The scene, with the one-way platform's hook installed.
World makeGameWorld(GameBodies& bodies, const GameSettings& settings = {});

struct GameStats {
  int shots = 0;
  int towerHits = 0;           // Begin events of a sphere with a tower box
  double firstHitSpeed = 0.0;  // [m/s] approach speed of the first of them
  int sensorEntries = 0;       // distinct bodies that entered the sensor
  int sensorBegins = 0;        // overlap begin events (a body may enter twice)
  int sensorExits = 0;
  int zoneContacts = 0;         // contact events of the sensor's body: must stay 0
  double hardestImpulse = 0.0;  // [N s] largest total normal impulse of a Begin event
};

class GameDirector {
 public:
  GameDirector(GameBodies bodies, GameSettings settings = {});
  /// Before each step: tallies the last step's events, fires a sphere when one is due and moves
  /// the lift to where it must be at the end of the step.
  void beforeStep(World& world);
  /// Before, step, and once more to tally the last step: `frames` frames.
  void run(World& world, int frames);
  /// The name of the first body a ray from `origin` along `direction` (any length) hits within
  /// 100 m, or nullopt.
  [[nodiscard]] static std::optional<std::string> pick(const World& world,
                                                       const Eigen::Vector3d& origin,
                                                       const Eigen::Vector3d& direction);
  [[nodiscard]] const GameStats& stats() const { return stats_; }
  [[nodiscard]] const std::vector<BodyId>& spheres() const { return spheres_; }
  [[nodiscard]] const GameBodies& bodies() const { return bodies_; }
  /// The lift's height [m] at time t (what beforeStep drives it to).
  [[nodiscard]] static double liftHeight(double t);

 private:
  void tally(const World& world);
  GameBodies bodies_;
  GameSettings settings_;
  GameStats stats_;
  std::vector<BodyId> spheres_;
  std::set<std::uint64_t> entered_;  // bodies seen entering the sensor (by slot and generation)
  std::uint64_t tallied_ = 0;        // the step count of the events last tallied
};

}  // namespace coulomb::samples
