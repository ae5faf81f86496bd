// FclScene: every shape becomes an FCL geometry, queries are oriented a -> b, failures are caught.
#include <coulomb/geometry/FclAdapter.hpp>

#include <coulomb/meshes/MakeConvexHull.hpp>

#include <gtest/gtest.h>

#include <limits>
#include <memory>
#include <stdexcept>

namespace coulomb::geometry {
namespace {

std::shared_ptr<const Shape> make(Shape s) {
  return std::make_shared<const Shape>(std::move(s));
}

TriangleMesh cubeMesh(double half) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back((i & 1) ? half : -half, (i & 2) ? half : -half, (i & 4) ? half : -half);
  // Outward, counter-clockwise faces of the cube with corner bits (x, y, z).
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    m.triangles.emplace_back(f[0], f[1], f[2]);
    m.triangles.emplace_back(f[0], f[2], f[3]);
  }
  return m;
}

TEST(FclAdapter, BuildsEveryShapeKind) {
  FclScene scene(0.0);
  std::vector<Eigen::Vector3d> cloud;
  for (int i = 0; i < 8; ++i)
    cloud.emplace_back((i & 1) ? 0.5 : -0.5, (i & 2) ? 0.5 : -0.5, (i & 4) ? 0.5 : -0.5);
  const std::vector<Shape> shapes{Sphere{0.5},        Box{},   Capsule{0.1, 0.5},
                                  Cylinder{0.5, 0.5}, Plane{}, makeConvexHull(cloud),
                                  cubeMesh(0.5)};
  std::uint32_t index = 0;
  for (const Shape& s : shapes)
    EXPECT_NO_THROW(scene.upsert({index++, 0}, make(s))) << shapeKindName(s);
  EXPECT_EQ(scene.ids().size(), shapes.size());
}

TEST(FclAdapter, DegenerateShapesAreRejectedWithTheColliderNamed) {
  FclScene scene(0.0);
  try {
    scene.upsert({7, 0}, make(Box{{1.0, 0.0, 1.0}}));
    FAIL() << "a flat box must be rejected";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("collider 7"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("half_extents[1]"), std::string::npos) << e.what();
  }
  EXPECT_THROW(scene.upsert({8, 0}, make(Sphere{-1.0})), std::invalid_argument);
  EXPECT_THROW(scene.upsert({9, 0}, make(ConvexHull{
                                        {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {}, {}, {}})),
               std::invalid_argument);  // no faces computed
  EXPECT_FALSE(scene.contains({7, 0}));
}

TEST(FclAdapter, NanPoseIsRejected) {
  FclScene scene(0.0);
  scene.upsert({1, 0}, make(Box{}));
  Pose bad = Pose::translation({0, std::numeric_limits<double>::quiet_NaN(), 0});
  try {
    scene.setPose({1, 0}, bad);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos);
  }
}

TEST(FclAdapter, CollideNormalPointsFromAToBInBothOrders) {
  FclScene scene(0.0);
  std::vector<Eigen::Vector3d> cloud;
  for (int i = 0; i < 8; ++i)
    cloud.emplace_back((i & 1) ? 0.5 : -0.5, (i & 2) ? 0.5 : -0.5, (i & 4) ? 0.5 : -0.5);
  scene.upsert({1, 0}, make(makeConvexHull(cloud)));
  scene.upsert({2, 0}, make(Box{}));
  scene.setPose({1, 0}, Pose::identity());
  scene.setPose({2, 0}, Pose::translation({0, 0, 0.999}));
  const FclCollideResult ab = scene.collide({1, 0}, {2, 0}, 4);
  ASSERT_TRUE(ab.error.empty());
  ASSERT_FALSE(ab.contacts.empty());
  EXPECT_TRUE(ab.contacts[0].normal.isApprox(Eigen::Vector3d::UnitZ(), 1e-9));
  EXPECT_NEAR(ab.contacts[0].depth, 0.001, 1e-6);
  const FclCollideResult ba = scene.collide({2, 0}, {1, 0}, 4);
  ASSERT_FALSE(ba.contacts.empty());
  EXPECT_TRUE(ba.contacts[0].normal.isApprox(-Eigen::Vector3d::UnitZ(), 1e-9));
}

