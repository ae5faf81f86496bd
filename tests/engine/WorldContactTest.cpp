// The step with contacts: analytic resting and friction cases (docs/scene-specifications.md A2,
// section 0 rules).
#include <gtest/gtest.h>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

using namespace coulomb;
using geometry::BodyId;

namespace {

constexpr double kG = 9.81;

BodyId addGround(engine::World& world, const Eigen::Quaterniond& rotation, double mu) {
  engine::BodyDesc ground;
  ground.name = "ground";
  ground.motionType = geometry::MotionType::Static;
  ground.pose.rotation = rotation;
  ground.shapes.push_back({geometry::Plane{}, {}, {mu, 0.0}, {}});
  return world.createBody(ground);
}

// docs/scene-specifications.md "box(h, m)": cube of half side h, I = m 8h^2/12 on every axis.
BodyId addBox(engine::World& world, const geometry::Pose& pose, double h, double m, double mu,
              const std::string& solver = "") {
  engine::BodyDesc box;
  box.name = "box";
  box.pose = pose;
  box.shapes.push_back({geometry::Box{Eigen::Vector3d::Constant(h)}, {}, {mu, 0.0}, {}});
  box.mass = geometry::SpatialInertia{m, Eigen::Vector3d::Zero(),
                                      Eigen::Matrix3d::Identity() * m * 8.0 * h * h / 12.0};
  if (!solver.empty()) box.solver = coulomb::solvers::solverChoice(solver);
  return world.createBody(box);
}

class RestingBox : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(RestingBox, StaysStillAndCarriesItsWeight) {
  engine::WorldSettings settings;
  settings.solve.choice = coulomb::solvers::solverChoice(GetParam());
  settings.solve.options.tolerance = 1e-10;  // the weight to 1e-9 needs an answer this exact
  engine::World world(settings);
  addGround(world, Eigen::Quaterniond::Identity(), 0.5);
  const BodyId box = addBox(world, geometry::Pose::translation({0, 0, 0.1}), 0.1, 1.0, 0.5);
  const Eigen::Vector3d start = world.pose(box).position;
  for (int k = 0; k < 1000; ++k) {
    const engine::StepReport report = world.step(0.01);
    ASSERT_EQ(report.islands.size(), 1u);
    const auto& island = report.islands.front();
    EXPECT_EQ(island.contacts, 4u) << "step " << k;
    EXPECT_LE(island.solve.residual, 1e-10) << "step " << k << ": " << island.solve.message;
    double normalImpulse = 0.0;
    for (const auto& m : world.contacts())
      for (const auto& p : m.activePoints()) normalImpulse += p.normalImpulse;
    ASSERT_NEAR(normalImpulse, 1.0 * kG * 0.01, 1e-9) << "step " << k;
  }
  EXPECT_LT((world.pose(box).position - start).norm(), 1e-6);
  EXPECT_LT(world.linearVelocity(box).norm(), 1e-9);
}

INSTANTIATE_TEST_SUITE_P(EverySolver, RestingBox,
                         ::testing::Values("auto", "pgs", "bgs", "ac_newton"));

TEST(WorldContact, BoxOnInclineBelowFrictionAngleDoesNotCreep) {
  // docs/scene-specifications.md A2 A_stick: 20 degree incline, mu = tan 20 + 0.05, 1 kg box, h =
  // 0.1.
  const double angle = 20.0 * std::numbers::pi / 180.0;
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()));
  const double mu = std::tan(angle) + 0.05;
  engine::World world;
  addGround(world, tilt, mu);
  const Eigen::Vector3d n = tilt * Eigen::Vector3d::UnitZ();
  geometry::Pose pose{tilt, 0.1 * n};
  const BodyId box = addBox(world, pose, 0.1, 1.0, mu);
  for (int k = 0; k < 1000; ++k) world.step(0.01);
  EXPECT_LT((world.pose(box).position - 0.1 * n).norm(), 1e-6);
}

