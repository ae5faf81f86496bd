// Scene queries over many colliders: the tree's candidates never lose a hit (ray casts equal the
// brute-force minimum over every collider), shape casts stop at the analytic time of impact,
// overlaps, AABB queries, closest points, filters, and sync() following a changing scene.
#include <coulomb/geometry/SceneQuery.hpp>

#include <coulomb/geometry/RayCast.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace coulomb::geometry {
namespace {

using Eigen::Vector3d;

struct Scene {
  std::vector<Collider> colliders;
  std::vector<Pose> bodies;

  ColliderId add(Shape shape, const Pose& pose, CollisionFilter filter = {}) {
    const auto index = static_cast<std::uint32_t>(bodies.size());  // ids never reused here
    Collider c;
    c.id = ColliderId{index, 1};
    c.body = BodyId{index, 1};
    c.shape = std::make_shared<const Shape>(std::move(shape));
    c.filter = filter;
    colliders.push_back(c);
    bodies.push_back(pose);
    return c.id;
  }
  SceneQuery synced() const {
    SceneQuery q;
    q.sync(colliders, bodies);
    return q;
  }
};

std::shared_ptr<const Shape> sphere(double r) {
  return std::make_shared<const Shape>(Sphere{r});
}
std::shared_ptr<const Shape> box(const Vector3d& h) {
  return std::make_shared<const Shape>(Box{h});
}

Scene randomScene(unsigned seed, int count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Scene scene;
  scene.add(Plane{}, Pose::translation({0, 0, -5}));
  for (int k = 0; k < count; ++k) {
    const Pose pose{
        Eigen::Quaterniond(Eigen::AngleAxisd(3 * u(rng), Vector3d(u(rng), u(rng), 1).normalized())),
        4.0 * Vector3d(u(rng), u(rng), u(rng))};
    switch (k % 4) {
      case 0:
        scene.add(Sphere{0.2 + 0.1 * u(rng)}, pose);
        break;
      case 1:
        scene.add(Box{Vector3d(0.3, 0.2, 0.1)}, pose);
        break;
      case 2:
        scene.add(Capsule{0.1, 0.3}, pose);
        break;
      default:
        scene.add(Cylinder{0.2, 0.15}, pose);
        break;
    }
  }
  return scene;
}

TEST(SceneQuery, RayCastsEqualTheBruteForceMinimumOverEveryCollider) {
  const Scene scene = randomScene(7, 300);
  const SceneQuery query = scene.synced();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int hits = 0;
  for (int k = 0; k < 300; ++k) {
    const Vector3d origin = 6.0 * Vector3d(u(rng), u(rng), u(rng));
    const Vector3d translation = 12.0 * Vector3d(u(rng), u(rng), u(rng));
    std::vector<RayHit> expected;
    for (std::size_t c = 0; c < scene.colliders.size(); ++c) {
      const auto hit = rayCastShape(*scene.colliders[c].shape, scene.bodies[c], origin,
                                    translation.normalized(), translation.norm());
      if (hit)
        expected.push_back({scene.colliders[c].id, scene.colliders[c].body, Vector3d::Zero(),
                            hit->normal, hit->distance / translation.norm()});
    }
    std::stable_sort(expected.begin(), expected.end(),
                     [](const RayHit& a, const RayHit& b) { return a.fraction < b.fraction; });
    const std::vector<RayHit> all = query.castRayAll(origin, translation);
    ASSERT_EQ(all.size(), expected.size()) << "ray " << k;
    for (std::size_t h = 0; h < all.size(); ++h) {
      EXPECT_EQ(all[h].collider, expected[h].collider);
      EXPECT_NEAR(all[h].fraction, expected[h].fraction, 1e-12);  // rotations renormalised
      EXPECT_NEAR((all[h].point - (origin + all[h].fraction * translation)).norm(), 0, 1e-12);
    }
    const auto first = query.castRay(origin, translation);
    ASSERT_EQ(first.has_value(), !expected.empty());
    if (first) {
      ++hits;
      EXPECT_EQ(first->collider, expected.front().collider);
    }
  }
  EXPECT_GT(hits, 100);
}

TEST(SceneQuery, FiltersAndPredicateChooseWhatARaySees) {
  Scene scene;
  const ColliderId near =
      scene.add(Box{Vector3d(1, 1, 0.1)}, Pose::translation({0, 0, 1}), {2u, ~0u});
  const ColliderId far = scene.add(Box{Vector3d(1, 1, 0.1)}, Pose::translation({0, 0, 0}));
  const SceneQuery query = scene.synced();
  EXPECT_EQ(query.castRay({0, 0, 3}, {0, 0, -5})->collider, near);
  QueryFilter onlyDefault;
  onlyDefault.bits.mask = 1u;  // sees category 1 only: the near box (category 2) is skipped
  EXPECT_EQ(query.castRay({0, 0, 3}, {0, 0, -5}, onlyDefault)->collider, far);
  QueryFilter notFar;
  notFar.accept = [far](const Collider& c) { return c.id != far; };
  EXPECT_EQ(query.castRayAll({0, 0, 3}, {0, 0, -5}, notFar).size(), 1u);
  onlyDefault.accept = notFar.accept;
  EXPECT_FALSE(query.castRay({0, 0, 3}, {0, 0, -5}, onlyDefault));
}

TEST(SceneQuery, ShapeCastsStopAtTheAnalyticTimeOfImpact) {
  Scene scene;
  const ColliderId block = scene.add(Box{Vector3d(1, 1, 1)}, Pose::identity());
  const ColliderId floor = scene.add(Plane{}, Pose::translation({0, 0, -2}));
  const SceneQuery query = scene.synced();
  // Straight down onto the top face: the ball's bottom (3 - 0.5) meets z = 1 after 1.5 of 5 m.
  auto hit = query.castShape(sphere(0.5), Pose::translation({0, 0, 3}), {0, 0, -5});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->collider, block);
  EXPECT_NEAR(hit->fraction, 0.3, 1e-6);
  EXPECT_NEAR(hit->point.z(), 1.0, 1e-5);
  EXPECT_NEAR((hit->normal - Vector3d::UnitZ()).norm(), 0, 1e-4);
  // Over the top edge x = -1, z = 1 at height 1.4: touches when (x + 1)^2 + 0.4^2 = 0.5^2, i.e. at
  // x = -1.3, after 1.7 of 6 m; the normal points from the edge to the centre.
  hit = query.castShape(sphere(0.5), Pose::translation({-3, 0, 1.4}), {6, 0, 0});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->fraction, 1.7 / 6, 1e-6);
  EXPECT_NEAR((hit->normal - Vector3d(-0.6, 0, 0.8)).norm(), 0, 1e-4);
  // A box sliding into the side face, turned about z: its corner leads.
  const Pose turned{Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitZ())), {-4, 0, 0}};
  hit = query.castShape(box(Vector3d(0.5, 0.5, 0.5)), turned, {4, 0, 0});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->fraction, (4 - 1 - 0.5 * std::sqrt(2.0)) / 4, 1e-6);
  // Down past the block onto the floor plane (analytic), and a cast moving away from everything.
  hit = query.castShape(sphere(0.25), Pose::translation({3, 0, 0}), {0, 0, -4});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->collider, floor);
  EXPECT_NEAR(hit->fraction, 1.75 / 4, 1e-12);
  EXPECT_FALSE(query.castShape(sphere(0.25), Pose::translation({3, 0, 0}), {0, 0, 4}));
  EXPECT_FALSE(query.castShape(sphere(0.25), Pose::translation({-3, 0, 1.4}), {-6, 0, 0}));
  // Starting inside the block: fraction 0.
  hit = query.castShape(sphere(0.25), Pose::translation({0, 0, 0.9}), {0, 0, 4});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->fraction, 0.0);
}

