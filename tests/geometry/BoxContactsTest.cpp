// Box-box and box-capsule manifolds against hand-computed corners, normals and depths.
#include <coulomb/geometry/BoxContacts.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace coulomb::geometry {
namespace {

constexpr double kTol = 1e-12;
constexpr double kMargin = 0.005;

Pose rotated(const Eigen::Vector3d& axis, double angle, const Eigen::Vector3d& p) {
  return {Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized())), p};
}

bool hasPoint(const PairContact& c, const Eigen::Vector3d& p, double tol = 1e-9) {
  return std::any_of(c.points.begin(), c.points.end(),
                     [&](const ContactCandidate& q) { return (q.position - p).norm() < tol; });
}

TEST(BoxContacts, BoxOnBoxGivesTheFourCornersInTheFirstStep) {
  PairContact out;  // unit box resting 1 mm into a unit box below it
  ASSERT_TRUE(
      boxBox(Box{}, Pose::identity(), Box{}, Pose::translation({0, 0, 0.999}), kMargin, out));
  ASSERT_EQ(out.points.size(), 4u);
  EXPECT_TRUE(out.normal.isApprox(Eigen::Vector3d::UnitZ(), kTol));
  for (double x : {-0.5, 0.5})
    for (double y : {-0.5, 0.5}) EXPECT_TRUE(hasPoint(out, {x, y, 0.4995}));
  for (const auto& p : out.points) EXPECT_NEAR(p.depth, 0.001, kTol);
}

// The separating-axis decision against the 15 axes' separations computed in the world frame
// (|axis . d| - the two projected radii): random sizes, orientations and offsets straddling
// contact. Beyond the margin along some axis there is no contact; clearly overlapping boxes
// (every axis at least 1 mm deep) always give one, with a unit normal from A toward B.
TEST(BoxContacts, SeparatingAxisDecisionMatchesTheWorldFrameAxes) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), size(0.05, 0.6);
  int separated = 0, overlapping = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Box a{Eigen::Vector3d(size(rng), size(rng), size(rng))};
    const Box b{Eigen::Vector3d(size(rng), size(rng), size(rng))};
    const Eigen::Vector3d axis(unit(rng), unit(rng), unit(rng));
    const Eigen::Vector3d offset = Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized() *
                                   (0.2 + 0.8 * std::abs(unit(rng)));
    const Pose pa =
        rotated(Eigen::Vector3d(unit(rng), unit(rng), unit(rng)), 3 * unit(rng), {0, 0, 0});
    const Pose pb = rotated(axis, 3 * unit(rng), offset);
    const Eigen::Matrix3d ra = pa.rotationMatrix(), rb = pb.rotationMatrix();
    auto radius = [](const Box& box, const Eigen::Matrix3d& r, const Eigen::Vector3d& n) {
      return (r.transpose() * n).cwiseAbs().dot(box.halfExtents);
    };
    double worst = -1e300;  // the largest separation over the 15 axes
    std::vector<Eigen::Vector3d> axes;
    for (int i = 0; i < 3; ++i) axes.push_back(ra.col(i)), axes.push_back(rb.col(i));
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const Eigen::Vector3d c = ra.col(i).cross(rb.col(j));
        if (c.norm() > 1e-6) axes.push_back(c.normalized());
      }
    for (const Eigen::Vector3d& n : axes)
      worst = std::max(worst, std::abs(n.dot(offset)) - radius(a, ra, n) - radius(b, rb, n));
    PairContact out;
    const bool touching = boxBox(a, pa, b, pb, kMargin, out);
    if (worst > kMargin + 1e-9) {
      ++separated;
      EXPECT_FALSE(touching) << "trial " << trial << ": separated by " << worst;
    } else if (worst < -1e-3) {
      ++overlapping;
      ASSERT_TRUE(touching) << "trial " << trial << ": overlapping by " << -worst;
      EXPECT_NEAR(out.normal.norm(), 1.0, 1e-12);
      EXPECT_GE(out.normal.dot(offset), -1e-12) << "trial " << trial;
    }
  }
  EXPECT_GT(separated, 500);
  EXPECT_GT(overlapping, 500);
}