TEST(FclAdapter, MeshSecondIsReorientedAndDepthPositive) {
  FclScene scene(0.0);
  scene.upsert({1, 0}, make(Sphere{0.5}));
  scene.upsert({2, 0}, make(cubeMesh(0.5)));
  scene.setPose({1, 0}, Pose::translation({0, 0, 0.999}));
  scene.setPose({2, 0}, Pose::identity());
  const FclCollideResult r = scene.collide({1, 0}, {2, 0}, 64);  // sphere is a, mesh is b
  ASSERT_TRUE(r.error.empty());
  ASSERT_FALSE(r.contacts.empty());
  for (const FclContact& c : r.contacts) {
    EXPECT_TRUE(c.normal.isApprox(-Eigen::Vector3d::UnitZ(), 1e-6));  // sphere -> mesh
    EXPECT_GT(c.depth, 0.0);
    EXPECT_GE(c.triangleB, 0);
    EXPECT_EQ(c.triangleA, -1);
  }
}

TEST(FclAdapter, DistanceForSeparatedPairsAndRefusedForPlanes) {
  FclScene scene(0.0);
  scene.upsert({1, 0}, make(Box{}));
  scene.upsert({2, 0}, make(Cylinder{0.5, 0.5}));
  scene.upsert({3, 0}, make(Plane{}));
  scene.setPose({1, 0}, Pose::identity());
  scene.setPose({2, 0}, Pose::translation({0, 0, 1.003}));
  scene.setPose({3, 0}, Pose::identity());
  const FclDistanceResult d = scene.distance({1, 0}, {2, 0});
  ASSERT_TRUE(d.error.empty());
  EXPECT_NEAR(d.distance, 0.003, 1e-9);
  EXPECT_NEAR(d.pointA.z(), 0.5, 1e-9);
  EXPECT_NEAR(d.pointB.z(), 0.503, 1e-9);
  EXPECT_FALSE(scene.distance({1, 0}, {3, 0}).error.empty());
}

TEST(FclAdapter, ExceptionInsideTheQueryIsReportedNotThrown) {
  FclScene scene(0.0);
  scene.upsert({1, 0}, make(Box{}));
  scene.upsert({2, 0}, make(Box{}));
  scene.setPose({1, 0}, Pose::identity());
  scene.setPose({2, 0}, Pose::translation({0, 0, 0.9}));
  const FclFaultInjector fail = [](ColliderId, ColliderId) {
    throw std::logic_error("simulated EPA failure");
  };
  FclCollideResult r;
  EXPECT_NO_THROW(r = scene.collide({1, 0}, {2, 0}, 4, fail));
  EXPECT_NE(r.error.find("simulated EPA failure"), std::string::npos);
  EXPECT_TRUE(r.contacts.empty());
  EXPECT_NE(scene.distance({1, 0}, {2, 0}, fail).error.find("simulated"), std::string::npos);
}

TEST(FclAdapter, TreeFindsOverlapsWithMarginAndKeepsPlanesOut) {
  FclScene scene(0.01);
  for (std::uint32_t i = 0; i < 3; ++i) scene.upsert({i, 0}, make(Box{}));
  scene.upsert({3, 0}, make(Plane{}));
  scene.setPose({0, 0}, Pose::translation({0, 0, 0}));
  scene.setPose({1, 0}, Pose::translation({1.005, 0, 0}));  // 5 mm gap: within the 10 mm margin
  scene.setPose({2, 0}, Pose::translation({5, 0, 0}));
  scene.setPose({3, 0}, Pose::identity());
  scene.updateTree();
  std::vector<std::pair<ColliderId, ColliderId>> pairs;
  scene.overlappingPairs(pairs);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0].first, (ColliderId{0, 0}));
  EXPECT_EQ(pairs[0].second, (ColliderId{1, 0}));
  scene.erase({1, 0});
  scene.updateTree();
  scene.overlappingPairs(pairs);
  EXPECT_TRUE(pairs.empty());
}

}  // namespace
}  // namespace coulomb::geometry
