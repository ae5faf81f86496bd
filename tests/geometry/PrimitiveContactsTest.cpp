// Closed-form contacts against hand-computed points, normals and depths.
#include <coulomb/geometry/PrimitiveContacts.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace coulomb::geometry {
namespace {

constexpr double kTol = 1e-12;
const double kMargin = 0.005;

Pose at(double x, double y, double z) {
  return Pose::translation({x, y, z});
}
Pose rotated(const Eigen::Vector3d& axis, double angle, const Eigen::Vector3d& p) {
  return {Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized())), p};
}

TEST(PrimitiveContacts, SphereSphereOverlap) {
  PairContact out;
  ASSERT_TRUE(sphereSphere({0.5}, at(0, 0, 0), {0.5}, at(0.9, 0, 0), kMargin, out));
  ASSERT_EQ(out.points.size(), 1u);
  EXPECT_TRUE(out.normal.isApprox(Eigen::Vector3d::UnitX(), kTol));
  EXPECT_NEAR(out.points[0].depth, 0.1, kTol);
  EXPECT_TRUE(out.points[0].position.isApprox(Eigen::Vector3d(0.45, 0, 0), kTol));
}

TEST(PrimitiveContacts, SphereSphereSpeculativeAndApart) {
  PairContact out;
  ASSERT_TRUE(sphereSphere({0.5}, at(0, 0, 0), {0.5}, at(0, 0, 1.002), kMargin, out));
  EXPECT_NEAR(out.points[0].depth, -0.002, kTol);
  out = {};
  EXPECT_FALSE(sphereSphere({0.5}, at(0, 0, 0), {0.5}, at(0, 0, 1.01), kMargin, out));
  EXPECT_TRUE(out.points.empty());
}

TEST(PrimitiveContacts, ConcentricSpheresGetAFiniteNormal) {
  PairContact out;
  ASSERT_TRUE(sphereSphere({0.5}, at(1, 1, 1), {0.3}, at(1, 1, 1), kMargin, out));
  EXPECT_TRUE(out.normal.allFinite());
  EXPECT_NEAR(out.normal.norm(), 1.0, kTol);
  EXPECT_NEAR(out.points[0].depth, 0.8, kTol);
}

TEST(PrimitiveContacts, SphereOnBoxFaceEdgeAndInside) {
  const Box box{{1.0, 1.0, 0.5}};
  PairContact face;  // sphere r=0.25 resting 1 mm into the top face, normal sphere -> box = -z
  ASSERT_TRUE(sphereBox({0.25}, at(0.3, -0.2, 0.749), box, at(0, 0, 0), kMargin, face));
  EXPECT_TRUE(face.normal.isApprox(-Eigen::Vector3d::UnitZ(), kTol));
  EXPECT_NEAR(face.points[0].depth, 0.001, kTol);
  EXPECT_TRUE(face.points[0].position.isApprox(Eigen::Vector3d(0.3, -0.2, 0.4995), kTol));

  PairContact edge;  // off the +x,+z edge along the diagonal
  const double s = 0.2 / std::sqrt(2.0);
  ASSERT_TRUE(sphereBox({0.25}, at(1.0 + s, 0, 0.5 + s), box, at(0, 0, 0), kMargin, edge));
  EXPECT_TRUE(edge.normal.isApprox(-Eigen::Vector3d(1, 0, 1).normalized(), kTol));
  EXPECT_NEAR(edge.points[0].depth, 0.05, kTol);

  PairContact inside;  // centre inside, nearest face +y at 0.1
  ASSERT_TRUE(sphereBox({0.25}, at(0, 0.9, 0), box, at(0, 0, 0), kMargin, inside));
  EXPECT_TRUE(inside.normal.isApprox(-Eigen::Vector3d::UnitY(), kTol));
  EXPECT_NEAR(inside.points[0].depth, 0.35, kTol);
}

TEST(PrimitiveContacts, SphereBoxInRotatedBoxFrame) {
  const Pose boxPose = rotated(Eigen::Vector3d::UnitZ(), std::numbers::pi / 4, {2, 0, 0});
  PairContact out;  // sphere on the box's local +x face, which now faces (1,1,0)/sqrt2
  const Eigen::Vector3d n = Eigen::Vector3d(1, 1, 0).normalized();
  ASSERT_TRUE(sphereBox({0.5}, Pose::translation(Eigen::Vector3d(2, 0, 0) + 0.9 * n), Box{},
                        boxPose, kMargin, out));
  EXPECT_TRUE(out.normal.isApprox(-n, 1e-12));
  EXPECT_NEAR(out.points[0].depth, 0.1, 1e-12);
}

