// Exact ray tests and support points of every shape: analytic hits, and on random rays the hit
// checked against an independent inside-test of each solid (just before the hit: outside; just
// after: inside; no hit: every sample along the ray outside).
#include <coulomb/geometry/RayCast.hpp>
#include <coulomb/meshes/MakeConvexHull.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

namespace coulomb::geometry {
namespace {

using Eigen::Vector3d;

Pose rotated(const Vector3d& position, double angle, const Vector3d& axis) {
  return {Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized())), position};
}

TEST(RayCast, SphereFromOutsideHitsAtDistanceMinusRadius) {
  const auto hit =
      rayCastShape(Sphere{0.5}, Pose::translation({0, 0, 2}), {0, 0, 0}, {0, 0, 1}, 10);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, 1.5, 1e-14);
  EXPECT_NEAR((hit->normal - Vector3d(0, 0, -1)).norm(), 0, 1e-14);
  EXPECT_FALSE(rayCastShape(Sphere{0.5}, Pose::translation({0, 0, 2}), {0, 0, 0}, {0, 0, 1}, 1.4));
  EXPECT_FALSE(rayCastShape(Sphere{0.5}, Pose::translation({0, 0, 2}), {0, 0, 0}, {0, 0, -1}, 10));
  EXPECT_FALSE(rayCastShape(Sphere{0.5}, Pose::translation({0, 0.6, 2}), {0, 0, 0}, {0, 0, 1}, 10));
}

TEST(RayCast, RayStartingInsideHitsAtZeroAgainstItsDirection) {
  const auto hit =
      rayCastShape(Box{Vector3d(1, 1, 1)}, Pose::identity(), {0.2, 0, 0}, {1, 0, 0}, 5);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->distance, 0.0);
  EXPECT_EQ(hit->normal, Vector3d(-1, 0, 0));
  const auto ground = rayCastShape(Plane{}, Pose::identity(), {0, 0, -1}, {0, 0, 1}, 5);
  ASSERT_TRUE(ground);
  EXPECT_EQ(ground->distance, 0.0);
}

TEST(RayCast, RotatedBoxFaceNormal) {
  // A box turned 90 deg about z: its local x face now faces world y.
  const Pose pose = rotated({0, 3, 0}, M_PI / 2, Vector3d::UnitZ());
  const auto hit = rayCastShape(Box{Vector3d(0.5, 0.25, 1)}, pose, {0, 0, 0}, {0, 1, 0}, 10);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, 2.5, 1e-12);
  EXPECT_NEAR((hit->normal - Vector3d(0, -1, 0)).norm(), 0, 1e-12);
}

TEST(RayCast, CapsuleSideAndCap) {
  const Capsule c{0.2, 0.5};
  auto side = rayCastShape(c, Pose::identity(), {-2, 0, 0.3}, {1, 0, 0}, 10);
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->distance, 1.8, 1e-12);
  EXPECT_NEAR((side->normal - Vector3d(-1, 0, 0)).norm(), 0, 1e-12);
  auto cap = rayCastShape(c, Pose::identity(), {0, 0, 3}, {0, 0, -1}, 10);
  ASSERT_TRUE(cap);
  EXPECT_NEAR(cap->distance, 3 - 0.7, 1e-12);
  EXPECT_NEAR((cap->normal - Vector3d(0, 0, 1)).norm(), 0, 1e-12);
}

TEST(RayCast, CylinderCapAndSideAndPlaneAndMesh) {
  const Cylinder cyl{0.5, 1.0};
  auto cap = rayCastShape(cyl, Pose::identity(), {0.3, 0, 5}, {0, 0, -1}, 10);
  ASSERT_TRUE(cap);
  EXPECT_NEAR(cap->distance, 4.0, 1e-12);
  EXPECT_NEAR((cap->normal - Vector3d(0, 0, 1)).norm(), 0, 1e-12);
  auto side = rayCastShape(cyl, Pose::identity(), {0, -3, 0.9}, {0, 1, 0}, 10);
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->distance, 2.5, 1e-12);
  // A tilted plane n = (0, 1, 1)/sqrt 2, offset 0, from (0, 0, 1) straight down.
  auto plane =
      rayCastShape(Plane{Vector3d(0, 1, 1), 0}, Pose::identity(), {0, 0, 1}, {0, 0, -1}, 5);
  ASSERT_TRUE(plane);
  EXPECT_NEAR(plane->distance, 1.0, 1e-12);
  EXPECT_NEAR((plane->normal - Vector3d(0, 1, 1).normalized()).norm(), 0, 1e-12);
  // Two triangles forming the unit square at z = 0, seen from above and from below.
  TriangleMesh square{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}};
  auto top = rayCastShape(square, Pose::identity(), {0.7, 0.2, 2}, {0, 0, -1}, 5);
  ASSERT_TRUE(top);
  EXPECT_NEAR(top->distance, 2.0, 1e-12);
  EXPECT_NEAR((top->normal - Vector3d(0, 0, 1)).norm(), 0, 1e-12);
  EXPECT_TRUE(rayCastShape(square, Pose::identity(), {0.7, 0.2, -2}, {0, 0, 1}, 5));
  EXPECT_FALSE(rayCastShape(square, Pose::identity(), {1.7, 0.2, 2}, {0, 0, -1}, 5));
}

