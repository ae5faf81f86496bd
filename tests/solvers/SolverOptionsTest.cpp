#include <gtest/gtest.h>
#include <coulomb/solvers/SolverOptions.hpp>

#include <cmath>

using namespace coulomb::solvers;

TEST(SolverOptions, DefaultsAreValid) {
  const SolverOptions o;
  EXPECT_FALSE(validateOptions(o).has_value());
  EXPECT_EQ(o.tolerance, 1e-8);
  EXPECT_TRUE(std::isinf(o.timeLimitSeconds));
}

TEST(SolverOptions, NamesTheBadField) {
  SolverOptions o;
  o.tolerance = -1;
  ASSERT_TRUE(validateOptions(o).has_value());
  EXPECT_NE(validateOptions(o)->find("tolerance"), std::string::npos);
  o = {};
  o.maxIterations = -3;
  EXPECT_NE(validateOptions(o)->find("maxIterations"), std::string::npos);
  o = {};
  o.timeLimitSeconds = 0;
  EXPECT_NE(validateOptions(o)->find("timeLimitSeconds"), std::string::npos);
  o = {};
  o.stallWindow = -1;
  EXPECT_NE(validateOptions(o)->find("stallWindow"), std::string::npos);
  o = {};
  o.sweepPartBlocks = -1;
  EXPECT_NE(validateOptions(o)->find("sweepPartBlocks"), std::string::npos);
}
