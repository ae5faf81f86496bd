// Warm starts: impulses follow feature ids, else proximity; a flipped normal drops them.
#include <coulomb/geometry/ContactCache.hpp>

#include <gtest/gtest.h>

namespace coulomb::geometry {
namespace {

ContactManifold manifold(std::uint32_t a, std::uint32_t b,
                         std::initializer_list<std::uint32_t> ids) {
  ContactManifold m;
  m.colliderA = {a, 0};
  m.colliderB = {b, 0};
  m.bodyA = {0, 0};
  m.bodyB = {1, 0};
  int k = 0;
  for (std::uint32_t id : ids) {
    ContactPoint& p = m.points[static_cast<std::size_t>(k)];
    p.featureId = id;
    p.position = Eigen::Vector3d(k, 0, 0);
    p.localA = p.localB = p.position;
    ++k;
  }
  m.pointCount = k;
  return m;
}

const std::vector<Pose> kPoses{Pose::identity(), Pose::identity()};

const std::vector<ContactManifold>& refresh(ContactCache& cache,
                                            std::vector<ContactManifold> fresh) {
  return cache.refresh(fresh, kPoses);
}

TEST(ContactCache, CarriesImpulsesByFeatureId) {
  ContactCache cache;
  refresh(cache, {manifold(1, 2, {10, 11, 12})});
  for (ContactPoint& p : cache.manifolds()[0].activePoints()) {
    p.normalImpulse = p.featureId * 1.0;
    p.tangentImpulse = Eigen::Vector2d(p.featureId, -1.0 * p.featureId);
  }
  auto next = manifold(1, 2, {12, 10, 99});  // same features in another order, plus a new one
  next.points[2].position = next.points[2].localA = next.points[2].localB = {50, 0, 0};
  const auto& out = refresh(cache, {next});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_DOUBLE_EQ(out[0].points[0].normalImpulse, 12.0);
  EXPECT_DOUBLE_EQ(out[0].points[1].normalImpulse, 10.0);
  EXPECT_DOUBLE_EQ(out[0].points[1].tangentImpulse.y(), -10.0);
  EXPECT_TRUE(out[0].points[0].warmStarted);
  EXPECT_FALSE(out[0].points[2].warmStarted);
  EXPECT_DOUBLE_EQ(out[0].points[2].normalImpulse, 0.0);
}

TEST(ContactCache, FallsBackToProximityWhenTheIdChanged) {
  ContactCache cache;
  refresh(cache, {manifold(1, 2, {10})});
  cache.manifolds()[0].points[0].normalImpulse = 3.0;
  auto moved = manifold(1, 2, {20});
  moved.points[0].position = {0.001, 0, 0};
  EXPECT_DOUBLE_EQ(refresh(cache, {moved})[0].points[0].normalImpulse, 3.0);
  cache.manifolds()[0].points[0].normalImpulse = 4.0;
  auto far = manifold(1, 2, {30});
  far.points[0].position = {0.5, 0, 0};
  EXPECT_DOUBLE_EQ(refresh(cache, {far})[0].points[0].normalImpulse, 0.0);
}

TEST(ContactCache, FlippedNormalDropsTheWarmStart) {
  ContactCache cache;
  refresh(cache, {manifold(1, 2, {10})});
  cache.manifolds()[0].points[0].normalImpulse = 3.0;
  auto flipped = manifold(1, 2, {10});
  flipped.normal = -flipped.normal;
  EXPECT_DOUBLE_EQ(refresh(cache, {flipped})[0].points[0].normalImpulse, 0.0);
}

TEST(ContactCache, SortedByCollidersAndPairsNeverMix) {
  ContactCache cache;
  refresh(cache, {manifold(3, 4, {1}), manifold(1, 2, {1})});
  cache.manifolds()[0].points[0].normalImpulse = 12.0;  // pair (1,2)
  cache.manifolds()[1].points[0].normalImpulse = 34.0;  // pair (3,4)
  auto other = manifold(1, 5, {1});
  other.bodyB = {2, 0};  // another body: no hand-over from (1,2) either
  const auto& out = refresh(cache, {manifold(3, 4, {1}), other});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].colliderB.index, 5u);
  EXPECT_DOUBLE_EQ(out[0].points[0].normalImpulse, 0.0);
  EXPECT_DOUBLE_EQ(out[1].points[0].normalImpulse, 34.0);
}