TEST(PrimitiveContacts, SphereCapsuleSideAndCap) {
  const Capsule capsule{0.1, 0.5};
  PairContact side;
  ASSERT_TRUE(sphereCapsule({0.2}, at(0.29, 0, 0.3), capsule, at(0, 0, 0), kMargin, side));
  EXPECT_TRUE(side.normal.isApprox(-Eigen::Vector3d::UnitX(), kTol));
  EXPECT_NEAR(side.points[0].depth, 0.01, kTol);
  PairContact cap;
  ASSERT_TRUE(sphereCapsule({0.2}, at(0, 0, 0.79), capsule, at(0, 0, 0), kMargin, cap));
  EXPECT_TRUE(cap.normal.isApprox(-Eigen::Vector3d::UnitZ(), kTol));
  EXPECT_NEAR(cap.points[0].depth, 0.01, kTol);
}

TEST(PrimitiveContacts, SphereCylinderSideCapRimInside) {
  const Cylinder cyl{0.5, 0.5};
  PairContact side, cap, rim, inside;
  ASSERT_TRUE(sphereCylinder({0.1}, at(0, 0.59, 0.2), cyl, at(0, 0, 0), kMargin, side));
  EXPECT_TRUE(side.normal.isApprox(-Eigen::Vector3d::UnitY(), kTol));
  EXPECT_NEAR(side.points[0].depth, 0.01, kTol);
  ASSERT_TRUE(sphereCylinder({0.1}, at(0.2, 0, -0.59), cyl, at(0, 0, 0), kMargin, cap));
  EXPECT_TRUE(cap.normal.isApprox(Eigen::Vector3d::UnitZ(), kTol));
  EXPECT_NEAR(cap.points[0].depth, 0.01, kTol);
  const double s = 0.09 / std::sqrt(2.0);
  ASSERT_TRUE(sphereCylinder({0.1}, at(0.5 + s, 0, 0.5 + s), cyl, at(0, 0, 0), kMargin, rim));
  EXPECT_TRUE(rim.normal.isApprox(-Eigen::Vector3d(1, 0, 1).normalized(), kTol));
  EXPECT_NEAR(rim.points[0].depth, 0.01, kTol);
  ASSERT_TRUE(sphereCylinder({0.1}, at(0, 0, 0.45), cyl, at(0, 0, 0), kMargin, inside));
  EXPECT_TRUE(inside.normal.isApprox(-Eigen::Vector3d::UnitZ(), kTol));
  EXPECT_NEAR(inside.points[0].depth, 0.15, kTol);
}

TEST(PrimitiveContacts, CrossedCapsulesOnePoint) {
  const Capsule c{0.1, 0.5};
  const Pose a = rotated(Eigen::Vector3d::UnitY(), std::numbers::pi / 2, {0, 0, 0});     // along x
  const Pose b = rotated(Eigen::Vector3d::UnitX(), std::numbers::pi / 2, {0, 0, 0.19});  // along y
  PairContact out;
  ASSERT_TRUE(capsuleCapsule(c, a, c, b, kMargin, out));
  ASSERT_EQ(out.points.size(), 1u);
  EXPECT_TRUE(out.normal.isApprox(Eigen::Vector3d::UnitZ(), kTol));
  EXPECT_NEAR(out.points[0].depth, 0.01, kTol);
  EXPECT_TRUE(out.points[0].position.isApprox(Eigen::Vector3d(0, 0, 0.095), kTol));
}

TEST(PrimitiveContacts, CapToCapIsExactWhereMprIsNot) {
  // End to end along a tilted line: the exact normal is the direction between the two ends.
  const Capsule c{0.1, 0.3};
  const Eigen::Vector3d dir = Eigen::Vector3d(1, 0, 1).normalized();
  const Pose a = rotated(Eigen::Vector3d::UnitY(), std::numbers::pi / 4, Eigen::Vector3d::Zero());
  const Pose b{a.rotation, dir * (0.6 + 0.199)};
  PairContact out;
  ASSERT_TRUE(capsuleCapsule(c, a, c, b, kMargin, out));
  EXPECT_TRUE(out.normal.isApprox(dir, 1e-9));
  EXPECT_NEAR(out.points[0].depth, 0.001, 1e-9);
}

TEST(PrimitiveContacts, ParallelCapsulesGiveTheOverlapEnds) {
  const Capsule c{0.1, 0.5};
  const Pose a = rotated(Eigen::Vector3d::UnitY(), std::numbers::pi / 2, {0, 0, 0});
  const Pose b = rotated(Eigen::Vector3d::UnitY(), std::numbers::pi / 2, {0.4, 0, 0.199});
  PairContact out;
  ASSERT_TRUE(capsuleCapsule(c, a, c, b, kMargin, out));
  ASSERT_EQ(out.points.size(), 2u);
  EXPECT_TRUE(out.normal.isApprox(Eigen::Vector3d::UnitZ(), kTol));
  EXPECT_TRUE(out.points[0].position.isApprox(Eigen::Vector3d(-0.1, 0, 0.0995), kTol));
  EXPECT_TRUE(out.points[1].position.isApprox(Eigen::Vector3d(0.5, 0, 0.0995), kTol));
  EXPECT_NEAR(out.points[0].depth, 0.001, kTol);
  EXPECT_NEAR(out.points[1].depth, 0.001, kTol);
}

