// SweepPartition: the interiors of different parts share no body (no W_bc between them), no two
// boundary blocks of one colour share a body, every block is visited once, and the split
// depends on the problem and the number of parts alone.
#include <gtest/gtest.h>
#include <coulomb/solvers/PreparedProblem.hpp>
#include <coulomb/solvers/SweepPartition.hpp>

#include <algorithm>
#include <map>
#include <numeric>
#include <set>
#include <vector>

#include "TestProblems.hpp"

using namespace coulomb::solvers;

namespace {

// Every block once; the parts then the colours, ascending inside each, as the accessors say.
void expectAPermutationInSegments(const SweepPartition& s, int blocks) {
  ASSERT_EQ(static_cast<int>(s.order().size()), blocks);
  std::vector<int> sorted = s.order();
  std::sort(sorted.begin(), sorted.end());
  for (int b = 0; b < blocks; ++b) ASSERT_EQ(sorted[b], b);
  ASSERT_EQ(s.partStart(0), 0);
  ASSERT_EQ(s.colourStart(0), s.partStart(s.parts()));
  ASSERT_EQ(s.colourStart(s.colours()), blocks);
  for (int k = 0; k < s.parts(); ++k)
    for (int i = s.partStart(k); i < s.partStart(k + 1); ++i) {
      EXPECT_EQ(s.partOf(s.order()[i]), k);
      EXPECT_EQ(s.colourOf(s.order()[i]), -1);
      if (i > s.partStart(k)) {
        EXPECT_LT(s.order()[i - 1], s.order()[i]);
      }
    }
  for (int c = 0; c < s.colours(); ++c)
    for (int i = s.colourStart(c); i < s.colourStart(c + 1); ++i) {
      EXPECT_EQ(s.partOf(s.order()[i]), -1);
      EXPECT_EQ(s.colourOf(s.order()[i]), c);
      if (i > s.colourStart(c)) {
        EXPECT_LT(s.order()[i - 1], s.order()[i]);
      }
    }
}

}  // namespace

TEST(SweepPartition, PartsAndColoursShareNoBodyInBodySpace) {
  const ContactProblem problem = fixtures::bodyGrid(12, 2, 0.5, 3);  // 144 bodies, 552 blocks
  const PreparedProblem p = PreparedProblem::from(problem, /*keepBodySpace=*/true);
  ASSERT_TRUE(p.bodySpace);
  SweepPartition s;
  s.build(p, 4);
  ASSERT_EQ(s.parts(), 4);
  expectAPermutationInSegments(s, p.blockCount());
  std::map<int, std::set<int>> partsOfBody;  // over interior blocks
  for (int b = 0; b < p.blockCount(); ++b)
    for (int side = 0; side < 2; ++side)
      if (const int body = p.bodySpace->blockBody(b, side); body >= 0 && s.partOf(b) >= 0)
        partsOfBody[body].insert(s.partOf(b));
  for (const auto& [body, parts] : partsOfBody) EXPECT_EQ(parts.size(), 1u) << "body " << body;
  for (int c = 0; c < s.colours(); ++c) {
    std::set<int> bodies;
    for (int i = s.colourStart(c); i < s.colourStart(c + 1); ++i)
      for (int side = 0; side < 2; ++side)
        if (const int body = p.bodySpace->blockBody(s.order()[i], side); body >= 0) {
          EXPECT_TRUE(bodies.insert(body).second) << "body " << body << " twice in colour " << c;
        }
  }
  // Breadth-first parts are compact: the boundary is a small share, every part has an interior.
  const int boundary = p.blockCount() - s.partStart(s.parts());
  EXPECT_GT(boundary, 0);
  EXPECT_LT(boundary, p.blockCount() / 4) << boundary << " of " << p.blockCount();
  for (int k = 0; k < s.parts(); ++k) EXPECT_GT(s.partStart(k + 1) - s.partStart(k), 60) << k;
}

TEST(SweepPartition, TheMatrixFormSplitsWithoutCouplingAcrossParts) {
  const ContactProblem problem = fixtures::bodyGrid(8, 2, 0.5, 7);
  const PreparedProblem p = PreparedProblem::from(problem, false);
  ASSERT_FALSE(p.bodySpace);
  SweepPartition s;
  s.build(p, 3);
  expectAPermutationInSegments(s, p.blockCount());
  for (int b = 0; b < p.blockCount(); ++b)
    for (int k = p.W().rowBegin(b); k < p.W().rowEnd(b); ++k) {
      const int other = p.W().blockColumn(k);
      if (other == b) continue;
      if (s.partOf(b) >= 0) {  // an interior block's neighbours: its part or the boundary
        EXPECT_TRUE(s.partOf(other) == s.partOf(b) || s.partOf(other) == -1) << b << ", " << other;
      } else if (s.partOf(other) == -1) {
        EXPECT_NE(s.colourOf(b), s.colourOf(other)) << b << ", " << other;
      }
    }
  EXPECT_GT(s.partStart(s.parts()), p.blockCount() / 2);  // mostly interior
}

TEST(SweepPartition, OnePartIsTheBlockOrder) {
  const PreparedProblem p = PreparedProblem::from(fixtures::bodyGrid(5, 2, 0.5, 1), true);
  SweepPartition s;
  s.build(p, 1);
  std::vector<int> blockOrder(p.blockCount());
  std::iota(blockOrder.begin(), blockOrder.end(), 0);
  EXPECT_EQ(s.order(), blockOrder);
  EXPECT_EQ(s.parts(), 1);
  EXPECT_EQ(s.colours(), 0);
}

TEST(SweepPartition, DependsOnTheProblemAloneAndReusesItsStorage) {
  const PreparedProblem big = PreparedProblem::from(fixtures::bodyGrid(10, 3, 0.5, 1), true);
  const PreparedProblem small = PreparedProblem::from(fixtures::bodyGrid(3, 1, 0.5, 2), true);
  SweepPartition first, reused;
  first.build(big, 5);
  reused.build(small, 2);
  reused.build(big, 5);  // a smaller problem before must leave no trace
  EXPECT_EQ(first.order(), reused.order());
  EXPECT_EQ(first.colours(), reused.colours());
  EXPECT_EQ(first.partStart(first.parts()), reused.partStart(reused.parts()));
}

TEST(SweepPartition, AnEmptyProblemHasNothingToVisit) {
  PreparedProblem empty;
  SweepPartition s;
  s.build(empty, 4);
  EXPECT_TRUE(s.order().empty());
  EXPECT_EQ(s.colours(), 0);
}
