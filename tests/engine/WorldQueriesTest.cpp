// Scene queries on a live World: they see the bodies where the last step left them (a ray
// follows a falling box to the millimetre of its pose), a sphere cast lands on the resting box,
// overlaps and closest points agree with the resting contact, and removed bodies disappear.
#include <coulomb/engine/WorldQueries.hpp>

#include <coulomb/engine/CoulombError.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace coulomb::engine {
namespace {

using Eigen::Vector3d;
using geometry::BodyId;
using geometry::ColliderId;

BodyId addGround(World& world) {
  BodyDesc ground;
  ground.name = "ground";
  ground.motionType = geometry::MotionType::Static;
  ground.shapes.push_back({geometry::Plane{}, {}, {}, {}});
  return world.createBody(ground);
}

BodyId addBox(World& world, const Vector3d& at, double h) {
  BodyDesc box;
  box.pose.position = at;
  box.shapes.push_back({geometry::Box{Vector3d::Constant(h)}, {}, {}, {}});
  return world.createBody(box);
}

ColliderId colliderOf(const World& world, BodyId body) {
  for (const geometry::Collider& c : world.colliders())
    if (c.body == body) return c.id;
  return {};
}

TEST(WorldQueries, RayFollowsAFallingBoxStepByStep) {
  World world;
  addGround(world);
  const BodyId box = addBox(world, {0.3, -0.2, 2.0}, 0.1);
  WorldQueries queries(world);
  for (int step = 0; step < 120; ++step) {
    world.step(0.01);
    const auto hit = queries.castRay({0.3, -0.2, 5.0}, {0, 0, -10});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, box);
    const double top = world.pose(box).position.z() + 0.1;
    // The box may tilt a little after landing; before, its top face is exactly level.
    EXPECT_NEAR(hit->point.z(), top, step < 60 ? 1e-12 : 1e-6) << "step " << step;
    EXPECT_NEAR(hit->normal.z(), 1.0, 1e-6);
  }
  // Resting on the floor: the top at 0.2 m (within the speculative contact's millimetre).
  EXPECT_NEAR(queries.castRay({0.3, -0.2, 5.0}, {0, 0, -10})->point.z(), 0.2, 1e-3);
}

TEST(WorldQueries, ShapeCastOverlapAndClosestPointsOnARestingBox) {
  World world;
  const BodyId ground = addGround(world);
  const BodyId box = addBox(world, {0, 0, 0.1}, 0.1);
  for (int step = 0; step < 50; ++step) world.step(0.01);
  WorldQueries queries(world);
  const auto ball = std::make_shared<const geometry::Shape>(geometry::Sphere{0.05});
  const auto hit = queries.castShape(ball, geometry::Pose::translation({0, 0, 1}), {0, 0, -2});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->body, box);
  const double top = world.pose(box).position.z() + 0.1;
  EXPECT_NEAR(1.0 - 2.0 * hit->fraction - 0.05, top, 1e-5);  // the ball's bottom meets the top
  EXPECT_EQ(queries.overlap(ball, geometry::Pose::translation({0, 0, 0.1})),
            (std::vector<ColliderId>{colliderOf(world, box)}));
  const geometry::ClosestPoints gap =
      queries.closestPoints(colliderOf(world, ground), colliderOf(world, box));
  EXPECT_LT(std::abs(gap.distance), 1e-3);  // resting: touching within the contact tolerance
  world.removeBody(box);
  EXPECT_EQ(queries.castRay({0, 0, 1}, {0, 0, -2})->body, ground);
  EXPECT_THROW(static_cast<void>(queries.closestPoints(colliderOf(world, ground), hit->collider)),
               CoulombError);
  EXPECT_THROW(static_cast<void>(queries.castRay({0, 0, std::nan("")}, {0, 0, -1})), CoulombError);
}

}  // namespace
}  // namespace coulomb::engine