TEST(PrimitiveContacts, PlaneAgainstBoxCornersAndCapsuleEnds) {
  const WorldPlane ground{Eigen::Vector3d::UnitZ(), 0.0};
  const auto corners = boxCorners(Box{}, at(0, 0, 0.499));
  PairContact box;
  ASSERT_TRUE(planePoints(ground, corners, 0.0, kMargin, box));
  ASSERT_EQ(box.points.size(), 4u);  // the bottom four corners, ids 0..3
  for (std::uint32_t i = 0; i < 4; ++i) {
    EXPECT_EQ(box.points[i].featureId, i);
    EXPECT_NEAR(box.points[i].depth, 0.001, kTol);
    EXPECT_NEAR(box.points[i].position.z(), -0.0005, kTol);
  }
  const Capsule c{0.1, 0.5};
  const Pose lying = rotated(Eigen::Vector3d::UnitY(), std::numbers::pi / 2, {0, 0, 0.099});
  const std::array<Eigen::Vector3d, 2> ends{lying.apply({0, 0, -0.5}), lying.apply({0, 0, 0.5})};
  PairContact capsule;
  ASSERT_TRUE(planePoints(ground, ends, c.radius, kMargin, capsule));
  ASSERT_EQ(capsule.points.size(), 2u);
  EXPECT_NEAR(std::abs(capsule.points[0].position.x()), 0.5, kTol);
  EXPECT_NEAR(capsule.points[1].depth, 0.001, kTol);
}

TEST(PrimitiveContacts, PlaneInWorldFromPose) {
  const WorldPlane w = toWorld(Plane{{0, 0, 2}, 1.0}, at(0, 0, 3));  // z <= 0.5, moved up 3
  EXPECT_TRUE(w.normal.isApprox(Eigen::Vector3d::UnitZ(), kTol));
  EXPECT_NEAR(w.offset, 3.5, kTol);
}

TEST(PrimitiveContacts, CylinderStandingLyingTilted) {
  const WorldPlane ground{Eigen::Vector3d::UnitZ(), 0.0};
  const Cylinder cyl{0.5, 0.5};
  PairContact standing;
  ASSERT_TRUE(planeCylinder(ground, cyl, at(0, 0, 0.499), kMargin, standing));
  EXPECT_EQ(standing.points.size(), 8u);  // the bottom rim, reduced to 4 later
  for (const auto& p : standing.points) EXPECT_NEAR(p.depth, 0.001, kTol);
  PairContact lying;
  ASSERT_TRUE(planeCylinder(ground, cyl,
                            rotated(Eigen::Vector3d::UnitX(), std::numbers::pi / 2, {0, 0, 0.499}),
                            kMargin, lying));
  ASSERT_EQ(lying.points.size(), 2u);  // the deepest point of each rim: a line contact
  for (const auto& p : lying.points) EXPECT_NEAR(p.depth, 0.001, kTol);
  PairContact tilted;  // tilted 30 deg: one exact deepest rim point
  const double t = std::numbers::pi / 6;
  const double lowest = 0.5 * std::cos(t) + 0.5 * std::sin(t);
  ASSERT_TRUE(planeCylinder(
      ground, cyl, rotated(Eigen::Vector3d::UnitX(), t, {0, 0, lowest - 0.002}), kMargin, tilted));
  double deepest = -1;
  for (const auto& p : tilted.points) deepest = std::max(deepest, p.depth);
  EXPECT_NEAR(deepest, 0.002, kTol);
}

TEST(PrimitiveContacts, ClosestSegmentPointsParallelAndSkew) {
  Eigen::Vector3d c1, c2;
  closestSegmentPoints({0, 0, 0}, {1, 0, 0}, {0.5, -1, 1}, {0.5, 1, 1}, c1, c2);
  EXPECT_TRUE(c1.isApprox(Eigen::Vector3d(0.5, 0, 0), kTol));
  EXPECT_TRUE(c2.isApprox(Eigen::Vector3d(0.5, 0, 1), kTol));
  closestSegmentPoints({0, 0, 0}, {1, 0, 0}, {2, 0, 1}, {3, 0, 1}, c1, c2);
  EXPECT_TRUE(c1.isApprox(Eigen::Vector3d(1, 0, 0), kTol));
  EXPECT_TRUE(c2.isApprox(Eigen::Vector3d(2, 0, 1), kTol));
}

}  // namespace
}  // namespace coulomb::geometry
