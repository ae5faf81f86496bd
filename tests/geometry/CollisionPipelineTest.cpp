// The facade World::step calls: resting contacts persist with stable ids for 1000 steps, bad
// input is reported (never thrown), failures skip one pair only, output is deterministic.
#include <coulomb/geometry/CollisionPipeline.hpp>

#include <coulomb/meshes/MeshLoader.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

namespace coulomb::geometry {
namespace {

Collider collider(std::uint32_t id, std::uint32_t body, Shape shape) {
  Collider c;
  c.id = {id, 0};
  c.body = {body, 0};
  c.shape = std::make_shared<const Shape>(std::move(shape));
  return c;
}

// Slightly perturbed pose, as a resting body jitters under a solver: 1e-5 m and 1e-5 rad.
Pose jitter(const Eigen::Vector3d& at, int step) {
  const double s = std::sin(0.37 * step), c = std::cos(0.91 * step);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(1e-5 * s, Eigen::Vector3d(c, s, 0.3).normalized()));
  return {q, at + 1e-5 * Eigen::Vector3d(c, s, s * c)};
}

std::vector<std::uint32_t> ids(const ContactManifold& m) {
  std::vector<std::uint32_t> out;
  for (const ContactPoint& p : m.activePoints()) out.push_back(p.featureId);
  return out;
}

TEST(CollisionPipeline, RestingBoxOnPlaneKeepsFourPointsAndIdsFor1000Steps) {
  CollisionPipeline pipeline;
  const std::vector<Collider> colliders{collider(0, 0, Plane{}), collider(1, 1, Box{})};
  std::vector<Pose> poses{Pose::identity(), Pose::translation({0, 0, 0.4995})};
  const auto& first = pipeline.step(colliders, poses);
  ASSERT_EQ(first.size(), 1u);
  ASSERT_EQ(first[0].pointCount, 4);
  const auto firstIds = ids(first[0]);
  for (const ContactPoint& p : first[0].activePoints()) {
    EXPECT_NEAR(p.depth, 0.0005, 1e-12);
    EXPECT_NEAR(std::abs(p.position.x()), 0.5, 1e-12);
    EXPECT_NEAR(std::abs(p.position.y()), 0.5, 1e-12);
  }
  for (int step = 1; step <= 1000; ++step) {
    for (ContactPoint& p : pipeline.cache().manifolds()[0].activePoints()) p.normalImpulse = 2.5;
    poses[1] = jitter({0, 0, 0.4995}, step);
    const auto& now = pipeline.step(colliders, poses);
    ASSERT_EQ(now.size(), 1u) << "step " << step;
    ASSERT_EQ(now[0].pointCount, 4) << "step " << step;
    ASSERT_EQ(ids(now[0]), firstIds) << "step " << step;
    for (const ContactPoint& p : now[0].activePoints()) {
      ASSERT_TRUE(p.warmStarted) << "step " << step;
      ASSERT_DOUBLE_EQ(p.normalImpulse, 2.5);
    }
  }
  EXPECT_TRUE(pipeline.diagnostics().failures.empty());
}

TEST(CollisionPipeline, StackOfBoxesKeepsFourPointsPerContactFor1000Steps) {
  CollisionPipeline pipeline;
  std::vector<Collider> colliders{collider(0, 0, Plane{})};
  std::vector<Pose> rest{Pose::identity()};
  for (std::uint32_t k = 1; k <= 3; ++k) {
    colliders.push_back(collider(k, k, Box{}));
    rest.push_back(
        Pose::translation({0, 0, k - 0.5 - 0.0004 * k}));  // each 0.4 mm into the one below
  }
  const auto first = pipeline.step(colliders, rest);
  ASSERT_EQ(first.size(), 3u);
  for (const ContactManifold& m : first) {
    ASSERT_EQ(m.pointCount, 4);
    EXPECT_TRUE(m.normal.isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
    for (const ContactPoint& p : m.activePoints()) EXPECT_NEAR(p.depth, 0.0004, 1e-9);
  }
  std::vector<Pose> poses = rest;
  for (int step = 1; step <= 1000; ++step) {
    for (std::size_t k = 1; k < poses.size(); ++k)
      poses[k] = jitter(rest[k].position, step + 7 * int(k));
    const auto& now = pipeline.step(colliders, poses);
    ASSERT_EQ(now.size(), 3u) << "step " << step;
    for (std::size_t i = 0; i < 3; ++i) {
      ASSERT_EQ(now[i].pointCount, 4) << "step " << step;
      ASSERT_EQ(ids(now[i]), ids(first[i])) << "step " << step << " pair " << i;
    }
  }
}

TEST(CollisionPipeline, MaterialsCombineAndBodiesAreNamed) {
  CollisionPipeline pipeline;
  std::vector<Collider> colliders{collider(0, 0, Plane{}), collider(1, 1, Sphere{0.5})};
  colliders[0].material = {0.25, 0.2};
  colliders[1].material = {1.0, 0.6};
  const std::vector<Pose> poses{Pose::identity(), Pose::translation({0, 0, 0.49})};
  const auto& m = pipeline.step(colliders, poses);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_DOUBLE_EQ(m[0].friction, 0.5);
  EXPECT_DOUBLE_EQ(m[0].restitution, 0.6);
  EXPECT_EQ(m[0].bodyA.index, 0u);
  EXPECT_EQ(m[0].bodyB.index, 1u);
  EXPECT_EQ(pipeline.diagnostics().stats.contactPoints, 1u);
}

TEST(CollisionPipeline, NanPoseAndBadShapeAreReportedAndSkipped) {
  CollisionPipeline pipeline;
  std::vector<Collider> colliders{collider(0, 0, Plane{}), collider(1, 1, Box{}),
                                  collider(2, 2, Box{}), collider(3, 3, Sphere{0.0})};
  std::vector<Pose> poses{Pose::identity(), Pose::translation({0, 0, 0.499}),
                          Pose::translation({5, 0, std::numeric_limits<double>::quiet_NaN()}),
                          Pose::translation({-5, 0, 0})};
  EXPECT_TRUE(CollisionPipeline::validateCollider(colliders[1]) == std::nullopt);
  const auto problem = CollisionPipeline::validateCollider(colliders[3]);
  ASSERT_TRUE(problem.has_value());
  EXPECT_NE(problem->find("sphere radius"), std::string::npos) << *problem;
  const auto& m = pipeline.step(colliders, poses);
  ASSERT_EQ(m.size(), 1u);  // the good box still rests on the plane
  const auto& failures = pipeline.diagnostics().failures;
  ASSERT_EQ(failures.size(), 2u);
  EXPECT_EQ(failures[0].a.index, 2u);
  EXPECT_NE(failures[0].message.find("not finite"), std::string::npos) << failures[0].message;
  EXPECT_EQ(failures[1].a.index, 3u);
  EXPECT_NE(failures[1].message.find("radius"), std::string::npos) << failures[1].message;
}

TEST(CollisionPipeline, PairThatThrowsInsideFclDoesNotStopTheStep) {
  CollisionPipeline pipeline;
  pipeline.setFaultInjector([](ColliderId a, ColliderId) {
    if (a.index == 1) throw std::logic_error("FailedAtThisConfiguration (injected)");
  });
  const std::vector<Collider> colliders{collider(1, 0, Box{}), collider(2, 1, Cylinder{0.5, 0.5}),
                                        collider(3, 2, Box{}), collider(4, 3, Cylinder{0.5, 0.5})};
  const std::vector<Pose> poses{Pose::identity(), Pose::translation({0, 0, 0.999}),
                                Pose::translation({5, 0, 0}), Pose::translation({5, 0, 0.999})};
  const auto& m = pipeline.step(colliders, poses);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].colliderA.index, 3u);
  const auto& failures = pipeline.diagnostics().failures;
  ASSERT_EQ(failures.size(), 1u) << failures[0].message << " / " << failures[1].message;
  EXPECT_NE(failures[0].message.find("injected"), std::string::npos);
}

