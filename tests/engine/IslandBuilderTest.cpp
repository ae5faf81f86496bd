#include <gtest/gtest.h>
#include <coulomb/engine/IslandBuilder.hpp>

using coulomb::engine::ConstraintEdge;
using coulomb::engine::IslandBuilder;

namespace {
constexpr std::int32_t kWorld = ConstraintEdge::kNoBody;
}

TEST(IslandBuilder, StaticFloorDoesNotLinkTwoStacks) {
  // body 0 = static floor; stack {1, 2} and stack {3, 4} both rest on it.
  const std::vector<std::uint8_t> dynamic{0, 1, 1, 1, 1};
  const std::vector<ConstraintEdge> edges{{0, 1}, {1, 2}, {0, 3}, {3, 4}};
  IslandBuilder builder;
  const auto islands = builder.build(dynamic, edges);
  ASSERT_EQ(islands.size(), 2u);
  EXPECT_EQ(islands[0].bodies, (std::vector<std::int32_t>{1, 2}));
  EXPECT_EQ(islands[0].constraints, (std::vector<std::int32_t>{0, 1}));
  EXPECT_EQ(islands[1].bodies, (std::vector<std::int32_t>{3, 4}));
  EXPECT_EQ(islands[1].constraints, (std::vector<std::int32_t>{2, 3}));
  EXPECT_EQ(islands[1].id, 1);
}

TEST(IslandBuilder, OrderDoesNotDependOnEdgeOrder) {
  const std::vector<std::uint8_t> dynamic{1, 1, 1, 1, 1, 1};
  const std::vector<ConstraintEdge> forward{{5, 4}, {0, 2}, {2, 1}, {3, kWorld}};
  const std::vector<ConstraintEdge> shuffled{{3, kWorld}, {2, 1}, {5, 4}, {0, 2}};
  IslandBuilder builder;
  const auto a = builder.build(dynamic, forward);
  const auto b = builder.build(dynamic, shuffled);
  ASSERT_EQ(a.size(), 3u);
  ASSERT_EQ(b.size(), 3u);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].bodies, b[i].bodies);
  EXPECT_EQ(a[0].bodies, (std::vector<std::int32_t>{0, 1, 2}));
  EXPECT_EQ(a[1].bodies, (std::vector<std::int32_t>{3}));
  EXPECT_EQ(a[2].bodies, (std::vector<std::int32_t>{4, 5}));
}

TEST(IslandBuilder, FreeBodiesAndStaticPairsMakeNoIsland) {
  const std::vector<std::uint8_t> dynamic{0, 0, 1};
  const std::vector<ConstraintEdge> edges{{0, 1}};
  IslandBuilder builder;
  EXPECT_TRUE(builder.build(dynamic, edges).empty());
}

TEST(IslandBuilder, BadBodyIndexIsAnError) {
  const std::vector<std::uint8_t> dynamic{1};
  const std::vector<ConstraintEdge> edges{{0, 7}};
  IslandBuilder builder;
  EXPECT_THROW(builder.build(dynamic, edges), std::out_of_range);
}