TEST(SceneQuery, ShapeCastOntoATriangleMeshFloor) {
  Scene scene;
  scene.add(TriangleMesh{{{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, {0, 0, -1}},
                         {{0, 1, 2}, {0, 2, 3}, {1, 0, 4}, {2, 1, 4}, {3, 2, 4}, {0, 3, 4}}},
            Pose::identity());
  const auto hit =
      scene.synced().castShape(sphere(0.5), Pose::translation({0.3, 0.2, 2}), {0, 0, -3});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->fraction, 0.5, 1e-6);
}

TEST(SceneQuery, OverlapAabbAndClosestPoints) {
  Scene scene;
  const ColliderId a = scene.add(Sphere{0.5}, Pose::translation({0, 0, 0}));
  const ColliderId b = scene.add(Sphere{0.5}, Pose::translation({2, 0, 0}));
  const ColliderId c = scene.add(Box{Vector3d(0.5, 0.5, 0.5)}, Pose::translation({0, 3, 0}));
  const ColliderId ground = scene.add(Plane{}, Pose::translation({0, 0, -1}));
  const SceneQuery query = scene.synced();
  EXPECT_EQ(query.overlap(sphere(0.6), Pose::translation({1, 0, 0})),
            (std::vector<ColliderId>{a, b}));
  EXPECT_EQ(query.overlap(sphere(0.3), Pose::translation({0, 0, -0.9})),
            (std::vector<ColliderId>{ground}));
  EXPECT_TRUE(query.overlap(sphere(0.2), Pose::translation({0, 1.5, 0})).empty());
  EXPECT_EQ(query.queryAabb({Vector3d(-0.1, 2.4, -0.1), Vector3d(0.1, 2.6, 0.1)}),
            (std::vector<ColliderId>{c}));
  ClosestPoints p = query.closestPoints(a, b);
  EXPECT_NEAR(p.distance, 1.0, 1e-6);
  EXPECT_NEAR((p.pointA - Vector3d(0.5, 0, 0)).norm(), 0, 1e-5);
  EXPECT_NEAR((p.pointB - Vector3d(1.5, 0, 0)).norm(), 0, 1e-5);
  p = query.closestPoints(ground, c);  // the box's bottom face is 1.5 above z = -1
  EXPECT_NEAR(p.distance, 0.5, 1e-12);
  EXPECT_NEAR(p.pointA.z(), -1.0, 1e-12);
  p = query.closestPoints(a, ground);  // the ball's bottom (z = -0.5) is 0.5 above the floor
  EXPECT_NEAR(p.distance, 0.5, 1e-12);
  EXPECT_NEAR((p.pointA - Vector3d(0, 0, -0.5)).norm(), 0, 1e-12);
  EXPECT_NEAR((p.pointB - Vector3d(0, 0, -1)).norm(), 0, 1e-12);
  EXPECT_THROW(static_cast<void>(query.closestPoints(a, ColliderId{99, 1})), std::invalid_argument);
}

