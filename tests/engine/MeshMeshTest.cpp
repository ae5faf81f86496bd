// A triangle-mesh body dropped on a triangle-mesh terrain lands and rests (mesh against mesh,
// triangle pairs: geometry/NarrowPhase.cpp, docs/collision.md): tilted 0.3 rad, its lowest
// corner 0.27 m up, it settles flat on its face at the analytic height and stays there.
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>

#include <Eigen/Geometry>

#include <cmath>

#include "bench/ShapeFixtures.hpp"

using namespace coulomb;
using samples::gridSlab;

TEST(MeshMesh, TiltedMeshBodyDroppedOnAMeshTerrainLandsAndRestsFlat) {
  engine::World world;
  engine::BodyDesc terrain;
  terrain.name = "terrain";
  terrain.motionType = geometry::MotionType::Static;
  terrain.shapes.push_back({gridSlab(10, 2.0, 0.2), {}, {0.6, 0.0}, {}});
  world.createBody(terrain);
  // A 0.4 x 0.4 x 0.2 block as a 12-triangle mesh (its shape frame has the top at z = 0; the
  // body's pose is that of its centre of mass, 0.1 below the top).
  engine::BodyDesc block;
  block.name = "block";
  block.pose = {Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 1, 0).normalized())),
                {0.3, -0.2, 0.45}};
  block.shapes.push_back({gridSlab(1, 0.2, 0.2), {}, {0.6, 0.0}, {}});
  const geometry::BodyId id = world.createBody(block);
  double lowest = 1.0;
  for (int k = 0; k < 300; ++k) {
    world.step(0.01);
    ASSERT_TRUE(world.pose(id).position.allFinite());
    lowest = std::min(lowest, world.pose(id).position.z());
  }
  const geometry::Pose rest = world.pose(id);
  // Flat on its bottom face: body z axis up, centre of mass 0.1 above the terrain's top (z = 0).
  EXPECT_GT((rest.rotation * Eigen::Vector3d::UnitZ()).z(), 1.0 - 1e-6);
  EXPECT_NEAR(rest.position.z(), 0.1, 1e-4);
  EXPECT_GT(lowest, 0.1 - 5e-3);  // it never sank into the terrain
  EXPECT_LT(world.linearVelocity(id).norm(), 1e-3);
  for (int k = 0; k < 100; ++k) world.step(0.01);
  EXPECT_LT((world.pose(id).position - rest.position).norm(), 1e-6);  // and stays there
}
