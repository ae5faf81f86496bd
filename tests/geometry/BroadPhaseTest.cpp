// Candidate pairs: sorted by collider ids, filtered by body, bits and the caller's predicate.
#include <coulomb/geometry/BroadPhase.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <span>
#include <vector>

namespace coulomb::geometry {
namespace {

struct Fixture {
  std::vector<Collider> colliders;
  std::vector<Pose> poses;
  FclScene scene{0.005};
  BroadPhase broad;
  std::vector<CollisionFailure> failures;

  void add(std::uint32_t id, std::uint32_t body, Shape shape, const Eigen::Vector3d& at) {
    Collider c;
    c.id = {id, 0};
    c.body = {body, 0};
    c.shape = std::make_shared<const Shape>(std::move(shape));
    colliders.push_back(c);
    poses.push_back(Pose::translation(at));
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> run(const PairPredicate& keep = {},
                                                           std::span<const double> sweeps = {}) {
    std::vector<char> usable(colliders.size(), 1);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
    for (const CandidatePair& p :
         broad.update(colliders, poses, usable, scene, 0.005, keep, failures, sweeps))
      out.emplace_back(colliders[p.a].id.index, colliders[p.b].id.index);
    return out;
  }
};

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

TEST(BroadPhase, SortedByIdsWhateverTheListOrder) {
  Fixture f;  // a row of touching boxes, listed out of id order
  f.add(5, 5, Box{}, {2.0, 0, 0});
  f.add(1, 1, Box{}, {0.0, 0, 0});
  f.add(3, 3, Box{}, {1.0, 0, 0});
  f.add(9, 9, Box{}, {3.0, 0, 0});
  EXPECT_EQ(f.run(), (Pairs{{1, 3}, {3, 5}, {5, 9}}));
  f.poses[0] = Pose::translation({20, 0, 0});  // incremental update: 5 leaves
  EXPECT_EQ(f.run(), (Pairs{{1, 3}}));
}

// Colliders are found by their slot when the ids' slots are dense (a World's), and by a search
// otherwise (ids from anywhere) or when two generations share a slot: the same pairs each way.
TEST(BroadPhase, SparseSlotsAndSharedSlotsGiveTheSamePairs) {
  Fixture dense, sparse, shared;
  for (std::uint32_t k = 0; k < 4; ++k) {
    dense.add(k, k, Box{}, {1.0 * k, 0, 0});
    sparse.add(1000000u * (k + 1), k, Box{}, {1.0 * k, 0, 0});
    shared.add(k, k, Box{}, {1.0 * k, 0, 0});
  }
  shared.colliders[2].id = {1, 7};  // slot 1 twice: generations 0 and 7
  EXPECT_EQ(dense.run(), (Pairs{{0, 1}, {1, 2}, {2, 3}}));
  EXPECT_EQ(sparse.run(), (Pairs{{1000000, 2000000}, {2000000, 3000000}, {3000000, 4000000}}));
  std::vector<char> usable(4, 1);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> bodies;
  for (const CandidatePair& p : shared.broad.update(shared.colliders, shared.poses, usable,
                                                    shared.scene, 0.005, {}, shared.failures))
    bodies.emplace_back(shared.colliders[p.a].body.index, shared.colliders[p.b].body.index);
  std::sort(bodies.begin(), bodies.end());
  EXPECT_EQ(bodies, (Pairs{{0, 1}, {1, 2}, {2, 3}}));
}

TEST(BroadPhase, NoPairsWithinOneBody) {
  Fixture f;
  f.add(1, 7, Box{}, {0, 0, 0});
  f.add(2, 7, Sphere{}, {0.5, 0, 0});
  f.add(3, 8, Sphere{}, {0.0, 0, 0.9});
  EXPECT_EQ(f.run(), (Pairs{{1, 3}, {2, 3}}));
}

TEST(BroadPhase, CategoryAndMaskBits) {
  Fixture f;
  f.add(1, 1, Box{}, {0, 0, 0});
  f.add(2, 2, Box{}, {0.9, 0, 0});
  f.add(3, 3, Box{}, {-0.9, 0, 0});
  f.colliders[1].filter = {0b10, 0b10};  // collider 2 only meets category 2
  EXPECT_EQ(f.run(), (Pairs{{1, 3}}));
  f.colliders[0].filter = {0b11, 0xffffffffu};
  EXPECT_EQ(f.run(), (Pairs{{1, 2}, {1, 3}}));
}

TEST(BroadPhase, PredicateSkipsJointedOrStaticPairs) {
  Fixture f;
  f.add(1, 1, Box{}, {0, 0, 0});
  f.add(2, 2, Box{}, {0.9, 0, 0});
  f.add(3, 3, Box{}, {-0.9, 0, 0});
  const PairPredicate notJointed = [](const Collider& a, const Collider& b) {
    return !(a.body.index == 1 && b.body.index == 2);  // say bodies 1 and 2 share a joint
  };
  EXPECT_EQ(f.run(notJointed), (Pairs{{1, 3}}));
}

TEST(BroadPhase, PlanesPairWithEverythingNearTheirSurface) {
  Fixture f;
  f.add(1, 0, Plane{}, {0, 0, 0});
  f.add(2, 1, Box{}, {0, 0, 0.503});              // 3 mm above: within the margin
  f.add(3, 2, Box{}, {3, 0, 2.0});                // far above
  f.add(4, 3, Sphere{}, {-3, 0, 0.4});            // sunk
  f.add(5, 0, Plane{{1, 0, 0}, -10}, {0, 0, 0});  // far wall on plane 1's body: no pairs
  EXPECT_EQ(f.run(), (Pairs{{1, 2}, {1, 4}}));
}

TEST(BroadPhase, RemovedCollidersLeaveTheTree) {
  Fixture f;
  f.add(1, 1, Box{}, {0, 0, 0});
  f.add(2, 2, Box{}, {0.9, 0, 0});
  EXPECT_EQ(f.run().size(), 1u);
  f.colliders.pop_back();
  f.poses.pop_back();
  EXPECT_TRUE(f.run().empty());
}

// A body's box grows with its sweep (v* h) while it moves fast and shrinks back once it rests: a
// box that kept the sweep of a fall would pair with neighbours it no longer comes near for as long
// as it rests (FCL's tree keeps a leaf's old box when the new one fits inside it).
TEST(BroadPhase, ABoxShrinksBackOnceItsSweepIsGone) {
  Fixture f;
  f.add(1, 1, Box{}, {0, 0, 0});
  f.add(2, 2, Box{}, {1.3, 0, 0});  // 0.3 m apart: no pair at rest
  EXPECT_TRUE(f.run().empty());
  const std::vector<double> falling{0.5, 0.0};  // box 1 can travel 0.5 m in this step
  EXPECT_EQ(f.run({}, falling), (Pairs{{1, 2}}));
  EXPECT_TRUE(f.run().empty());  // at rest again: its old wide box is gone from the tree
  EXPECT_TRUE(f.run().empty());
  EXPECT_EQ(f.run({}, falling), (Pairs{{1, 2}}));  // and it grows again when it moves
}

}  // namespace
}  // namespace coulomb::geometry