TEST(SceneQuery, OverlappingCollidersReportPenetrationAsNegativeDistance) {
  Scene scene;
  const ColliderId a = scene.add(Sphere{0.5}, Pose::translation({0, 0, 0}));
  const ColliderId b = scene.add(Sphere{0.5}, Pose::translation({0.8, 0, 0}));
  EXPECT_NEAR(scene.synced().closestPoints(a, b).distance, -0.2, 1e-6);
}

TEST(SceneQuery, SyncFollowsMovedAddedRemovedAndBrokenColliders) {
  Scene scene;
  scene.add(Sphere{0.5}, Pose::translation({0, 0, 0}));
  const ColliderId second = scene.add(Sphere{0.5}, Pose::translation({5, 0, 0}));
  SceneQuery query;
  query.sync(scene.colliders, scene.bodies);
  EXPECT_EQ(query.castRayAll({-2, 0, 0}, {10, 0, 0}).size(), 2u);
  scene.bodies[1].position = {5, 3, 0};  // moved out of the ray: the fast path (poses only)
  query.sync(scene.colliders, scene.bodies);
  EXPECT_EQ(query.castRayAll({-2, 0, 0}, {10, 0, 0}).size(), 1u);
  EXPECT_EQ(query.castRay({5, -2, 0}, {0, 10, 0})->collider, second);
  scene.bodies[0].position.x() = std::nan("");  // a broken pose: left out, no throw
  query.sync(scene.colliders, scene.bodies);
  EXPECT_TRUE(query.castRayAll({-2, 0, 0}, {10, 0, 0}).empty());
  scene.colliders.erase(scene.colliders.begin());                         // removed
  scene.add(Box{Vector3d(0.5, 0.5, 0.5)}, Pose::translation({2, 0, 0}));  // added
  query.sync(scene.colliders, scene.bodies);
  const auto hits = query.castRayAll({-2, 0, 0}, {10, 0, 0});
  ASSERT_EQ(hits.size(), 1u);
  EXPECT_NEAR(hits[0].fraction, 0.35, 1e-12);
}

TEST(SceneQuery, BadInputIsRefusedWithAClearMessage) {
  Scene scene;
  scene.add(Sphere{0.5}, Pose::identity());
  const SceneQuery query = scene.synced();
  EXPECT_THROW(static_cast<void>(query.castRay({std::nan(""), 0, 0}, {1, 0, 0})),
               std::invalid_argument);
  EXPECT_TRUE(query.castRayAll({0, 0, 0}, {0, 0, 0}).empty());  // zero length: nothing
  EXPECT_THROW(static_cast<void>(query.castShape(std::make_shared<const Shape>(Plane{}),
                                                 Pose::identity(), {1, 0, 0})),
               std::invalid_argument);
  EXPECT_THROW(static_cast<void>(query.overlap(sphere(-1), Pose::identity())),
               std::invalid_argument);
  Pose broken = Pose::identity();
  broken.position.y() = INFINITY;
  EXPECT_THROW(static_cast<void>(query.overlap(sphere(1), broken)), std::invalid_argument);
}

}  // namespace
}  // namespace coulomb::geometry
