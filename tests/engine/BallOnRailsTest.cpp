// A spinning ball on two parallel rails of static capsules (docs/scene-specifications.md B11's
// contact geometry on a straight track): the spin turns into rolling at the analytic speed and
// time, whether each rail is one capsule or a chain of 1 cm pieces, and a rolling ball keeps its
// kinetic energy over the capsule joints (no ghost contacts at the shared ends, no lift-off).
#include <coulomb/engine/World.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace coulomb::engine {
namespace {

constexpr double kRho = 0.1, kRail = 0.01, kWidth = 0.1, kMass = 1.0, kInertia = 0.004;
constexpr double kOmega0 = 180.0, kG = 9.81, kH = 0.01;
#ifdef COULOMB_SANITIZE
constexpr double kLength = 4.0;  // rails [m] from x = -1 (the slip test ends at x = 2.7 m)
#else
constexpr double kLength = 8.0;
#endif

// Ball centre height above the rail axes' plane and the rolling radius
// (docs/scene-specifications.md B11).
const double kHeight = std::sqrt((kRho + kRail) * (kRho + kRail) - kWidth * kWidth / 4);
const double kRhoEff = kRho * kHeight / (kRho + kRail);

struct Rig {
  World world;
  geometry::BodyId ball;
};

// Rails along x at y = +-w/2, z = 0, from x = -1 to kLength - 1, in pieces of `piece` metres.
std::unique_ptr<Rig> makeRig(double mu, double piece, const Eigen::Vector3d& v,
                             const Eigen::Vector3d& w) {
  WorldSettings settings;
  settings.solve.choice = coulomb::solvers::solverChoice("ac_newton");
  auto rig = std::make_unique<Rig>(Rig{World(settings), {}});
  BodyDesc rails;
  rails.motionType = geometry::MotionType::Static;
  const int pieces = static_cast<int>(std::lround(kLength / piece));
  const Eigen::Quaterniond alongX =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX());
  for (const double side : {1.0, -1.0})
    for (int j = 0; j < pieces; ++j)
      rails.shapes.push_back(
          {geometry::Capsule{kRail, piece / 2},
           {alongX, Eigen::Vector3d(-1.0 + (j + 0.5) * piece, side * kWidth / 2, 0.0)},
           {mu, 0.0},
           {}});
  rig->world.createBody(rails);
  BodyDesc ball;
  ball.pose.position = {0.0, 0.0, kHeight};
  ball.linearVelocity = v;
  ball.angularVelocity = w;
  ball.shapes.push_back({geometry::Sphere{kRho}, {}, {mu, 0.0}, {}});
  ball.mass = geometry::SpatialInertia{kMass, Eigen::Vector3d::Zero(),
                                       kInertia * Eigen::Matrix3d::Identity()};
  rig->ball = rig->world.createBody(ball);
  return rig;
}

// Slip to rolling on a straight: friction mu N / cos(beta) in all drives the ball and brakes the
// spin about the rolling radius; slip ends at t* = rho_eff w0 / (mu g / cos beta (1 + 1/k')) with
// v = rho_eff w0 k' / (1 + k'), k' = I / (m rho_eff^2) (docs/scene-specifications.md B11, reduced
// model).
void expectAnalyticRolling(double piece) {
  const double mu = 0.6, cosBeta = kHeight / (kRho + kRail);
  const double k = kInertia / (kMass * kRhoEff * kRhoEff);
  const double vRoll = kRhoEff * kOmega0 * k / (1 + k);  // 5.374 m/s
  const double tStar = kRhoEff * kOmega0 / (mu * kG / cosBeta * (1 + 1 / k));
  auto rig = makeRig(mu, piece, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, kOmega0, 0.0));
  double tRoll = -1.0;
  const int steps = static_cast<int>(std::ceil(tStar / kH)) + 10;
  for (int s = 1; s <= steps; ++s) {
    rig->world.step(kH);
    const Eigen::Vector3d v = rig->world.linearVelocity(rig->ball);
    const Eigen::Vector3d w = rig->world.angularVelocity(rig->ball);
    ASSERT_LT(std::abs(rig->world.pose(rig->ball).position.z() - kHeight), 1e-3) << "step " << s;
    ASSERT_LT(std::abs(v.y()), 1e-6) << "step " << s;
    if (tRoll < 0 && std::abs(w.y() * kRhoEff - v.x()) < 1e-6 * vRoll) tRoll = s * kH;
  }
  const Eigen::Vector3d v = rig->world.linearVelocity(rig->ball);
  EXPECT_NEAR(v.x(), vRoll, 0.01 * vRoll) << "piece " << piece;
  EXPECT_NEAR(rig->world.angularVelocity(rig->ball).y() * kRhoEff, vRoll, 0.01 * vRoll);
  EXPECT_NEAR(tRoll, tStar, 1.5 * kH) << "piece " << piece;
}

TEST(BallOnRails, SpinTurnsIntoRollingAtTheAnalyticSpeedOnOneCapsulePerRail) {
  expectAnalyticRolling(kLength);
}

TEST(BallOnRails, SpinTurnsIntoRollingAtTheAnalyticSpeedOnChainsOfShortCapsules) {
  expectAnalyticRolling(0.01);  // 1 cm pieces as the double loop's rails (5-12 mm)
}

TEST(BallOnRails, RollingOverCapsuleJointsKeepsItsKineticEnergy) {
  const double v0 = 5.0;
  auto rig =
      makeRig(0.6, 0.01, Eigen::Vector3d(v0, 0.0, 0.0), Eigen::Vector3d(0.0, v0 / kRhoEff, 0.0));
  const double e0 = rig->world.mechanicalEnergy();
  const int steps = static_cast<int>((kLength - 2.0) / v0 / kH);
  for (int s = 0; s < steps; ++s) {
    rig->world.step(kH);
    ASSERT_LT(std::abs(rig->world.pose(rig->ball).position.z() - kHeight), 1e-4) << "step " << s;
  }
  EXPECT_NEAR(rig->world.mechanicalEnergy(), e0, 1e-6 * e0);
  EXPECT_NEAR(rig->world.linearVelocity(rig->ball).x(), v0, 1e-6 * v0);
}

}  // namespace
}  // namespace coulomb::engine
