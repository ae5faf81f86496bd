// A triangle-mesh body dropped on a triangle-mesh terrain lands and rests (mesh against mesh,
// triangle pairs: geometry/NarrowPhase.cpp, docs/collision.md): tilted 0.3 rad, its lowest
// corner 0.27 m up, it settles flat on its face at the analytic height and stays there.
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>

#include <Eigen/Geometry>

#include <cmath>

using namespace coulomb;

namespace {

// A closed slab whose top face (z = 0) is an n x n grid of 2 n^2 triangles, `thickness` deep.
geometry::TriangleMesh gridSlab(int n, double half, double thickness) {
  geometry::TriangleMesh mesh;
  auto index = [n](int layer, int i, int j) { return layer * (n + 1) * (n + 1) + i * (n + 1) + j; };
  for (int layer = 0; layer < 2; ++layer)
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j)
        mesh.vertices.emplace_back(-half + 2.0 * half * i / n, -half + 2.0 * half * j / n,
                                   layer == 0 ? 0.0 : -thickness);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = index(0, i, j), b = index(0, i + 1, j), c = index(0, i + 1, j + 1),
                d = index(0, i, j + 1);
      mesh.triangles.push_back({a, b, c});
      mesh.triangles.push_back({a, c, d});
      const int e = index(1, i, j), f = index(1, i + 1, j), g = index(1, i + 1, j + 1),
                h = index(1, i, j + 1);
      mesh.triangles.push_back({e, g, f});
      mesh.triangles.push_back({e, h, g});
    }
  std::vector<std::pair<int, int>> ring;
  for (int i = 0; i < n; ++i) ring.emplace_back(i, 0);
  for (int j = 0; j < n; ++j) ring.emplace_back(n, j);
  for (int i = n; i > 0; --i) ring.emplace_back(i, n);
  for (int j = n; j > 0; --j) ring.emplace_back(0, j);
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const auto [i0, j0] = ring[k];
    const auto [i1, j1] = ring[(k + 1) % ring.size()];
    mesh.triangles.push_back({index(1, i0, j0), index(1, i1, j1), index(0, i1, j1)});
    mesh.triangles.push_back({index(1, i0, j0), index(0, i1, j1), index(0, i0, j0)});
  }
  return mesh;
}

}  // namespace

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