TEST(CollisionPipeline, SameOutputWhateverTheColliderListOrder) {
  std::vector<Collider> colliders{collider(0, 0, Plane{})};
  std::vector<Pose> poses{Pose::identity()};
  for (std::uint32_t k = 1; k <= 12; ++k) {
    colliders.push_back(collider(k, k, k % 2 ? Shape{Box{}} : Shape{Sphere{0.5}}));
    poses.push_back(Pose::translation({0.97 * (k % 4), 0.97 * (k / 4), 0.499}));
  }
  CollisionPipeline forward, backward;
  const auto a = forward.step(colliders, poses);
  std::vector<Collider> reversed(colliders.rbegin(), colliders.rend());
  const auto b = backward.step(reversed, poses);  // poses are indexed by body, not list order
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 12u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].colliderA, b[i].colliderA);
    EXPECT_EQ(a[i].colliderB, b[i].colliderB);
    EXPECT_EQ(ids(a[i]), ids(b[i]));
    EXPECT_EQ(a[i].normal, b[i].normal);
  }
}

TEST(CollisionPipeline, BoxOnAStaticMeshFromTestData) {
  TriangleMesh slab =
      loadTriangleMesh(std::string(COULOMB_TEST_DATA_DIR) + "/meshes/unit_cube.obj", {4, 4, 1});
  CollisionPipeline pipeline;
  const std::vector<Collider> colliders{collider(0, 0, slab), collider(1, 1, Box{{0.3, 0.3, 0.3}})};
  const std::vector<Pose> poses{Pose::identity(), Pose::translation({0.2, 0.1, 0.799})};
  const auto& m = pipeline.step(colliders, poses);
  ASSERT_TRUE(pipeline.diagnostics().failures.empty())
      << pipeline.diagnostics().failures[0].message;
  ASSERT_EQ(m.size(), 1u);
  EXPECT_TRUE(m[0].normal.isApprox(Eigen::Vector3d::UnitZ(), 1e-6));
  ASSERT_GE(m[0].pointCount, 1);
  for (const ContactPoint& p : m[0].activePoints()) EXPECT_NEAR(p.depth, 0.001, 1e-6);
}

}  // namespace
}  // namespace coulomb::geometry
