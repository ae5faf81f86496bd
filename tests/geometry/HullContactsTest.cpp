// Hull-hull and box-hull manifolds (geometry/HullContacts) against hand-computed corners, normals
// and depths, and against boxBox for the same geometry: exactly touching faces get their full
// face contact (FCL gives none there), tilted faces their own normal, crossing edges one point.
#include <coulomb/geometry/BoxContacts.hpp>
#include <coulomb/geometry/HullContacts.hpp>
#include <coulomb/meshes/MakeConvexHull.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace coulomb::geometry {
namespace {

constexpr double kTol = 1e-12;
constexpr double kMargin = 0.005;

ConvexHull cubeHull(double half) {
  std::vector<Eigen::Vector3d> points;
  for (int c = 0; c < 8; ++c)
    points.emplace_back(c & 1 ? half : -half, c & 2 ? half : -half, c & 4 ? half : -half);
  return makeConvexHull(points);
}

// A wedge-shaped voussoir: a trapezoid in x-z extruded along y, its two joint faces tilted by
// +-`tilt` from the vertical (like a block of an arch).
ConvexHull wedge(double tilt) {
  const double bottom = 0.5, top = 0.5 + std::tan(tilt), h = 1.0, depth = 0.5;
  std::vector<Eigen::Vector3d> points;
  for (const double y : {-depth, depth}) {
    points.emplace_back(-bottom, y, 0.0);
    points.emplace_back(bottom, y, 0.0);
    points.emplace_back(top, y, h);
    points.emplace_back(-top, y, h);
  }
  return makeConvexHull(points);
}

Pose rotated(const Eigen::Vector3d& axis, double angle, const Eigen::Vector3d& p) {
  return {Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized())), p};
}

bool hasPoint(const PairContact& c, const Eigen::Vector3d& p, double tol = 1e-9) {
  return std::any_of(c.points.begin(), c.points.end(),
                     [&](const ContactCandidate& q) { return (q.position - p).norm() < tol; });
}

TEST(HullContacts, ExactlyTouchingCubesGetTheirFourCornersAtZeroDepth) {
  PairContact out;
  const ConvexHull cube = cubeHull(0.5);
  ASSERT_EQ(hullHull(cube, Pose::identity(), cube, Pose::translation({0, 0, 1.0}), kMargin, out),
            1);
  ASSERT_EQ(out.points.size(), 4u);
  EXPECT_TRUE(out.normal.isApprox(Eigen::Vector3d::UnitZ(), kTol));
  for (double x : {-0.5, 0.5})
    for (double y : {-0.5, 0.5}) EXPECT_TRUE(hasPoint(out, {x, y, 0.5}));
  for (const auto& p : out.points) EXPECT_NEAR(p.depth, 0.0, kTol);
}

TEST(HullContacts, BoxOnHullMatchesBoxOnBox) {
  // A unit box 1 mm into a unit-cube hull, yawed by 30 degrees: the same points, depths and
  // normal as the box-box routine gives for two boxes.
  const Pose top = rotated(Eigen::Vector3d::UnitZ(), std::numbers::pi / 6, {0.1, -0.05, 0.999});
  PairContact hull, box;
  ASSERT_EQ(boxHull(Box{}, top, cubeHull(0.5), Pose::identity(), kMargin, hull), 1);
  ASSERT_TRUE(boxBox(Box{}, top, Box{}, Pose::identity(), kMargin, box));
  EXPECT_TRUE(hull.normal.isApprox(box.normal, 1e-12));
  EXPECT_TRUE(hull.normal.isApprox(-Eigen::Vector3d::UnitZ(), 1e-12));
  ASSERT_EQ(hull.points.size(), box.points.size());
  for (const ContactCandidate& p : box.points) {
    EXPECT_TRUE(hasPoint(hull, p.position, 1e-9)) << p.position.transpose();
  }
  for (const auto& p : hull.points) EXPECT_NEAR(p.depth, 0.001, 1e-12);
}

TEST(HullContacts, TiltedJointFacesGiveTheirOwnNormal) {
  // Two wedges side by side sharing a joint face tilted 10 degrees from the vertical, exactly
  // touching: four points on the shared face, normal = the face's normal (FCL gave (0, 0, -1)
  // or nothing for the arch's joints).
  const double tilt = 10.0 * std::numbers::pi / 180.0;
  const ConvexHull block = wedge(tilt);
  // The right face of the left wedge runs from (0.5, 0) to (0.5 + tan, 1). The same wedge turned
  // upside down (by pi about y) and moved so that its bottom is at z = 1 has a left face from
  // (shift - 0.5 - tan, 1) to (shift - 0.5, 0): with shift = 1 + tan the two faces coincide.
  const double shift = 1.0 + std::tan(tilt);
  PairContact out;
  const Pose flipped = rotated(Eigen::Vector3d::UnitY(), std::numbers::pi, {shift, 0.0, 1.0});
  ASSERT_EQ(hullHull(block, Pose::identity(), block, flipped, kMargin, out), 1);
  const Eigen::Vector3d faceNormal(std::cos(tilt), 0.0, -std::sin(tilt));
  EXPECT_TRUE(out.normal.isApprox(faceNormal, 1e-12)) << out.normal.transpose();
  EXPECT_EQ(out.points.size(), 4u);
  for (const auto& p : out.points) {
    EXPECT_NEAR(p.depth, 0.0, 1e-12);
    EXPECT_NEAR(faceNormal.dot(p.position - Eigen::Vector3d(0.5, 0.0, 0.0)), 0.0, 1e-12);
  }
}

