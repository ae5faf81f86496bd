// Dispatch: every pair yields a normal from A (lower id) to B, closed forms or FCL, and failures
// are reported per pair.
#include <coulomb/geometry/NarrowPhase.hpp>

#include <coulomb/meshes/MakeConvexHull.hpp>

#include <gtest/gtest.h>

#include <memory>
#include <numbers>
#include <stdexcept>

namespace coulomb::geometry {
namespace {

Collider collider(std::uint32_t id, Shape shape) {
  Collider c;
  c.id = {id, 0};
  c.body = {id, 0};
  c.shape = std::make_shared<const Shape>(std::move(shape));
  return c;
}

ConvexHull unitCubeHull() {
  std::vector<Eigen::Vector3d> cloud;
  for (int i = 0; i < 8; ++i)
    cloud.emplace_back((i & 1) ? 0.5 : -0.5, (i & 2) ? 0.5 : -0.5, (i & 4) ? 0.5 : -0.5);
  return makeConvexHull(cloud);
}

struct Case {
  Shape lower;   // collider id 1, at the origin
  Shape upper;   // collider id 2, on top
  double z;      // centre height of the upper shape
  double depth;  // expected deepest penetration
};

// The lower shape's top surface is at z = 0.5 for all of these; the upper shape reaches 0.5
// below its centre, so depth = 1.0 - z.
TEST(NarrowPhase, EveryPairPointsFromAToBInBothIdOrders) {
  const std::vector<Case> cases{
      {Box{}, Sphere{0.5}, 0.999, 0.001},
      {Sphere{0.5}, Box{}, 0.999, 0.001},
      {Box{}, Capsule{0.1, 0.4}, 0.999, 0.001},
      {Capsule{0.5, 0.0}, Box{}, 0.999, 0.001},
      {Box{}, Cylinder{0.5, 0.5}, 0.999, 0.001},
      {Cylinder{0.5, 0.5}, Sphere{0.5}, 0.999, 0.001},
      {Box{}, Box{}, 0.999, 0.001},
      {unitCubeHull(), Box{}, 0.999, 0.001},
      {Box{}, unitCubeHull(), 0.999, 0.001},
      {Cylinder{0.5, 0.5}, Capsule{0.5, 0.0}, 0.999, 0.001},
  };
  NarrowPhase narrow;
  for (const Case& c : cases) {
    for (bool lowerFirst : {true, false}) {
      FclScene scene(0.005);
      const Collider low = collider(lowerFirst ? 1 : 2, c.lower);
      const Collider up = collider(lowerFirst ? 2 : 1, c.upper);
      const Pose pl = Pose::identity(), pu = Pose::translation({0, 0, c.z});
      scene.upsert(low.id, low.shape);
      scene.upsert(up.id, up.shape);
      scene.setPose(low.id, pl);
      scene.setPose(up.id, pu);
      PairContact out;
      std::string error;
      const bool touching = lowerFirst ? narrow.contactPair(low, pl, up, pu, scene, out, error)
                                       : narrow.contactPair(up, pu, low, pl, scene, out, error);
      const std::string what = std::string(shapeKindName(c.lower)) + " under " +
                               shapeKindName(c.upper) + (lowerFirst ? "" : " (swapped ids)");
      ASSERT_TRUE(error.empty()) << what << ": " << error;
      ASSERT_TRUE(touching) << what;
      const Eigen::Vector3d expected = (lowerFirst ? 1.0 : -1.0) * Eigen::Vector3d::UnitZ();
      EXPECT_TRUE(out.normal.isApprox(expected, 1e-6)) << what << ": " << out.normal.transpose();
      double deepest = -1.0;
      for (const auto& p : out.points) deepest = std::max(deepest, p.depth);
      EXPECT_NEAR(deepest, c.depth, 1e-6) << what;
    }
  }
}

TEST(NarrowPhase, PlaneUnderEveryShape) {
  NarrowPhase narrow;
  FclScene scene(0.005);
  const Collider ground = collider(0, Plane{});
  const std::vector<std::pair<Shape, std::size_t>> shapes{{Sphere{0.5}, 1},
                                                          {Box{}, 4},
                                                          {Capsule{0.5, 0.0}, 1},
                                                          {Cylinder{0.5, 0.5}, 8},
                                                          {unitCubeHull(), 4}};
  for (const auto& [shape, count] : shapes) {
    const Collider body = collider(1, shape);
    PairContact out;
    std::string error;
    ASSERT_TRUE(narrow.contactPair(ground, Pose::identity(), body, Pose::translation({0, 0, 0.499}),
                                   scene, out, error))
        << shapeKindName(shape);
    EXPECT_TRUE(out.normal.isApprox(Eigen::Vector3d::UnitZ()));
    EXPECT_EQ(out.points.size(), count) << shapeKindName(shape);
    for (const auto& p : out.points) EXPECT_NEAR(p.depth, 0.001, 1e-12);
  }
}

TEST(NarrowPhase, SpeculativePointThroughFclDistance) {
  NarrowPhase narrow;
  FclScene scene(0.005);
  const Collider a = collider(1, Box{}), b = collider(2, Cylinder{0.5, 0.5});
  scene.upsert(a.id, a.shape);
  scene.upsert(b.id, b.shape);
  scene.setPose(a.id, Pose::identity());
  scene.setPose(b.id, Pose::translation({0, 0, 1.002}));
  PairContact out;
  std::string error;
  ASSERT_TRUE(narrow.contactPair(a, Pose::identity(), b, Pose::translation({0, 0, 1.002}), scene,
                                 out, error));
  // The cap's rim within the margin (FeatureContacts), all at FCL's distance.
  ASSERT_GE(out.points.size(), 4u);
  for (const auto& p : out.points) EXPECT_NEAR(p.depth, -0.002, 1e-9);
  EXPECT_TRUE(out.normal.isApprox(Eigen::Vector3d::UnitZ(), 1e-9));
}

TEST(NarrowPhase, FailingPairIsReportedAndOthersGoOn) {
  NarrowPhase narrow;
  narrow.setFaultInjector([](ColliderId a, ColliderId) {
    if (a.index == 1) throw std::runtime_error("libccd blew up");
  });
  FclScene scene(0.005);
  std::vector<Collider> colliders{collider(1, Box{}), collider(2, Cylinder{0.5, 0.5}),
                                  collider(3, Box{}), collider(4, Cylinder{0.5, 0.5})};
  std::vector<Pose> poses{Pose::identity(), Pose::translation({0, 0, 0.999}),
                          Pose::translation({5, 0, 0}), Pose::translation({5, 0, 0.999})};
  for (std::size_t i = 0; i < 4; ++i) {
    scene.upsert(colliders[i].id, colliders[i].shape);
    scene.setPose(colliders[i].id, poses[i]);
  }
  const std::vector<CandidatePair> pairs{{0, 1}, {2, 3}};
  std::vector<ContactManifold> out;
  std::vector<CollisionFailure> failures;
  std::vector<Pose> bodyPoses{Pose::identity()};  // bodies are numbered like the colliders: 1..4
  bodyPoses.insert(bodyPoses.end(), poses.begin(), poses.end());
  narrow.collide(pairs, colliders, poses, bodyPoses, scene, out, failures);
  ASSERT_EQ(failures.size(), 1u);
  EXPECT_EQ(failures[0].a.index, 1u);
  EXPECT_NE(failures[0].message.find("libccd blew up"), std::string::npos);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].colliderA.index, 3u);
}