// A ball rolling from capsule 2 onto capsule 5 of the same rail body: the new one-point manifold
// takes over the ended one's impulses, the tangent impulse re-expressed in the new tangent frame.
TEST(ContactCache, HandsOverAnEndedOnePointManifoldOfTheSameBodies) {
  ContactCache cache;
  auto first = manifold(1, 2, {0});
  first.normal = Eigen::Vector3d(0.3, 0.2, 0.9).normalized();
  makeTangentFrame(first.normal, first.tangent1, first.tangent2);
  refresh(cache, {first});
  cache.manifolds()[0].points[0].normalImpulse = 2.0;
  cache.manifolds()[0].points[0].tangentImpulse = {0.5, -0.25};
  const Eigen::Vector3d world = 0.5 * first.tangent1 - 0.25 * first.tangent2;
  auto next = manifold(1, 5, {0});
  next.normal = Eigen::Vector3d(0.32, 0.2, 0.9).normalized();  // 1.2 degrees further on
  makeTangentFrame(next.normal, next.tangent1, next.tangent2);
  auto far = manifold(1, 6, {0});  // the other rail: its normal is 54 degrees away
  far.normal = Eigen::Vector3d(-0.3, 0.2, 0.9).normalized();
  makeTangentFrame(far.normal, far.tangent1, far.tangent2);
  const auto& out = refresh(cache, {next, far});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_TRUE(out[0].points[0].warmStarted);
  EXPECT_DOUBLE_EQ(out[0].points[0].normalImpulse, 2.0);
  const Eigen::Vector3d carried = out[0].points[0].tangentImpulse.x() * next.tangent1 +
                                  out[0].points[0].tangentImpulse.y() * next.tangent2;
  // The tangent part of the old world impulse that lies in the new tangent plane.
  EXPECT_NEAR((carried - (world - world.dot(next.normal) * next.normal)).norm(), 0.0, 1e-12);
  EXPECT_FALSE(out[1].points[0].warmStarted);
  EXPECT_DOUBLE_EQ(out[1].points[0].normalImpulse, 0.0);
}

// Where n_z changes sign the tangent frame (Duff et al.) flips: the warm start follows the world
// direction, not the frame's coefficients.
TEST(ContactCache, RotatesTheTangentImpulseIntoTheNewFrame) {
  ContactCache cache;
  auto before = manifold(1, 2, {0});
  before.normal = Eigen::Vector3d(1.0, 0.0, 1e-3).normalized();
  makeTangentFrame(before.normal, before.tangent1, before.tangent2);
  refresh(cache, {before});
  cache.manifolds()[0].points[0].tangentImpulse = {1.0, 0.0};
  auto after = manifold(1, 2, {0});
  after.normal = Eigen::Vector3d(1.0, 0.0, -1e-3).normalized();
  makeTangentFrame(after.normal, after.tangent1, after.tangent2);
  ASSERT_LT(after.tangent1.dot(before.tangent1), 0.0);  // the frame did flip
  const auto& out = refresh(cache, {after});
  const Eigen::Vector3d carried = out[0].points[0].tangentImpulse.x() * after.tangent1 +
                                  out[0].points[0].tangentImpulse.y() * after.tangent2;
  EXPECT_GT(carried.dot(before.tangent1), 0.999);
}

TEST(ContactCache, SnapshotRestoreRoundTrips) {
  ContactCache cache;
  refresh(cache, {manifold(1, 2, {10, 11})});
  cache.manifolds()[0].points[1].normalImpulse = 7.0;
  const std::vector<ContactManifold> saved = cache.manifolds();
  cache.clear();
  cache.restore(saved);
  EXPECT_DOUBLE_EQ(refresh(cache, {manifold(1, 2, {11})})[0].points[0].normalImpulse, 7.0);
}

}  // namespace
}  // namespace coulomb::geometry
