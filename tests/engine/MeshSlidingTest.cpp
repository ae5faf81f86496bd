// A box sliding across a flat triangulated floor meets no internal edges (geometry/MeshEdges):
// over a 2-triangle and a 200-triangle top face it keeps its height to 1e-6 m and its speed as on
// a plane, step by step, while it crosses the triangles' diagonals and grid lines.
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bench/ShapeFixtures.hpp"

using namespace coulomb;
using geometry::BodyId;
using samples::gridSlab;

namespace {

struct Track {
  std::vector<Eigen::Vector3d> positions, velocities;
};

// A 0.2 m cube of 1 kg launched at (2.0, 0.6) m/s on mu = 0.3, 60 steps of 0.01 s (it stops
// after ~0.71 s), on a plane or on the slab.
Track slide(const geometry::Shape& floorShape) {
  engine::WorldSettings settings;
  settings.solve.options.tolerance = 1e-10;  // both runs solved to round-off: compared to 1e-6
  engine::World world(settings);
  engine::BodyDesc floor;
  floor.name = "floor";
  floor.motionType = geometry::MotionType::Static;
  floor.shapes.push_back({floorShape, {}, {0.3, 0.0}, {}});
  world.createBody(floor);
  engine::BodyDesc box;
  box.name = "box";
  box.pose.position = {-1.3, -0.9, 0.1};
  box.linearVelocity = {2.0, 0.6, 0.0};
  box.shapes.push_back({geometry::Box{Eigen::Vector3d::Constant(0.1)}, {}, {0.3, 0.0}, {}});
  box.mass = geometry::SpatialInertia{1.0, Eigen::Vector3d::Zero(),
                                      Eigen::Matrix3d::Identity() * 8.0 * 0.01 / 12.0};
  const BodyId id = world.createBody(box);
  Track track;
  for (int k = 0; k < 60; ++k) {
    world.step(0.01);
    track.positions.push_back(world.pose(id).position);
    track.velocities.push_back(world.linearVelocity(id));
  }
  return track;
}

class MeshSliding : public ::testing::TestWithParam<int> {};

}  // namespace

TEST_P(MeshSliding, KeepsItsHeightAndSpeedAsOnAPlane) {
  const Track plane = slide(geometry::Plane{});
  const Track mesh = slide(gridSlab(GetParam(), 2.0));
  double travelled = 0.0, height = 0.0, speed = 0.0;
  for (std::size_t k = 0; k < plane.positions.size(); ++k) {
    height = std::max(height, std::abs(mesh.positions[k].z() - 0.1));
    speed = std::max(speed, (mesh.velocities[k] - plane.velocities[k]).norm());
    EXPECT_NEAR(mesh.positions[k].z(), 0.1, 1e-6) << "step " << k;
    EXPECT_NEAR(plane.positions[k].z(), 0.1, 1e-6) << "step " << k;
    EXPECT_LT((mesh.velocities[k] - plane.velocities[k]).norm(), 1e-6) << "step " << k;
    EXPECT_LT((mesh.positions[k] - plane.positions[k]).norm(), 1e-6) << "step " << k;
    if (k > 0) travelled += (plane.positions[k] - plane.positions[k - 1]).norm();
  }
  std::printf("%d triangles: height error %.2e m, speed difference to the plane %.2e m/s\n",
              2 * GetParam() * GetParam(), height, speed);
  EXPECT_GT(travelled, 0.65);  // across the diagonal of the 2-triangle face, 2 cells of the grid
}

INSTANTIATE_TEST_SUITE_P(Floors, MeshSliding, ::testing::Values(1, 10), [](const auto& info) {
  return std::to_string(2 * info.param * info.param) + "_triangles";
});
