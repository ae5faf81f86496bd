// solvers/SolvePolicy: the text form at the edges and the one validation of a policy.
#include <gtest/gtest.h>
#include <coulomb/solvers/SolvePolicy.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>

#include <cmath>
#include <stdexcept>

using namespace coulomb::solvers;

TEST(SolvePolicy, TextFormRoundTrips) {
  for (const char* text : {"auto", "pgs", "pgs!", "bgs,ac_newton"}) {
    std::string error;
    const std::optional<SolverChoice> c = parseSolverChoice(text, error);
    ASSERT_TRUE(c) << text << ": " << error;
    EXPECT_EQ(c->text(), text);
  }
  EXPECT_EQ(solverChoice("pgs!"), SolverChoice::only("pgs"));
  EXPECT_EQ(solverChoice("pgs").mode, ChoiceMode::Preferred);
}

TEST(SolvePolicy, MalformedTextIsRefused) {
  for (const char* text : {"", "pgs!,bgs", "a,,b", "!", "pg!s"}) {
    std::string error;
    EXPECT_FALSE(parseSolverChoice(text, error)) << text;
    EXPECT_FALSE(error.empty()) << text;
  }
  EXPECT_THROW((void)solverChoice("pgs!,bgs"), std::invalid_argument);
}

TEST(SolvePolicy, ValidationNamesTheProblem) {
  const SolverRegistry registry = SolverRegistry::builtIn();
  SolvePolicy ok;
  EXPECT_FALSE(ok.validate(&registry));
  SolvePolicy unknown;
  unknown.choice = SolverChoice::only("pgz");
  ASSERT_TRUE(unknown.validate(&registry));
  EXPECT_NE(unknown.validate(&registry)->find("unknown solver 'pgz'"), std::string::npos);
  EXPECT_FALSE(unknown.validate(nullptr));  // names are the registry's business
  SolvePolicy empty;
  empty.choice.mode = ChoiceMode::Exactly;
  EXPECT_TRUE(empty.validate(&registry));
  SolvePolicy nanTolerance;
  nanTolerance.options.tolerance = std::nan("");
  EXPECT_TRUE(nanTolerance.validate(&registry));
  SolvePolicy negativeCap;
  negativeCap.choice = SolverChoice::only("pgs");
  negativeCap.choice.attempts[0].maxIterations = -1;
  EXPECT_TRUE(negativeCap.validate(&registry));
  SolvePolicy badChooser;
  badChooser.chooser.pileNu = 0.0;
  EXPECT_TRUE(badChooser.validate(&registry));
  SolvePolicy badPromotion;
  badPromotion.promotion.toleranceScale = 2.0;
  EXPECT_TRUE(badPromotion.validate(&registry));
}
