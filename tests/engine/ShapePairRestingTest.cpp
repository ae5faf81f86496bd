// Every convex pair rests on a full manifold from its first step (issue: cylinder-box,
// cylinder-cylinder, cylinder-capsule, capsule-hull, cylinder-hull and hull-mesh got one FCL
// point and rested on persistence alone; mesh-mesh was refused): placed exactly touching, the top
// body stays within 1e-6 m over 1 000 steps and the normal impulses carry its weight on every step,
// as for box-box (WorldContactTest.RestingBox). Meshes come from geometry code here;
// docs/collision.md lists the pairs.
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>

#include "bench/ShapeFixtures.hpp"

using namespace coulomb;
using geometry::BodyId;
using samples::boxHull;
using samples::gridSlab;

namespace {

constexpr double kG = 9.81;

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
      // Overhanging the slab's edge by 0.1 m: its side triangles are near and must not push.
      {"hull_overhanging_a_mesh_edge", gridSlab(10, 1.0), geometry::Pose::identity(),
       boxHull({0.2, 0.15, 0.1}), geometry::Pose::translation({0.9, 0.3, 0.1}), 3},
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
