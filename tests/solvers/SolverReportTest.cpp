#include <gtest/gtest.h>
#include <coulomb/solvers/SolverReport.hpp>

using namespace coulomb::solvers;

TEST(SolverReport, StatusNamesAndNotes) {
  EXPECT_STREQ(statusName(SolverStatus::Converged), "converged");
  EXPECT_STREQ(statusName(SolverStatus::MaxIterations), "max_iterations");
  EXPECT_STREQ(statusName(SolverStatus::Stalled), "stalled");
  EXPECT_STREQ(statusName(SolverStatus::NumericalFailure), "numerical_failure");
  EXPECT_STREQ(statusName(SolverStatus::InvalidProblem), "invalid_problem");
  EXPECT_STREQ(statusName(SolverStatus::NotApplicable), "not_applicable");
  SolverReport r;
  EXPECT_FALSE(r.converged());
  r.note("a");
  r.note("");
  r.note("b");
  EXPECT_EQ(r.message, "a; b");
}