TEST(BoxContacts, NormalPointsFromAToBWhicheverIsOnTop) {
  PairContact out;
  ASSERT_TRUE(
      boxBox(Box{}, Pose::translation({0, 0, 0.999}), Box{}, Pose::identity(), kMargin, out));
  EXPECT_TRUE(out.normal.isApprox(-Eigen::Vector3d::UnitZ(), kTol));
  EXPECT_EQ(out.points.size(), 4u);
}

TEST(BoxContacts, SmallBoxOnSlabUsesTheSmallFace) {
  PairContact out;
  const Box slab{{2.0, 2.0, 0.1}}, small{{0.2, 0.1, 0.1}};
  ASSERT_TRUE(
      boxBox(slab, Pose::identity(), small, Pose::translation({0.5, 0.5, 0.199}), kMargin, out));
  ASSERT_EQ(out.points.size(), 4u);
  for (double x : {0.3, 0.7})
    for (double y : {0.4, 0.6}) EXPECT_TRUE(hasPoint(out, {x, y, 0.0995}));
}

TEST(BoxContacts, OverhangClipsToTheOverlap) {
  PairContact out;
  ASSERT_TRUE(
      boxBox(Box{}, Pose::identity(), Box{}, Pose::translation({0.5, 0, 0.999}), kMargin, out));
  ASSERT_EQ(out.points.size(), 4u);
  for (double x : {0.0, 0.5})
    for (double y : {-0.5, 0.5}) EXPECT_TRUE(hasPoint(out, {x, y, 0.4995}));
}

TEST(BoxContacts, RotatedTopBoxGivesTheOctagonBeforeReduction) {
  PairContact out;
  ASSERT_TRUE(boxBox(Box{}, Pose::identity(), Box{},
                     rotated(Eigen::Vector3d::UnitZ(), std::numbers::pi / 4, {0, 0, 0.999}),
                     kMargin, out));
  EXPECT_EQ(out.points.size(), 8u);  // ManifoldBuilder reduces these to 4
  for (const auto& p : out.points) EXPECT_NEAR(p.depth, 0.001, kTol);
}

TEST(BoxContacts, TiltedBoxRestsOnAnEdgeWithTwoPoints) {
  const double tilt = 5.0 * std::numbers::pi / 180.0;
  // Lowest edge (x = -0.5 side after tilting about y) 1 mm into the top face at z = 0.5.
  const double lowest = 0.5 * std::cos(tilt) + 0.5 * std::sin(tilt);
  PairContact out;
  ASSERT_TRUE(boxBox(Box{}, Pose::identity(), Box{},
                     rotated(Eigen::Vector3d::UnitY(), tilt, {0, 0, 0.5 + lowest - 0.001}), kMargin,
                     out));
  ASSERT_EQ(out.points.size(), 2u);
  EXPECT_TRUE(out.normal.isApprox(Eigen::Vector3d::UnitZ(), kTol));
  for (const auto& p : out.points) EXPECT_NEAR(p.depth, 0.001, 1e-12);
}

TEST(BoxContacts, SpeculativePointsWithinTheMargin) {
  PairContact out;
  ASSERT_TRUE(
      boxBox(Box{}, Pose::identity(), Box{}, Pose::translation({0, 0, 1.002}), kMargin, out));
  ASSERT_EQ(out.points.size(), 4u);
  for (const auto& p : out.points) EXPECT_NEAR(p.depth, -0.002, kTol);
  PairContact apart;
  EXPECT_FALSE(
      boxBox(Box{}, Pose::identity(), Box{}, Pose::translation({0, 0, 1.01}), kMargin, apart));
}

