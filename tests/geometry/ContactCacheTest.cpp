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
  const auto& out = refresh(cache, {manifold(3, 4, {1}), manifold(1, 5, {1})});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].colliderB.index, 5u);
  EXPECT_DOUBLE_EQ(out[0].points[0].normalImpulse, 0.0);
  EXPECT_DOUBLE_EQ(out[1].points[0].normalImpulse, 34.0);
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
