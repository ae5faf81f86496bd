// solvers::UnionFind: sets joined by unite, each rooted at its smallest member whatever the order
// of the unions (island and group numberings rely on it), storage reused by reset.
#include <gtest/gtest.h>
#include <coulomb/solvers/UnionFind.hpp>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

using coulomb::solvers::UnionFind;

TEST(UnionFind, RootsAreTheSmallestMembersWhateverTheOrderOfTheUnions) {
  // Chains {0, 3, 6, 9}, {1, 4, 7}, {2, 5, 8} and the singleton 10, joined in shuffled orders.
  std::vector<std::pair<int, int>> edges = {{9, 6}, {6, 3}, {3, 0}, {7, 4}, {4, 1}, {5, 8}, {2, 5}};
  std::mt19937 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    std::shuffle(edges.begin(), edges.end(), rng);
    UnionFind sets;
    sets.reset(11);
    for (const auto& [a, b] : edges) EXPECT_TRUE(sets.unite(a, b));
    for (int x = 0; x < 11; ++x) EXPECT_EQ(sets.find(x), x == 10 ? 10 : x % 3);
    EXPECT_FALSE(sets.unite(9, 0));  // already one set: closes a loop
    EXPECT_TRUE(sets.unite(10, 8));
    EXPECT_EQ(sets.find(10), 2);
  }
}

TEST(UnionFind, ResetMakesSingletonsAgain) {
  UnionFind sets;
  sets.reset(4);
  sets.unite(0, 3);
  sets.reset(5);
  for (int x = 0; x < 5; ++x) EXPECT_EQ(sets.find(x), x);
}