// Independent inside-tests, in the shape frame.
using Inside = std::function<bool(const Vector3d&)>;

void checkRandomRays(const Shape& shape, const Inside& inside, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const Pose pose = rotated({0.3, -0.2, 0.1}, 0.7, Vector3d(1, 2, 3));
  int hits = 0;
  for (int k = 0; k < 400; ++k) {
    const Vector3d origin = 3.0 * Vector3d(u(rng), u(rng), u(rng));
    const Vector3d target = 0.5 * Vector3d(u(rng), u(rng), u(rng));
    const Vector3d dir = (target - origin).normalized();
    const double reach = 6.0;
    const auto hit = rayCastShape(shape, pose, origin, dir, reach);
    auto in = [&](double t) { return inside(pose.applyInverse(origin + t * dir)); };
    if (in(0)) {
      ASSERT_TRUE(hit);
      EXPECT_EQ(hit->distance, 0.0);
      continue;
    }
    if (!hit) {
      for (double t = 0; t <= reach; t += 1e-3) ASSERT_FALSE(in(t)) << "missed a hit at t = " << t;
      continue;
    }
    ++hits;
    EXPECT_FALSE(in(hit->distance - 1e-7)) << "ray " << k;
    EXPECT_TRUE(in(hit->distance + 1e-7)) << "ray " << k;
    EXPECT_NEAR(hit->normal.norm(), 1.0, 1e-12);
    EXPECT_LT(hit->normal.dot(dir), 1e-9) << "normal faces the ray";
  }
  EXPECT_GT(hits, 100);
}

TEST(RayCast, RandomRaysAgreeWithInsideTests) {
  checkRandomRays(
      Sphere{0.8}, [](const Vector3d& p) { return p.norm() <= 0.8; }, 1);
  const Vector3d h(0.9, 0.4, 0.6);
  checkRandomRays(
      Box{h}, [&](const Vector3d& p) { return (p.cwiseAbs().array() <= h.array()).all(); }, 2);
  checkRandomRays(
      Capsule{0.3, 0.6},
      [](const Vector3d& p) {
        return (p - Vector3d(0, 0, std::clamp(p.z(), -0.6, 0.6))).norm() <= 0.3;
      },
      3);
  checkRandomRays(
      Cylinder{0.5, 0.4},
      [](const Vector3d& p) { return std::hypot(p.x(), p.y()) <= 0.5 && std::abs(p.z()) <= 0.4; },
      4);
  // A hull: the octahedron |x| + |y| + |z| <= 0.9.
  const ConvexHull octahedron = makeConvexHull(
      {{0.9, 0, 0}, {-0.9, 0, 0}, {0, 0.9, 0}, {0, -0.9, 0}, {0, 0, 0.9}, {0, 0, -0.9}});
  checkRandomRays(
      octahedron, [](const Vector3d& p) { return p.cwiseAbs().sum() <= 0.9; }, 5);
}

TEST(RayCast, SupportPointsAreFarthestAlongTheDirection) {
  const Vector3d d = Vector3d(0.3, -1, 0.5).normalized();
  EXPECT_NEAR((supportPoint(Sphere{2}, d) - 2 * d).norm(), 0, 1e-14);
  EXPECT_EQ(supportPoint(Box{Vector3d(1, 2, 3)}, d), Vector3d(1, -2, 3));
  const Vector3d capsule = supportPoint(Capsule{0.5, 1}, d);
  EXPECT_NEAR((capsule - (Vector3d(0, 0, 1) + 0.5 * d)).norm(), 0, 1e-14);
  const Vector3d cylinder = supportPoint(Cylinder{0.5, 1}, d);
  EXPECT_NEAR(cylinder.z(), 1, 0);
  EXPECT_NEAR(std::hypot(cylinder.x(), cylinder.y()), 0.5, 1e-14);
  EXPECT_THROW(static_cast<void>(supportPoint(Plane{}, d)), std::invalid_argument);
}

}  // namespace
}  // namespace coulomb::geometry