TEST(HullContacts, CrossingEdgesGiveOnePointOnTheEdgeAxis) {
  // A cube hull turned 45 degrees about x and lifted onto a cube hull turned 45 degrees about y:
  // their edges cross at right angles, 1 mm into each other.
  const double r = 0.5 * std::sqrt(2.0);
  const Pose lower = rotated(Eigen::Vector3d::UnitY(), std::numbers::pi / 4, {0, 0, 0});
  const Pose upper = rotated(Eigen::Vector3d::UnitX(), std::numbers::pi / 4, {0, 0, 2 * r - 0.001});
  PairContact out;
  const ConvexHull cube = cubeHull(0.5);
  ASSERT_EQ(hullHull(cube, lower, cube, upper, kMargin, out), 1);
  ASSERT_EQ(out.points.size(), 1u);
  EXPECT_TRUE(out.normal.isApprox(Eigen::Vector3d::UnitZ(), 1e-9)) << out.normal.transpose();
  EXPECT_NEAR(out.points[0].depth, 0.001, 1e-9);
  EXPECT_TRUE(out.points[0].position.isApprox(Eigen::Vector3d(0, 0, r - 0.0005), 1e-9));
}

TEST(HullContacts, SeparatedBeyondTheMarginGivesNothingWithinItASpeculativeContact) {
  PairContact out;
  const ConvexHull cube = cubeHull(0.5);
  EXPECT_EQ(hullHull(cube, Pose::identity(), cube, Pose::translation({0, 0, 1.01}), kMargin, out),
            0);
  EXPECT_TRUE(out.points.empty());
  ASSERT_EQ(hullHull(cube, Pose::identity(), cube, Pose::translation({0, 0, 1.002}), kMargin, out),
            1);
  for (const auto& p : out.points) EXPECT_NEAR(p.depth, -0.002, 1e-12);
}

TEST(HullContacts, LargeHullsAreLeftToFcl) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 200; ++i) {
    const double t = 2.0 * std::numbers::pi * i / 200.0;
    points.emplace_back(std::cos(t), std::sin(t), i % 2 == 0 ? 0.5 : -0.5);
  }
  const ConvexHull big = makeConvexHull(points);
  ASSERT_GT(big.vertices.size(), kMaxClippedHullVertices);
  PairContact out;
  EXPECT_EQ(
      hullHull(big, Pose::identity(), cubeHull(0.5), Pose::translation({0, 0, 1}), kMargin, out),
      -1);
}

// makeConvexHull builds the faces once: wedges of an arch get one polygonal face per joint (a
// quadrilateral from two triangles), and each edge once.
TEST(HullContacts, MakeConvexHullMergesCoplanarTrianglesIntoFaces) {
  const ConvexHull block = wedge(0.1);
  ASSERT_EQ(block.faces.size(), 6u);
  for (const HullFace& face : block.faces) {
    EXPECT_EQ(face.loop.size(), 4u);
    for (const int v : face.loop)
      EXPECT_NEAR(face.normal.dot(block.vertices[static_cast<std::size_t>(v)]), face.offset, 1e-12);
  }
  EXPECT_EQ(block.edges.size(), 12u);
}

// A hull given with triangles but without faces (built by hand) gets the same manifold: the
// query builds the faces itself, and a kept scratch answers the same on reuse.
TEST(HullContacts, HullWithoutFacesGivesTheSameManifold) {
  const ConvexHull block = wedge(0.1);
  ConvexHull bare;
  bare.vertices = block.vertices;
  bare.triangles = block.triangles;
  const Pose upper = rotated({1, 0.3, 0}, 0.05, {0.1, 0.05, 1.0 - 1e-3});
  PairContact withFaces, withoutFaces, again;
  ASSERT_EQ(hullHull(block, Pose::identity(), block, upper, kMargin, withFaces), 1);
  HullScratch scratch;
  ASSERT_EQ(hullHull(bare, Pose::identity(), bare, upper, kMargin, withoutFaces, scratch), 1);
  ASSERT_EQ(hullHull(block, Pose::identity(), block, upper, kMargin, again, scratch), 1);
  ASSERT_EQ(withFaces.points.size(), withoutFaces.points.size());
  ASSERT_EQ(withFaces.points.size(), again.points.size());
  EXPECT_TRUE(withFaces.normal.isApprox(withoutFaces.normal, 1e-12));
  for (std::size_t k = 0; k < withFaces.points.size(); ++k) {
    EXPECT_TRUE(withFaces.points[k].position.isApprox(withoutFaces.points[k].position, 1e-12));
    EXPECT_EQ(withFaces.points[k].featureId, again.points[k].featureId);
  }
}

}  // namespace
}  // namespace coulomb::geometry
