// Manifolds of the convex pairs without a closed form (geometry/FeatureContacts), through the
// narrow phase as the step calls it (FCL's point and normal, then the supporting features):
// hand-computed rim points, lines, normals and depths. Before these manifolds the same pairs got
// FCL's one point (docs/fcl-notes.md section 2).
#include <coulomb/geometry/FeatureContacts.hpp>
#include <coulomb/geometry/MeshEdges.hpp>
#include <coulomb/geometry/NarrowPhase.hpp>
#include <coulomb/meshes/MakeConvexHull.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <bit>
#include <cmath>
#include <memory>
#include <numbers>

#include "bench/ShapeFixtures.hpp"

namespace coulomb::geometry {
namespace {

constexpr double kMargin = 0.005;
using samples::boxHull;

// A prism of `sides` sides (2 * sides vertices), axis z: a hull too large for HullContacts when
// sides > 32.
ConvexHull prism(int sides, double radius, double half) {
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < sides; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / sides;
    for (const double z : {-half, half})
      points.emplace_back(radius * std::cos(angle), radius * std::sin(angle), z);
  }
  return makeConvexHull(points);
}

Pose turned(const Eigen::Vector3d& axis, double angle, const Eigen::Vector3d& p) {
  return {Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized())), p};
}

// Two colliders in an FclScene, contacted by the narrow phase (a = the lower id).
struct Pair {
  FclScene scene{0.01};
  std::vector<Collider> colliders;
  NarrowPhase narrow;
  PairContact out;
  std::string error;

  bool contact(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb) {
    colliders.clear();
    for (int k = 0; k < 2; ++k) {
      Collider c;
      c.id = ColliderId{static_cast<std::uint32_t>(k), 0};
      c.body = BodyId{static_cast<std::uint32_t>(k), 0};
      c.shape = std::make_shared<const Shape>(k == 0 ? a : b);
      scene.upsert(c.id, c.shape);
      scene.setPose(c.id, k == 0 ? pa : pb);
      colliders.push_back(c);
    }
    scene.updateTree();
    return narrow.contactPair(colliders[0], pa, colliders[1], pb, scene, out, error);
  }
};

double radialDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& centre) {
  return std::hypot(p.x() - centre.x(), p.y() - centre.y());
}

