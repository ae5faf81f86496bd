// Every convex pair rests on a full manifold from its first step (issue: cylinder-box,
// cylinder-cylinder, cylinder-capsule, capsule-hull, cylinder-hull and hull-mesh got one FCL
// point and rested on persistence alone; mesh-mesh was refused): placed exactly touching, the top
// body stays within 1e-6 m over 1 000 steps and the normal impulses carry its weight on every step,
// as for box-box (WorldContactTest.RestingBox). Meshes come from geometry code here;
// docs/collision.md lists the pairs.
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>
#include <coulomb/meshes/MakeConvexHull.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>

using namespace coulomb;
using geometry::BodyId;

namespace {

constexpr double kG = 9.81;

geometry::ConvexHull boxHull(const Eigen::Vector3d& half) {
  std::vector<Eigen::Vector3d> points;
  for (int c = 0; c < 8; ++c)
    points.emplace_back(c & 1 ? half.x() : -half.x(), c & 2 ? half.y() : -half.y(),
                        c & 4 ? half.z() : -half.z());
  return geometry::makeConvexHull(points);
}

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
      mesh.triangles.push_back({a, b, c});  // top: counter-clockwise seen from +z
      mesh.triangles.push_back({a, c, d});
      const int e = index(1, i, j), f = index(1, i + 1, j), g = index(1, i + 1, j + 1),
                h = index(1, i, j + 1);
      mesh.triangles.push_back({e, g, f});  // bottom: seen from -z
      mesh.triangles.push_back({e, h, g});
    }
  // Sides: the boundary of the top grid joined to the bottom's, walked counter-clockwise.
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

struct PairCase {
  std::string name;
  geometry::Shape base;  // static, pose given
  geometry::Pose basePose;
  geometry::Shape top;  // dynamic, placed exactly touching
  geometry::Pose topPose;
  std::size_t minPoints;  // points of the manifold from the first step
};

std::vector<PairCase> cases() {
  const double half = std::numbers::pi / 2;
  const auto lyingX = Eigen::Quaterniond(Eigen::AngleAxisd(half, Eigen::Vector3d::UnitY()));
  return {
      {"cylinder_on_box", geometry::Box{{1.0, 1.0, 0.1}}, geometry::Pose::identity(),
       geometry::Cylinder{0.2, 0.3}, geometry::Pose::translation({0.05, 0.0, 0.4}), 3},
      {"cylinder_lying_on_box",
       geometry::Box{{1.0, 1.0, 0.1}},
       geometry::Pose::identity(),
       geometry::Cylinder{0.2, 0.3},
       {lyingX, {0.0, 0.1, 0.3}},
       2},
      {"can_on_can", geometry::Cylinder{0.1, 0.2}, geometry::Pose::identity(),
       geometry::Cylinder{0.1, 0.2}, geometry::Pose::translation({0.0, 0.0, 0.4}), 3},
      {"capsule_across_cylinder",
       geometry::Cylinder{0.2, 0.2},
       geometry::Pose::identity(),
       geometry::Capsule{0.05, 0.5},
       {lyingX, {0.0, 0.0, 0.25}},
       2},
      {"capsule_lying_on_hull",
       boxHull({1.0, 1.0, 0.5}),
       geometry::Pose::identity(),
       geometry::Capsule{0.05, 0.3},
       {lyingX, {0.0, 0.0, 0.55}},
       2},
      {"cylinder_on_hull", boxHull({1.0, 1.0, 0.5}), geometry::Pose::identity(),
       geometry::Cylinder{0.2, 0.3}, geometry::Pose::translation({0.0, 0.1, 0.8}), 3},
      {"hull_on_mesh", gridSlab(1, 1.0), geometry::Pose::identity(), boxHull({0.2, 0.15, 0.1}),
       geometry::Pose::translation({0.1, 0.05, 0.1}), 3},
      {"hull_on_200_triangle_mesh", gridSlab(10, 1.0), geometry::Pose::identity(),
       boxHull({0.2, 0.15, 0.1}), geometry::Pose::translation({0.13, 0.07, 0.1}), 3},
      {"cylinder_on_mesh", gridSlab(10, 1.0), geometry::Pose::identity(),
       geometry::Cylinder{0.2, 0.3}, geometry::Pose::translation({0.0, 0.0, 0.3}), 3},
      // A 0.4 x 0.4 x 0.2 mesh slab (12 triangles, top at its z = 0) on the 200-triangle slab.
      {"mesh_on_mesh", gridSlab(10, 1.0), geometry::Pose::identity(), gridSlab(1, 0.2),
       geometry::Pose::translation({0.11, 0.07, 0.2}), 3},
  };
}

class ShapePairResting : public ::testing::TestWithParam<PairCase> {};

}  // namespace

TEST_P(ShapePairResting, StaysStillAndCarriesItsWeightFromTheFirstStep) {
  const PairCase& pair = GetParam();
  engine::WorldSettings settings;
  settings.solve.options.tolerance = 1e-10;  // the weight to 1e-9 needs an answer this exact
  settings.sleep.enabled = false;            // every step solved, none skipped
  engine::World world(settings);
  engine::BodyDesc base;
  base.name = "base";
  base.motionType = geometry::MotionType::Static;
  base.pose = pair.basePose;
  base.shapes.push_back({pair.base, {}, {0.5, 0.0}, {}});
  world.createBody(base);
  engine::BodyDesc top;
  top.name = "top";
  top.pose = pair.topPose;
  top.shapes.push_back({pair.top, {}, {0.5, 0.0}, {}});
  const BodyId body = world.createBody(top);
  const double weight = world.massProperties(body).mass * kG * 0.01;
  const Eigen::Vector3d start = world.pose(body).position;
  double worstLoad = 0.0;
  std::size_t firstPoints = 0;
  for (int k = 0; k < 1000; ++k) {
    world.step(0.01);
    ASSERT_EQ(world.contacts().size(), 1u) << "step " << k;
    const auto& manifold = world.contacts().front();
    if (k == 0) {
      firstPoints = manifold.activePoints().size();
      EXPECT_GE(firstPoints, std::min<std::size_t>(pair.minPoints, 4));
    }
    double normalImpulse = 0.0;
    for (const auto& p : manifold.activePoints()) normalImpulse += p.normalImpulse;
    worstLoad = std::max(worstLoad, std::abs(normalImpulse - weight) / weight);
    ASSERT_NEAR(normalImpulse, weight, 1e-8 * weight)
        << "step " << k;  // as RestingBox: 1e-9 of 0.1
  }
  const double drift = (world.pose(body).position - start).norm();
  std::printf("%s: %zu points in step 1, drift %.2e m after 1000 steps, load error %.2e\n",
              pair.name.c_str(), firstPoints, drift, worstLoad);
  EXPECT_LT(drift, 1e-6);
  EXPECT_LT(world.linearVelocity(body).norm(), 1e-8);
}

INSTANTIATE_TEST_SUITE_P(Pairs, ShapePairResting, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.name; });