TEST(WorldContact, BoxOnInclineAboveFrictionAngleSlidesAtTheCoulombAcceleration) {
  // docs/scene-specifications.md A2 B_slide: mu = tan 20 - 0.1, a = g (sin 20 - mu cos 20) =
  // 0.9218385 m/s^2.
  const double angle = 20.0 * std::numbers::pi / 180.0;
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()));
  const double mu = std::tan(angle) - 0.1;
  engine::World world;
  addGround(world, tilt, mu);
  const Eigen::Vector3d n = tilt * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d downhill = tilt * Eigen::Vector3d::UnitX();
  const BodyId box = addBox(world, geometry::Pose{tilt, 0.1 * n}, 0.1, 1.0, mu);
  double v05 = 0.0;
  for (int k = 1; k <= 200; ++k) {
    world.step(0.01);
    if (k == 50) v05 = world.linearVelocity(box).dot(downhill);
  }
  const double acceleration = (world.linearVelocity(box).dot(downhill) - v05) / 1.5;
  const double exact = kG * (std::sin(angle) - mu * std::cos(angle));
  EXPECT_NEAR(acceleration, exact, 1e-6 * exact);
}

TEST(WorldContact, PushAtAnAngleSlidesStraight) {
  // docs/scene-specifications.md A2 C_flat_22.5deg: the exact cone keeps the direction (pyramids
  // bend it 13.5 deg).
  engine::World world;
  addGround(world, Eigen::Quaterniond::Identity(), 0.5);
  const BodyId box = addBox(world, geometry::Pose::translation({0, 0, 0.1}), 0.1, 1.0, 0.5);
  const double a = 22.5 * std::numbers::pi / 180.0;
  world.setVelocity(box, {std::cos(a), std::sin(a), 0.0}, Eigen::Vector3d::Zero());
  for (int k = 0; k < 100; ++k) world.step(0.01);
  const Eigen::Vector3d p = world.pose(box).position;
  EXPECT_NEAR(std::atan2(p.y(), p.x()), a, 1e-6);
  // Discrete floor at dt 0.01: stop distance 0.096995 m (docs/scene-specifications.md A2).
  EXPECT_NEAR(std::hypot(p.x(), p.y()), 0.096995, 1e-5);
  EXPECT_LT(world.linearVelocity(box).norm(), 1e-9);
}

TEST(WorldContact, UnknownSolverIsRejected) {
  engine::WorldSettings settings;
  settings.solve.choice = coulomb::solvers::solverChoice("no_such_solver");
  EXPECT_THROW(engine::World world(settings), engine::CoulombError);
  engine::World world;
  EXPECT_THROW(world.setSolver(coulomb::solvers::solverChoice("nope")), engine::CoulombError);
  // A bad policy is refused whole and leaves the world's as it was.
  coulomb::solvers::SolvePolicy bad = world.settings().solve;
  bad.options.tolerance = -1.0;
  EXPECT_THROW(world.setSolvePolicy(bad), engine::CoulombError);
  EXPECT_EQ(world.settings().solve.options.tolerance,
            engine::WorldSettings{}.solve.options.tolerance);
}

// The split impulse is a stage of its own with a kept report (docs/architecture.md "The step"):
// an island that penetrates beyond the slop is corrected and its stage is timed; an island that
// does not has nothing to do and reports none (its clock is not read).
TEST(WorldContact, SplitImpulseReportsOnlyIslandsThatPenetrate) {
  for (const double depth : {0.005, 0.0}) {
    engine::World world;
    addGround(world, Eigen::Quaterniond::Identity(), 0.5);
    geometry::Pose pose;
    pose.position = {0, 0, 0.1 - depth};
    addBox(world, pose, 0.1, 1.0, 0.5);
    const engine::StepReport& report = world.step(0.01);
    ASSERT_EQ(report.islands.size(), 1u);
    if (depth > 0) {
      ASSERT_TRUE(report.islands[0].penetration.has_value());
      EXPECT_GT(report.penetrationStageSeconds, 0.0);
    } else {
      EXPECT_FALSE(report.islands[0].penetration.has_value());
      EXPECT_EQ(report.penetrationStageSeconds, 0.0);
    }
  }
}
