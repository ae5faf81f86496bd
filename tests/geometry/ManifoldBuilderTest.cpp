// Reduction to 4 points, polygon clipping ids, tangent frame and the final manifold.
#include <coulomb/geometry/ManifoldBuilder.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

namespace coulomb::geometry {
namespace {

std::vector<ContactCandidate> octagon() {
  std::vector<ContactCandidate> points;
  for (int k = 0; k < 8; ++k) {
    const double a = k * std::numbers::pi / 4;
    points.push_back({{std::cos(a), std::sin(a), 0.0}, 0.001, static_cast<std::uint32_t>(10 + k)});
  }
  return points;
}

TEST(ManifoldBuilder, ReducesAnOctagonToFourSpreadPoints) {
  auto points = octagon();
  reduceToFour(Eigen::Vector3d::UnitZ(), points);
  ASSERT_EQ(points.size(), 4u);
  // Equal depths: the lowest id starts; the result spans a square (area 2 for a unit octagon).
  EXPECT_EQ(points[0].featureId, 10u);
  const Eigen::Vector3d c =
      0.25 * (points[0].position + points[1].position + points[2].position + points[3].position);
  EXPECT_NEAR(c.norm(), 0.0, 1e-12);
}

TEST(ManifoldBuilder, ReductionDoesNotDependOnInputOrder) {
  auto reference = octagon();
  reference[5].depth = 0.002;  // one deeper point must survive
  auto shuffled = reference;
  std::reverse(shuffled.begin(), shuffled.end());
  std::rotate(shuffled.begin(), shuffled.begin() + 3, shuffled.end());
  reduceToFour(Eigen::Vector3d::UnitZ(), reference);
  reduceToFour(Eigen::Vector3d::UnitZ(), shuffled);
  ASSERT_EQ(reference.size(), shuffled.size());
  for (std::size_t i = 0; i < reference.size(); ++i)
    EXPECT_EQ(reference[i].featureId, shuffled[i].featureId);
  EXPECT_TRUE(std::any_of(reference.begin(), reference.end(),
                          [](const auto& p) { return p.featureId == 15u; }));
}

TEST(ManifoldBuilder, ClipKeepsInsideVerticesAndNamesNewOnes) {
  ClipPolygon square;
  square.vertices[0] = {{-1, -1, 0}, 0};
  square.vertices[1] = {{1, -1, 0}, 1};
  square.vertices[2] = {{1, 1, 0}, 2};
  square.vertices[3] = {{-1, 1, 0}, 3};
  square.count = 4;
  clipPolygon(square, Eigen::Vector3d::UnitX(), 0.5, 2);
  ASSERT_EQ(square.size(), 4u);
  EXPECT_EQ(square[0].id, 0u);
  EXPECT_EQ(square[1].id, 0x100u | (2u << 4) | 0u);  // on edge 0 (from vertex 0 to 1)
  EXPECT_TRUE(square[1].position.isApprox(Eigen::Vector3d(0.5, -1, 0)));
  EXPECT_EQ(square[2].id, 0x100u | (2u << 4) | 2u);  // on edge 2
  EXPECT_EQ(square[3].id, 3u);
}

TEST(ManifoldBuilder, TangentFrameIsOrthonormalAndRightHanded) {
  for (const Eigen::Vector3d& n :
       {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(1, 2, 3).normalized(),
        Eigen::Vector3d(0.3, -0.1, -0.9).normalized()}) {
    Eigen::Vector3d t1, t2;
    makeTangentFrame(n, t1, t2);
    EXPECT_NEAR(t1.norm(), 1.0, 1e-14);
    EXPECT_NEAR(t1.dot(n), 0.0, 1e-14);
    EXPECT_TRUE(n.cross(t1).isApprox(t2, 1e-14));
  }
}

TEST(ManifoldBuilder, FinishCombinesMaterialsAndAnchorsPoints) {
  Collider a, b;
  a.id = {1, 0};
  b.id = {2, 0};
  a.body = {0, 0};
  b.body = {1, 0};
  a.material = {0.4, 0.1};
  b.material = {0.9, 0.5};
  PairContact raw;
  raw.normal = Eigen::Vector3d::UnitZ();
  raw.points = octagon();
  const Pose poseB = Pose::translation({0, 0, 2});
  const ContactManifold m = finishManifold(raw, a, b, Pose::identity(), poseB);
  EXPECT_EQ(m.pointCount, 4);
  EXPECT_NEAR(m.friction, 0.6, 1e-14);
  EXPECT_NEAR(m.restitution, 0.5, 1e-14);
  for (const ContactPoint& p : m.activePoints()) {
    EXPECT_TRUE(p.localA.isApprox(p.position));
    EXPECT_TRUE(p.localB.isApprox(p.position - Eigen::Vector3d(0, 0, 2)));
  }
}

}  // namespace
}  // namespace coulomb::geometry