TEST(BoxContacts, EdgeOnEdgeGivesOnePoint) {
  // Box a rotated 45 deg about x, box b rotated 45 deg about z, stacked so their edges cross.
  const Pose a = rotated(Eigen::Vector3d::UnitX(), std::numbers::pi / 4, {0, 0, 0});
  const double h = 0.5 * std::sqrt(2.0);
  const Pose b{
      Eigen::Quaterniond(Eigen::AngleAxisd(std::numbers::pi / 4, Eigen::Vector3d::UnitY())),
      {0, 0, 2 * h - 0.001}};
  PairContact out;
  ASSERT_TRUE(boxBox(Box{}, a, Box{}, b, kMargin, out));
  ASSERT_EQ(out.points.size(), 1u);
  EXPECT_TRUE(out.normal.isApprox(Eigen::Vector3d::UnitZ(), 1e-9));
  EXPECT_NEAR(out.points[0].depth, 0.001, 1e-9);
  EXPECT_TRUE(out.points[0].position.isApprox(Eigen::Vector3d(0, 0, h - 0.0005), 1e-9));
  EXPECT_EQ(out.points[0].featureId >> 30, 1u);
}

TEST(BoxContacts, FeatureIdsAreStableUnderTinyMotion) {
  PairContact first, second;
  ASSERT_TRUE(
      boxBox(Box{}, Pose::identity(), Box{}, Pose::translation({0, 0, 0.999}), kMargin, first));
  ASSERT_TRUE(boxBox(Box{}, Pose::identity(), Box{},
                     rotated(Eigen::Vector3d(1, 2, 3), 1e-4, {1e-5, -2e-5, 0.9991}), kMargin,
                     second));
  ASSERT_EQ(first.points.size(), second.points.size());
  std::vector<std::uint32_t> a, b;
  for (const auto& p : first.points) a.push_back(p.featureId);
  for (const auto& p : second.points) b.push_back(p.featureId);
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
}

TEST(BoxContacts, CapsuleLyingOnABoxGivesTwoPoints) {
  const Capsule c{0.1, 0.4};
  PairContact out;
  ASSERT_EQ(boxCapsule(Box{}, Pose::identity(), c,
                       rotated(Eigen::Vector3d::UnitY(), std::numbers::pi / 2, {0.2, 0.2, 0.599}),
                       kMargin, out),
            BoxCapsuleResult::Touching);
  ASSERT_EQ(out.points.size(), 2u);
  EXPECT_TRUE(out.normal.isApprox(Eigen::Vector3d::UnitZ(), kTol));
  EXPECT_TRUE(hasPoint(out, {-0.2, 0.2, 0.4995}));
  EXPECT_TRUE(hasPoint(out, {0.5, 0.2, 0.4995}));  // clipped at the box edge x = 0.5
  for (const auto& p : out.points) EXPECT_NEAR(p.depth, 0.001, 1e-9);
}

TEST(BoxContacts, CapsuleStandingAndOnAnEdge) {
  const Capsule c{0.1, 0.4};
  PairContact standing;
  ASSERT_EQ(
      boxCapsule(Box{}, Pose::identity(), c, Pose::translation({0.2, 0, 0.999}), kMargin, standing),
      BoxCapsuleResult::Touching);
  ASSERT_EQ(standing.points.size(), 1u);
  EXPECT_NEAR(standing.points[0].depth, 0.001, 1e-9);
  EXPECT_TRUE(standing.points[0].position.isApprox(Eigen::Vector3d(0.2, 0, 0.4995), 1e-9));

  PairContact edge;  // capsule along y, beside the +x/+z edge on the diagonal
  const double s = 0.099 / std::sqrt(2.0);
  ASSERT_EQ(
      boxCapsule(Box{}, Pose::identity(), c,
                 rotated(Eigen::Vector3d::UnitX(), std::numbers::pi / 2, {0.5 + s, 0, 0.5 + s}),
                 kMargin, edge),
      BoxCapsuleResult::Touching);
  ASSERT_EQ(edge.points.size(), 1u);
  EXPECT_TRUE(edge.normal.isApprox(Eigen::Vector3d(1, 0, 1).normalized(), 1e-6));
  EXPECT_NEAR(edge.points[0].depth, 0.001, 1e-6);
}

TEST(BoxContacts, CapsuleAxisInsideTheBoxIsLeftToFcl) {
  PairContact out;
  EXPECT_EQ(boxCapsule(Box{}, Pose::identity(), Capsule{0.1, 0.4}, Pose::translation({0, 0, 0.3}),
                       kMargin, out),
            BoxCapsuleResult::AxisInsideBox);
}

}  // namespace
}  // namespace coulomb::geometry
