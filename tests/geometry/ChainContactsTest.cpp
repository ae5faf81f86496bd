// A ball over a chain of capsules: every capsule within the margin gives a point, the end-cap
// points of capsules ahead and behind are ghosts covered by their neighbours and go; the nearest
// contact of each chain stays, and a lone capsule end (nothing covers it) is never dropped.
#include <coulomb/geometry/ChainContacts.hpp>
#include <coulomb/geometry/ManifoldBuilder.hpp>
#include <coulomb/geometry/PrimitiveContacts.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace coulomb::geometry {
namespace {

constexpr double kMargin = 0.005;  // the world's default speculative margin [m]
constexpr double kBall = 0.1;      // ball radius [m]
constexpr double kRail = 0.01;     // capsule radius [m]

// Collider 0: the ball (body 0). Colliders 1..: capsules of body 1, consecutive pieces of
// `points` (a polyline), each rotated from local z onto its segment.
struct Chain {
  std::vector<Collider> colliders;
  std::vector<Pose> poses;

  explicit Chain(const Eigen::Vector3d& ball) {
    Collider c;
    c.id = {0, 0};
    c.body = {0, 0};
    c.shape = std::make_shared<const Shape>(Sphere{kBall});
    colliders.push_back(c);
    poses.push_back(Pose::translation(ball));
  }
  void addPolyline(const std::vector<Eigen::Vector3d>& points) {
    for (std::size_t j = 0; j + 1 < points.size(); ++j) {
      const Eigen::Vector3d d = points[j + 1] - points[j];
      Collider c;
      c.id = {static_cast<std::uint32_t>(colliders.size()), 0};
      c.body = {1, 0};
      c.shape = std::make_shared<const Shape>(Capsule{kRail, d.norm() / 2});
      colliders.push_back(c);
      poses.push_back({Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), d),
                       0.5 * (points[j] + points[j + 1])});
    }
  }
  // Sphere-capsule manifolds of every capsule within the margin (what the narrow phase gives).
  std::vector<ContactManifold> manifolds() const {
    std::vector<ContactManifold> out;
    for (std::size_t k = 1; k < colliders.size(); ++k) {
      PairContact raw;
      if (!sphereCapsule(std::get<Sphere>(*colliders[0].shape), poses[0],
                         std::get<Capsule>(*colliders[k].shape), poses[k], kMargin, raw))
        continue;
      out.push_back(finishManifold(raw, colliders[0], colliders[k],
                                   Pose::translation(poses[0].position), Pose::identity()));
    }
    return out;
  }
};

// A straight rail along x at y = offset, pieces of `length`, from x = -0.2.
std::vector<Eigen::Vector3d> straight(double offset, double length, int pieces) {
  std::vector<Eigen::Vector3d> p;
  for (int j = 0; j <= pieces; ++j) p.emplace_back(-0.2 + j * length, offset, 0.0);
  return p;
}

double touchingHeight() {
  return std::sqrt(std::pow(kBall + kRail, 2) - 0.05 * 0.05);
}

TEST(ChainContacts, OnePointPerRailOnAChainOfShortCapsules) {
  // 1 cm pieces: ~6 capsules per rail lie within the 5 mm margin of the ball.
  for (const double x : {0.0, 0.0031, 0.005, 0.01, 0.0173}) {  // mid-piece and on joints
    Chain chain(Eigen::Vector3d(x, 0.0, touchingHeight()));
    chain.addPolyline(straight(0.05, 0.01, 40));
    chain.addPolyline(straight(-0.05, 0.01, 40));
    std::vector<ContactManifold> m = chain.manifolds();
    ASSERT_GE(m.size(), 8u) << "x " << x;  // the ghosts the filter is for
    dropCoveredCapsuleEnds(chain.colliders, chain.poses, m);
    ASSERT_EQ(m.size(), 2u) << "x " << x;
    for (const ContactManifold& k : m) {
      EXPECT_NEAR(k.points[0].depth, 0.0, 1e-12) << "x " << x;  // the touching point stays
      EXPECT_NEAR(k.normal.x(), 0.0, 1e-12) << "x " << x;       // no tilt along the rail
    }
    EXPECT_LT(m[0].normal.y() * m[1].normal.y(), 0.0);  // one per rail
  }
}

TEST(ChainContacts, KeepsTheNearestPointOfAKinkedChain) {
  // Kinks of 0.5 degrees (the double loop's rails): the point of the nearest capsule stays.
  std::vector<Eigen::Vector3d> p;
  double angle = 0.0;
  Eigen::Vector3d at(-0.2, 0.05, 0.0);
  for (int j = 0; j <= 40; ++j, angle += 0.5 * M_PI / 180.0) {
    p.push_back(at);
    at += 0.01 * Eigen::Vector3d(std::cos(angle), 0.0, std::sin(angle));
  }
  for (const double x : {-0.05, 0.0, 0.0123}) {
    Chain chain(Eigen::Vector3d(x, 0.0, 0.0));
    chain.addPolyline(p);
    // Ball centre: just touching the chain above x (bisection on the height).
    double lo = -0.1, hi = 0.3;
    for (int it = 0; it < 100; ++it) {
      chain.poses[0].position.z() = 0.5 * (lo + hi);
      double gap = 1.0;
      for (const ContactManifold& k : chain.manifolds()) gap = std::min(gap, -k.points[0].depth);
      (gap < 0.0 ? lo : hi) = 0.5 * (lo + hi);
    }
    chain.poses[0].position.z() = hi;
    std::vector<ContactManifold> all = chain.manifolds();
    double nearest = 1.0;
    for (const ContactManifold& k : all) nearest = std::min(nearest, -k.points[0].depth);
    std::vector<ContactManifold> m = all;
    dropCoveredCapsuleEnds(chain.colliders, chain.poses, m);
    ASSERT_GE(m.size(), 1u);
    ASSERT_LE(m.size(), 2u) << "x " << x;  // over a joint both neighbours may touch
    EXPECT_NEAR(-m[0].points[0].depth, nearest, 1e-12);
    EXPECT_LT(m.size(), all.size());
  }
}

TEST(ChainContacts, KeepsALoneCapsuleEnd) {
  // The ball beyond the end of a rail touches its end cap: nothing covers it, it stays.
  Chain chain(Eigen::Vector3d(-0.2 - 0.106, 0.0, 0.0));
  chain.addPolyline({{-0.2, 0.0, 0.0}, {-0.198, 0.0, 0.0}, {-0.196, 0.0, 0.0}});
  std::vector<ContactManifold> m = chain.manifolds();
  ASSERT_EQ(m.size(), 2u);  // the end cap and the second piece, 2 mm further
  dropCoveredCapsuleEnds(chain.colliders, chain.poses, m);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].colliderB.index, 1u);
  EXPECT_NEAR(m[0].points[0].depth, 0.004, 1e-12);
}

TEST(ChainContacts, LeavesOtherPairsAlone) {
  // Capsules of two different bodies: no cap is covered by the other body's capsule.
  Chain chain(Eigen::Vector3d(0.0, 0.0, touchingHeight()));
  chain.addPolyline(straight(0.05, 0.01, 40));
  for (std::size_t k = 21; k < chain.colliders.size(); ++k) chain.colliders[k].body = {2, 0};
  std::vector<ContactManifold> m = chain.manifolds();
  const std::size_t before = m.size();
  dropCoveredCapsuleEnds(chain.colliders, chain.poses, m);
  EXPECT_EQ(m.size(), 2u);  // the nearest of each body (the piece boundary is at x = 0)
  EXPECT_LT(m.size(), before);
}

}  // namespace
}  // namespace coulomb::geometry