TEST(FeatureContacts, CylinderStandingOnABoxGetsItsRimWithTheFaceNormal) {
  Pair pair;
  const double depth = 1e-3;
  const Eigen::Vector3d centre(0.05, -0.03, 0.1 + 0.3 - depth);
  ASSERT_TRUE(pair.contact(Box{{1.0, 1.0, 0.1}}, Pose::identity(), Cylinder{0.2, 0.3},
                           Pose::translation(centre)))
      << pair.error;
  EXPECT_LT((pair.out.normal - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  ASSERT_GE(pair.out.points.size(), 8u);  // the 8-gon of the rim (reduced to 4 later)
  for (const ContactCandidate& p : pair.out.points) {
    EXPECT_NEAR(p.depth, depth, 1e-12);
    EXPECT_NEAR(radialDistance(p.position, centre), 0.2, 1e-12);
    EXPECT_NEAR(p.position.z(), 0.1 - 0.5 * depth, 1e-12);
  }
}

TEST(FeatureContacts, ExactlyTouchingCylinderStillGetsItsRim) {
  Pair pair;  // FCL finds no overlap and a zero distance: the face axes decide
  ASSERT_TRUE(pair.contact(Box{{1.0, 1.0, 0.1}}, Pose::identity(), Cylinder{0.2, 0.3},
                           Pose::translation({0, 0, 0.4})))
      << pair.error;
  EXPECT_LT((pair.out.normal - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  ASSERT_GE(pair.out.points.size(), 4u);
  for (const ContactCandidate& p : pair.out.points) EXPECT_NEAR(p.depth, 0.0, 1e-12);
}

TEST(FeatureContacts, CylinderHoveringWithinTheMarginGetsSpeculativeRimPoints) {
  Pair pair;
  ASSERT_TRUE(pair.contact(Box{{1.0, 1.0, 0.1}}, Pose::identity(), Cylinder{0.2, 0.3},
                           Pose::translation({0, 0, 0.402})));
  ASSERT_GE(pair.out.points.size(), 4u);
  for (const ContactCandidate& p : pair.out.points) EXPECT_NEAR(p.depth, -0.002, 1e-9);
  Pair far;
  EXPECT_FALSE(far.contact(Box{{1.0, 1.0, 0.1}}, Pose::identity(), Cylinder{0.2, 0.3},
                           Pose::translation({0, 0, 0.41})));
}

TEST(FeatureContacts, CylinderLyingOnABoxTouchesAlongALine) {
  Pair pair;
  const double depth = 5e-4;
  const Pose lying =
      turned(Eigen::Vector3d::UnitY(), std::numbers::pi / 2, {0.1, 0.2, 0.3 - depth});
  ASSERT_TRUE(pair.contact(Box{{1.0, 1.0, 0.1}}, Pose::identity(), Cylinder{0.2, 0.4}, lying));
  EXPECT_LT((pair.out.normal - Eigen::Vector3d::UnitZ()).norm(), 1e-9);
  ASSERT_EQ(pair.out.points.size(), 2u);
  std::vector<double> xs;
  for (const ContactCandidate& p : pair.out.points) {
    EXPECT_NEAR(p.depth, depth, 1e-9);
    EXPECT_NEAR(p.position.y(), 0.2, 1e-9);
    xs.push_back(p.position.x());
  }
  std::sort(xs.begin(), xs.end());
  EXPECT_NEAR(xs[0], 0.1 - 0.4, 1e-9);
  EXPECT_NEAR(xs[1], 0.1 + 0.4, 1e-9);
}

TEST(FeatureContacts, CanOnACanGetsTheCommonRim) {
  Pair pair;
  const double depth = 1e-3;
  ASSERT_TRUE(pair.contact(Cylinder{0.1, 0.2}, Pose::identity(), Cylinder{0.1, 0.2},
                           Pose::translation({0, 0, 0.4 - depth})));
  EXPECT_LT((pair.out.normal - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  ASSERT_GE(pair.out.points.size(), 8u);
  for (const ContactCandidate& p : pair.out.points) {
    EXPECT_NEAR(p.depth, depth, 1e-12);
    EXPECT_NEAR(radialDistance(p.position, Eigen::Vector3d::Zero()), 0.1, 1e-9);
  }
}

TEST(FeatureContacts, TiltedCylinderOnItsRimTouchesAtTheExactDeepestRimPoint) {
  Pair pair;
  // Tilted 30 degrees about an axis that puts the deepest rim point between two 8-gon vertices.
  const double tilt = std::numbers::pi / 6, depth = 1e-3;
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 0.4, 0.0).normalized();
  const Pose pose = turned(axis, tilt, Eigen::Vector3d::Zero());
  // The lowest point of the cylinder: centre - h (axis) - r (radial), put at z = 0.1 - depth.
  const Eigen::Matrix3d r = pose.rotationMatrix();
  const double lowest = -0.3 * std::abs(r(2, 2)) - 0.2 * std::sqrt(1.0 - r(2, 2) * r(2, 2));
  const Pose placed{pose.rotation, {0.0, 0.0, 0.1 - depth - lowest}};
  ASSERT_TRUE(pair.contact(Box{{1.0, 1.0, 0.1}}, Pose::identity(), Cylinder{0.2, 0.3}, placed));
  EXPECT_LT((pair.out.normal - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  const double deepest =
      std::max_element(pair.out.points.begin(), pair.out.points.end(),
                       [](const auto& x, const auto& y) { return x.depth < y.depth; })
          ->depth;
  EXPECT_NEAR(deepest, depth, 1e-12);
  for (const ContactCandidate& p : pair.out.points) EXPECT_LE(p.depth, depth + 1e-12);
}

TEST(FeatureContacts, CapsuleLyingOnAHullTouchesAtBothEnds) {
  Pair pair;
  const double depth = 1e-3;
  ASSERT_TRUE(pair.contact(
      Capsule{0.05, 0.3},
      turned(Eigen::Vector3d::UnitX(), std::numbers::pi / 2, {0.1, 0.0, 0.5 + 0.05 - depth}),
      boxHull({1.0, 1.0, 0.5}), Pose::identity()));
  // a = the capsule, b = the hull below it: the normal points down.
  EXPECT_LT((pair.out.normal + Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  ASSERT_EQ(pair.out.points.size(), 2u);
  for (const ContactCandidate& p : pair.out.points) {
    EXPECT_NEAR(p.depth, depth, 1e-12);
    EXPECT_NEAR(std::abs(p.position.y()), 0.3, 1e-12);
  }
}

TEST(FeatureContacts, CapsuleAcrossACylinderCapTouchesAtTheCapEdges) {
  Pair pair;
  const double depth = 1e-3;
  ASSERT_TRUE(pair.contact(
      Capsule{0.05, 0.5},
      turned(Eigen::Vector3d::UnitY(), std::numbers::pi / 2, {0.0, 0.0, 0.2 + 0.05 - depth}),
      Cylinder{0.2, 0.2}, Pose::identity()));
  EXPECT_LT((pair.out.normal + Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  ASSERT_EQ(pair.out.points.size(), 2u);
  for (const ContactCandidate& p : pair.out.points) {
    EXPECT_NEAR(p.depth, depth, 1e-12);
    EXPECT_NEAR(std::abs(p.position.x()), 0.2,
                1e-3);  // at the 8-gon vertex on the x axis (clip slop)
  }
}

TEST(FeatureContacts, CylinderStandingOnAHullAndALargeHullOnABox) {
  Pair pair;
  ASSERT_TRUE(pair.contact(Cylinder{0.2, 0.3}, Pose::translation({0, 0, 0.5 + 0.3 - 1e-3}),
                           boxHull({1.0, 1.0, 0.5}), Pose::identity()));
  EXPECT_GE(pair.out.points.size(), 8u);
  Pair large;  // 80 vertices: beyond kMaxClippedHullVertices, so FCL's point before this
  ASSERT_TRUE(large.contact(Box{{1.0, 1.0, 0.1}}, Pose::identity(), prism(40, 0.3, 0.2),
                            Pose::translation({0, 0, 0.3 - 1e-3})));
  EXPECT_LT((large.out.normal - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  EXPECT_GE(large.out.points.size(), 40u);
  for (const ContactCandidate& p : large.out.points) EXPECT_NEAR(p.depth, 1e-3, 1e-12);
}

TEST(FeatureContacts, CrossedCylindersKeepFclsSinglePoint) {
  Pair pair;  // curved against curved: no face, no line; FCL's point and normal stand
  ASSERT_TRUE(pair.contact(
      Cylinder{0.1, 0.5},
      turned(Eigen::Vector3d::UnitY(), std::numbers::pi / 2, Eigen::Vector3d::Zero()),
      Cylinder{0.1, 0.5}, turned(Eigen::Vector3d::UnitX(), std::numbers::pi / 2, {0, 0, 0.199})));
  ASSERT_EQ(pair.out.points.size(), 1u);
  EXPECT_NEAR(pair.out.points[0].depth, 1e-3, 1e-6);
  EXPECT_GT(pair.out.normal.z(), 0.999);
}

TEST(MeshEdges, FlatAndConcaveEdgesAreInternalConvexAndOpenOnesActive) {
  // A unit cube as 12 triangles: its face diagonals are flat (internal), its 12 edges convex.
  TriangleMesh cube;
  for (int c = 0; c < 8; ++c) cube.vertices.emplace_back(c & 1, (c >> 1) & 1, (c >> 2) & 1);
  cube.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  const MeshSurface surface = meshSurface(cube);
  const std::vector<std::uint8_t>& flags = surface.activeEdges;
  int active = 0;
  for (const std::uint8_t f : flags) active += std::popcount(static_cast<unsigned>(f));
  EXPECT_EQ(active, 24);  // 12 convex edges, each seen from its two triangles
  for (const std::uint8_t f : flags) EXPECT_EQ(std::popcount(static_cast<unsigned>(f)), 2);
  // Each face (two triangles across a flat diagonal) is one smooth patch, named by its first
  // triangle; the convex edges separate them.
  for (std::size_t t = 0; t < cube.triangles.size(); ++t)
    EXPECT_EQ(surface.patch[t], static_cast<std::uint32_t>(t & ~std::size_t{1}))
        << "triangle " << t;
}

TEST(MeshEdges, AConcaveRunOfFacetsIsOnePatch) {
  // Two quads folded towards their front (concave seen from it) and a third folded back
  // (convex): the first two are one patch, the third another.
  TriangleMesh strip;
  strip.vertices = {{0, 0, 0},   {0, 1, 0},   {1, 0, 0}, {1, 1, 0},
                    {2, 0, 0.3}, {2, 1, 0.3}, {3, 0, 0}, {3, 1, 0}};
  strip.triangles = {{0, 2, 3}, {0, 3, 1}, {2, 4, 5}, {2, 5, 3}, {4, 6, 7}, {4, 7, 5}};
  const MeshSurface surface = meshSurface(strip);
  EXPECT_EQ(surface.patch, (std::vector<std::uint32_t>{0, 0, 0, 0, 4, 4}));
  EXPECT_EQ(surface.activeEdges[2] & 0x2, 0x2);  // the crease at x = 2 (edge 4-5 of triangle 2)
}

}  // namespace
}  // namespace coulomb::geometry
