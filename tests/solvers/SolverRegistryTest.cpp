#include <gtest/gtest.h>
#include <coulomb/solvers/SolverRegistry.hpp>

#include "TestProblems.hpp"

using namespace coulomb::solvers;

TEST(SolverRegistry, ExplicitTable) {
  SolverRegistry r = SolverRegistry::builtIn();
  EXPECT_EQ(r.names(), (std::vector<std::string>{"pgs", "bgs", "nncg", "bgs_nncg", "ac_newton", "prox",
                                                 "fb_newton", "ldlt", "lemke", "staggered"}));
  for (const SolverEntry& e : r.entries()) {
    EXPECT_FALSE(e.summary.empty());
    EXPECT_EQ(r.create(e.name)->name(), e.name);
  }
  EXPECT_EQ(r.create("nope"), nullptr);
  EXPECT_THROW(r.add({"pgs", "again", r.find("pgs")->create}), std::invalid_argument);
  EXPECT_THROW(r.add({"", "no name", r.find("pgs")->create}), std::invalid_argument);
}

// Every solver on the small corpus problems of tests/data to the corpus tolerance 1e-8 (lemke:
// its faceted LCP to 1e-10).
TEST(SolverRegistry, EverySolverSolvesTheFixtures) {
  const SolverRegistry r = SolverRegistry::builtIn();
  SolverOptions o;
  o.timeLimitSeconds = 30;
  for (const char* name : fixtures::kFixtures) {
    const ContactProblem p = fixtures::loadFixture(name);
    for (const SolverEntry& e : r.entries()) {
      const SolveOutcome out = e.create()->solve(p, o);
      if (e.name == "lemke") {  // faceted cone: exact LCP, exact-cone error reported instead
        EXPECT_LT(out.report.nativeResidual, 1e-10) << name << ": " << out.report.message;
        continue;
      }
      if (e.name == "ldlt") {  // equality rows only: says so on contact problems
        EXPECT_EQ(out.report.status, SolverStatus::NotApplicable) << name;
        continue;
      }
      EXPECT_EQ(out.report.status, SolverStatus::Converged)
          << e.name << " on " << name << ": " << out.report.message;
      EXPECT_LE(out.report.residual, 1e-8) << e.name << " on " << name;
    }
  }
}
