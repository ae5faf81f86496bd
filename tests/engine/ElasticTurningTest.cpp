// Elastic turning (ContactSettings::elasticTurning, docs/tuning.md): a ball circling inside a
// ring of two capsule rails (docs/scene-specifications.md B11's rail geometry curled into one loop,
// no gravity) keeps its kinetic energy with the option on and loses ~ pi m v^3 h / R per turn with
// it off (each inelastic step removes the normal velocity n_k+1 . v = -v sin(v h / R) that the
// turning of the normal creates); a resting box stack is not made to bounce by it.
#include <coulomb/engine/World.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

namespace coulomb::engine {
namespace {

constexpr double kRho = 0.1, kRail = 0.01, kWidth = 0.1, kMass = 1.0, kInertia = 0.004;
constexpr double kRingRadius = 1.0;  // [m] rail axes
constexpr int kPieces = 720;         // 0.5 degree per capsule, as the double loop's rails
constexpr double kH = 0.01;
// Ball centre from the rails' plane along the normal and its rolling radius
// (docs/scene-specifications.md B11); the centre circles at kRingRadius - kHeight.
const double kHeight = std::sqrt((kRho + kRail) * (kRho + kRail) - kWidth * kWidth / 4);
const double kRhoEff = kRho * kHeight / (kRho + kRail);
const double kPathRadius = kRingRadius - kHeight;

struct Rig {
  World world;
  geometry::BodyId ball;
};

// Rails: circles of radius kRingRadius in the x-z plane about (0, 0, kRingRadius) at y = +-w/2,
// chains of kPieces capsules; the ball inside at the bottom moving along +x at v0, rolling (mu > 0)
// or not spinning (mu = 0).
std::unique_ptr<Rig> makeRing(double mu, double v0, bool elasticTurning) {
  WorldSettings settings;
  settings.solve.choice = coulomb::solvers::solverChoice("ac_newton");
  settings.gravity = Eigen::Vector3d::Zero();
  settings.contact.elasticTurning = elasticTurning;
  auto rig = std::make_unique<Rig>(Rig{World(settings), {}});
  BodyDesc rails;
  rails.motionType = geometry::MotionType::Static;
  auto railPoint = [](int j, double y) {
    const double phi = 2 * std::numbers::pi * j / kPieces;
    return Eigen::Vector3d(kRingRadius * std::sin(phi), y, kRingRadius * (1 - std::cos(phi)));
  };
  for (const double side : {1.0, -1.0})
    for (int j = 0; j < kPieces; ++j) {
      const Eigen::Vector3d a = railPoint(j, side * kWidth / 2);
      const Eigen::Vector3d b = railPoint(j + 1, side * kWidth / 2);
      rails.shapes.push_back(
          {geometry::Capsule{kRail, (b - a).norm() / 2},
           {Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), b - a), (a + b) / 2},
           {mu, 0.0},
           {}});
    }
  rig->world.createBody(rails);
  BodyDesc ball;
  ball.pose.position = {0.0, 0.0, kHeight};
  ball.linearVelocity = {v0, 0.0, 0.0};
  ball.angularVelocity = {0.0, mu > 0.0 ? v0 / kRhoEff : 0.0, 0.0};
  ball.shapes.push_back({geometry::Sphere{kRho}, {}, {mu, 0.0}, {}});
  ball.mass = geometry::SpatialInertia{kMass, Eigen::Vector3d::Zero(),
                                       kInertia * Eigen::Matrix3d::Identity()};
  rig->ball = rig->world.createBody(ball);
  return rig;
}

struct Turn {
  double energyRatio = 0.0;  // kinetic energy after one turn / before
  double maxOffPath = 0.0;   // [m] largest distance of the centre from its circle
};

// Steps the ring for one turn of the path (at the initial speed) and measures.
Turn oneTurn(double mu, double v0, bool elasticTurning) {
  auto rig = makeRing(mu, v0, elasticTurning);
  const double e0 = rig->world.mechanicalEnergy();
  const int steps = static_cast<int>(std::lround(2 * std::numbers::pi * kPathRadius / v0 / kH));
  Turn turn;
  for (int s = 0; s < steps; ++s) {
    rig->world.step(kH);
    const Eigen::Vector3d p = rig->world.pose(rig->ball).position;
    const double off = std::abs(std::hypot(p.x(), p.z() - kRingRadius) - kPathRadius);
    turn.maxOffPath = std::max(turn.maxOffPath, std::max(off, std::abs(p.y())));
  }
  turn.energyRatio = rig->world.mechanicalEnergy() / e0;
  return turn;
}

// Inelastic loss: dE = -(1/2) m v^2 theta^2 per step, theta = v h / R. With E = (1 + k) m v^2 / 2
// (k = 0 sliding; k = k' = I / (m rho_eff^2) rolling, where the projection onto the rolling motion
// about the new contact axis loses the same m v^2 theta^2 / 2 to first order): dv/ds = -v^2 h /
// (2 R^2 (1 + k)), so 1 / v grows by pi h / (R (1 + k)) over one turn (to first order: pi m v^3 h
// / R of energy).
double inelasticRatio(double v0, double k) {
  const double inverse = 1 / v0 + std::numbers::pi * kH / (kPathRadius * (1 + k));
  return 1 / (inverse * inverse * v0 * v0);
}

