// A ball running round the inside of a faceted drum (samples::ringWall, no gravity) keeps its
// speed: the contact keeps its identity from triangle to triangle of the smooth patch
// (MeshSurface), so elastic turning reflects the facets' turning (docs/tuning.md "Triangle
// meshes"). Without it every facet was a new point and an inelastic impact: 13 % of the kinetic
// energy per turn with 256 facets. The drums here turn by about the step's own turning per facet
// (v h / (R - rho) = 1.3 degrees, a facet 1.4 or 0.7 degrees); coarser facets are corners
// (docs/tuning.md gives the figures).
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "bench/ShapeFixtures.hpp"

using namespace coulomb;

namespace {

struct Lap {
  double turns = 0.0;        // angle travelled by the centre / 2 pi
  double energyRatio = 0.0;  // kinetic energy at the end / at the start
  double worstOffset = 0.0;  // largest |distance of the centre from the wall's circle - ρ| [m]
};

constexpr double kWallRadius = 1.0, kBallRadius = 0.1, kSpeed = 2.0;

// A 1 kg ball of radius 0.1 m starts in the middle of a facet, touching it, at 2 m/s along the
// wall; `rolling`: spinning as a ball rolling on the wall, with friction 0.5 (else frictionless).
Lap run(int facets, bool rolling, int steps) {
  engine::World world;
  world.setGravity(Eigen::Vector3d::Zero());
  const double friction = rolling ? 0.5 : 0.0;
  engine::BodyDesc drum;
  drum.name = "drum";
  drum.motionType = geometry::MotionType::Static;
  drum.shapes.push_back(
      {samples::ringWall(facets, kWallRadius, kWallRadius + 0.2, 0.4), {}, {friction, 0.0}, {}});
  world.createBody(drum);
  const double half = std::numbers::pi / facets;  // the facet's middle, at its plane
  const double centre = kWallRadius * std::cos(half) - kBallRadius;
  const Eigen::Vector3d radial(std::cos(half), std::sin(half), 0.0);
  const Eigen::Vector3d along(-std::sin(half), std::cos(half), 0.0);
  engine::BodyDesc ball;
  ball.name = "ball";
  ball.pose.position = centre * radial;
  ball.linearVelocity = kSpeed * along;
  // Rolling on the wall: the contact point (outward, at +ρ radial) at rest.
  if (rolling) ball.angularVelocity = -kSpeed / kBallRadius * radial.cross(along);
  ball.shapes.push_back({geometry::Sphere{kBallRadius}, {}, {friction, 0.0}, {}});
  const double inertia = 0.4 * kBallRadius * kBallRadius;
  ball.mass =
      geometry::SpatialInertia{1.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity() * inertia};
  const geometry::BodyId id = world.createBody(ball);
  auto kinetic = [&] {
    return 0.5 * world.linearVelocity(id).squaredNorm() +
           0.5 * inertia * world.angularVelocity(id).squaredNorm();
  };
  const double start = kinetic();
  Lap lap;
  double angle = std::atan2(ball.pose.position.y(), ball.pose.position.x());
  for (int k = 0; k < steps; ++k) {
    world.step(0.01);
    const Eigen::Vector3d p = world.pose(id).position;
    const double next = std::atan2(p.y(), p.x());
    lap.turns += std::remainder(next - angle, 2.0 * std::numbers::pi) / (2.0 * std::numbers::pi);
    angle = next;
    // Between the inscribed polygon's facets (R cos(pi/N)) and its vertices (R).
    const double offset = kWallRadius - kBallRadius - p.head<2>().norm();
    lap.worstOffset = std::max(lap.worstOffset, std::abs(offset));
  }
  lap.energyRatio = kinetic() / start;
  return lap;
}

}  // namespace

class MeshTurning : public ::testing::TestWithParam<std::tuple<int, bool>> {};

TEST_P(MeshTurning, BallKeepsItsSpeedRoundAFacetedDrum) {
  const auto [facets, rolling] = GetParam();
  const Lap lap = run(facets, rolling, 900);
  const double lossPerTurn = 1.0 - std::pow(lap.energyRatio, 1.0 / lap.turns);
  std::printf(
      "%d facets, %s: %.2f turns, kinetic energy x %.4f, loss per turn %.2f %%, "
      "largest offset from the circle %.1e m\n",
      facets, rolling ? "rolling" : "frictionless", lap.turns, lap.energyRatio, 100.0 * lossPerTurn,
      lap.worstOffset);
  EXPECT_GT(lap.turns, 2.5);
  EXPECT_LT(lossPerTurn, 0.02);
  EXPECT_LT(lap.energyRatio, 1.0 + 1e-9);  // the turning never adds energy
  // It stays on the wall: within the polygon's sag R (1 - cos(pi / N)) and the slop.
  EXPECT_LT(lap.worstOffset, kWallRadius * (1.0 - std::cos(std::numbers::pi / facets)) + 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Drums, MeshTurning,
                         ::testing::Combine(::testing::Values(256, 512), ::testing::Bool()),
                         [](const auto& info) {
                           return std::to_string(std::get<0>(info.param)) + "_facets_" +
                                  (std::get<1>(info.param) ? "rolling" : "frictionless");
                         });
