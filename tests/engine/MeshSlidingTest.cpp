// A box sliding across a flat triangulated floor meets no internal edges (geometry/MeshEdges):
// over a 2-triangle and a 200-triangle top face it keeps its height to 1e-6 m and its speed as on
// a plane, step by step, while it crosses the triangles' diagonals and grid lines.
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace coulomb;
using geometry::BodyId;

namespace {

// A closed slab whose top face (z = 0) is an n x n grid of 2 n^2 triangles, 0.2 m thick.
geometry::TriangleMesh gridSlab(int n, double half) {
  geometry::TriangleMesh mesh;
  auto index = [n](int layer, int i, int j) { return layer * (n + 1) * (n + 1) + i * (n + 1) + j; };
  for (int layer = 0; layer < 2; ++layer)
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j)
        mesh.vertices.emplace_back(-half + 2.0 * half * i / n, -half + 2.0 * half * j / n,
                                   layer == 0 ? 0.0 : -0.2);
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
    const int t0 = index(0, i0, j0), t1 = index(0, i1, j1), b0 = index(1, i0, j0),
              b1 = index(1, i1, j1);
    mesh.triangles.push_back({b0, b1, t1});
    mesh.triangles.push_back({b0, t1, t0});
  }
  return mesh;
}

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