TEST(NarrowPhase, MeshCubesTouchFaceToFaceWithTheFaceNormal) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back((i & 1) ? 0.5 : -0.5, (i & 2) ? 0.5 : -0.5, (i & 4) ? 0.5 : -0.5);
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    m.triangles.emplace_back(f[0], f[1], f[2]);
    m.triangles.emplace_back(f[0], f[2], f[3]);
  }
  NarrowPhase narrow;
  FclScene scene(0.005);
  const Collider a = collider(1, m), b = collider(2, m);
  const Pose pa = Pose::identity(), pb = Pose::translation({0.2, 0.1, 0.999});
  scene.upsert(a.id, a.shape);
  scene.upsert(b.id, b.shape);
  scene.setPose(a.id, pa);
  scene.setPose(b.id, pb);
  scene.updateTree();
  PairContact out;
  std::string error;
  ASSERT_TRUE(narrow.contactPair(a, pa, b, pb, scene, out, error)) << error;
  EXPECT_TRUE(error.empty());
  EXPECT_TRUE(out.normal.isApprox(Eigen::Vector3d::UnitZ(), 1e-12)) << out.normal.transpose();
  ASSERT_GE(out.points.size(), 4u);
  double deepest = 0.0;
  for (const auto& p : out.points) {
    EXPECT_GE(p.position.x(), -0.3 - 1e-9);  // inside the overlap of the two faces
    EXPECT_LE(p.position.y(), 0.5 + 1e-9);
    EXPECT_LE(p.depth, 1e-3 + 1e-12);
    deepest = std::max(deepest, p.depth);
  }
  EXPECT_NEAR(deepest, 1e-3, 1e-12);
  // Apart beyond the margin: nothing.
  const Pose far = Pose::translation({0.2, 0.1, 1.02});
  scene.setPose(b.id, far);
  scene.updateTree();
  EXPECT_FALSE(narrow.contactPair(a, pa, b, far, scene, out, error));
}

}  // namespace
}  // namespace coulomb::geometry