TEST(ElasticTurning, SlidingBallKeepsItsEnergyInARingOnlyWithTheOption) {
  const double v0 = 2.0;  // 1.27 degrees of turn per step
  const Turn on = oneTurn(0.0, v0, true);
  const Turn off = oneTurn(0.0, v0, false);
  const double predicted = 1 - inelasticRatio(v0, 0.0);  // 0.1260
  std::printf("mu 0 v0 %g: KE loss per turn on %.6f, off %.6f (predicted off %.6f)\n", v0,
              1 - on.energyRatio, 1 - off.energyRatio, predicted);
  // On: no energy gained, and at least 85 % of the loss gone (measured 0.93 % per turn against
  // 12.6 %). What is left: the capsule chain is a polygon of 0.5 degree kinks that the ball's
  // 2 cm steps cross two or three at a time, so some steps close a small gap first
  // (speculatively, inelastic) instead of turning.
  EXPECT_LE(on.energyRatio, 1.0 + 1e-6);
  EXPECT_LT(1 - on.energyRatio, 0.15 * predicted);
  EXPECT_NEAR(1 - off.energyRatio, predicted, 0.1 * predicted);
  EXPECT_LT(on.maxOffPath, 2e-3);
  EXPECT_LT(off.maxOffPath, 2e-3);
}

TEST(ElasticTurning, RollingBallKeepsItsEnergyInARingOnlyWithTheOption) {
  const double v0 = 2.0;
  const Turn on = oneTurn(1.0, v0, true);
  const Turn off = oneTurn(1.0, v0, false);
  const double k = kInertia / (kMass * kRhoEff * kRhoEff);  // 0.504
  const double predicted = 1 - inelasticRatio(v0, k);       // 0.0866
  std::printf("mu 1 v0 %g: KE loss per turn on %.6f, off %.6f (predicted off %.6f)\n", v0,
              1 - on.energyRatio, 1 - off.energyRatio, predicted);
  EXPECT_LE(on.energyRatio, 1.0 + 1e-6);
  EXPECT_LT(1 - on.energyRatio, 0.15 * predicted);  // measured 0.53 % against 8.6 %
  EXPECT_NEAR(1 - off.energyRatio, predicted, 0.1 * predicted);
  EXPECT_LT(on.maxOffPath, 2e-3);
}

// A resting stack of five boxes (each 2 cm off the one below) with the option on:
// its contacts are persistent and loaded, their normals do not turn, and gravity's h g stays
// inelastic, so nothing bounces and the mechanical energy never grows.
struct StackRun {
  double energyRise = 0.0;  // [J] largest rise of the mechanical energy over its value after 0.2 s
  double speedMax = 0.0;    // [m/s] fastest box after 0.2 s
};

StackRun restingStack(bool elasticTurning) {
  WorldSettings settings;
  settings.contact.elasticTurning = elasticTurning;
  World world(settings);
  BodyDesc ground;
  ground.motionType = geometry::MotionType::Static;
  ground.shapes.push_back({geometry::Plane{}, {}, {0.6, 0.0}, {}});
  world.createBody(ground);
  std::vector<geometry::BodyId> boxes;
  for (int i = 0; i < 5; ++i) {
    BodyDesc box;
    box.pose.position = {0.02 * i, 0.0, 0.1 + 0.2 * i};
    box.shapes.push_back({geometry::Box{Eigen::Vector3d::Constant(0.1)}, {}, {0.6, 0.0}, {}});
    boxes.push_back(world.createBody(box));
  }
  for (int s = 0; s < 20; ++s) world.step(kH);  // settle
  const double e0 = world.mechanicalEnergy();
  StackRun run;
  for (int s = 0; s < 300; ++s) {
    world.step(kH);
    run.energyRise = std::max(run.energyRise, world.mechanicalEnergy() - e0);
    for (const geometry::BodyId b : boxes)
      run.speedMax = std::max(run.speedMax, world.linearVelocity(b).norm());
  }
  return run;
}

TEST(ElasticTurning, RestingStackDoesNotGainEnergy) {
  const StackRun on = restingStack(true);
  const StackRun off = restingStack(false);
  std::printf("stack: energy rise on %.3e J off %.3e J, max speed on %.3e off %.3e m/s\n",
              on.energyRise, off.energyRise, on.speedMax, off.speedMax);
  // The solver's tolerance (1e-6 relative) lets the energy of 196 J wander by ~1e-7 J either
  // way, the same with and without the option.
  EXPECT_LT(on.energyRise, 1e-6);
  EXPECT_NEAR(on.energyRise, off.energyRise, 1e-9);
  EXPECT_LT(on.speedMax, 1e-5);
}

}  // namespace
}  // namespace coulomb::engine
