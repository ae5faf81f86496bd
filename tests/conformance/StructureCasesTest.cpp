// docs/scene-specifications.md B2, B3 (issue 8 item 1) and the long-run stability cases (item 5,
// A3, A4, B1) through the conformance framework (samples/conformance/StructureCases.cpp,
// StabilityCases.cpp):
// - the card house stands at mu 0.6 and collapses at mu 0.2 (static LP mu_min = 0.3292);
// - the masonry arch stands at mu 0.6 (crown thrust inside the admissible LP range, abutment load
//   W/2 to 1e-3) and collapses at mu 0.2 and 0.1 (thrust-line LP mu_min = 0.3086).
//   The collapse cases are the same metric failing: the code that says "stands" is shown to say
//   "moved" when friction cannot hold the structure.
// - the 10 000-step stability cases at a short horizon (the full runs: bench/ConformanceLongRun,
//   figures in docs/conformance.md; tests/conformance/StackStandsTest covers 1000 steps).
#include <gtest/gtest.h>

#include "conformance/ConformanceCase.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>

using namespace coulomb;

namespace {

// Horizon scales (fractions of the docs/scene-specifications.md duration): the structures that must
// stand run their full 10 s; a collapse is complete within 0.5 s (top_drop 0.49 m at 0.5 s, 0.54 m
// at 10 s, where the fallen cards cost ~0.2 s per step); the 10 000-step stability cases run 50-200
// steps.
#ifdef COULOMB_SANITIZE
constexpr double kSanitizerFactor = 0.2;  // ASan/UBSan run 3-5x slower
#else
constexpr double kSanitizerFactor = 1.0;
#endif

conformance::CaseRun runCase(const std::string& name, const std::string& solver, double scale) {
  const conformance::ConformanceCase& c = conformance::findCase(name);
  const conformance::CaseRun run = c.run({solver, scale});
  std::printf("%s %s: %s = %.6g (%s), %zu steps, %.3f ms/step, residual %.1e, fallbacks %zu [%s]\n",
              name.c_str(), solver.c_str(), c.metricName.c_str(), run.metric, c.criterion.c_str(),
              run.steps, run.msPerStep, run.maxResidual, run.fallbacks, run.detail.c_str());
  return run;
}

using CaseAndSolver = std::tuple<std::string, std::string>;
std::string caseLabel(const ::testing::TestParamInfo<CaseAndSolver>& info) {
  std::string label = std::get<0>(info.param) + "_" + std::get<1>(info.param);
  for (char& ch : label)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return label;
}

class Structure : public ::testing::TestWithParam<CaseAndSolver> {};
class Stability : public ::testing::TestWithParam<CaseAndSolver> {};

}  // namespace

double structureScale(const std::string& name) {
  if (name == "card_house/mu=0.2") return 0.05;  // the collapse costs ~0.2 s per step later on
  return kSanitizerFactor;
}

TEST_P(Structure, MeetsTheScenesCriterion) {
  const auto& [name, solver] = GetParam();
  const conformance::CaseRun run = runCase(name, solver, structureScale(name));
  EXPECT_TRUE(run.passed);
  EXPECT_TRUE(std::isfinite(run.metric));
}

INSTANTIATE_TEST_SUITE_P(CardHouseAndArch, Structure,
                         ::testing::Combine(::testing::Values("card_house/mu=0.6",
                                                              "card_house/mu=0.2"),
                                            ::testing::Values("auto")),
                         caseLabel);

TEST_P(Stability, HoldsOverAShortHorizon) {
  const auto& [name, solver] = GetParam();
  // 200 steps of the towers, 50 of the pyramid, 60 of the pile: its landing cascade (the top
  // layer lands at step ~55), where the pile used to fail: no NaN, no corner below -5 mm, no box
  // out, the energy never above E(0) (before the face-preferring box-box manifolds: -1.6 cm).
  double scale = 0.02;
  if (name == "pyramid/base=10") scale = 0.005;
  if (name == "box_pile_1000/container") scale = 0.006;
  scale *= kSanitizerFactor;
  const conformance::CaseRun run = runCase(name, solver, scale);
  EXPECT_TRUE(run.passed);
  EXPECT_GT(run.steps, 0u);
}

INSTANTIATE_TEST_SUITE_P(TowersPyramidPile, Stability,
                         ::testing::Combine(::testing::Values("box_stack/N=10", "box_stack/N=20",
                                                              "pyramid/base=10",
                                                              "box_pile_1000/container"),
                                            ::testing::Values("auto")),
                         caseLabel);

// The arch at mu 0.6 stands now that hull pairs get face contacts (geometry/HullContacts): its
// voussoirs stay within 1 mm for 2 s (0.4 s under the sanitizers), with the crown thrust inside
// the LP range and the abutment load W/2 to 1e-3 (the arch is statically indeterminate:
// StructureCases.cpp). At mu 0.2 it must still fall (thrust-line LP mu_min = 0.3086).
TEST(Arch, StandsAtMuZeroPointSixAndFallsAtZeroPointTwo) {
  const conformance::CaseRun stands =
      runCase("masonry_arch/mu=0.6", "auto", 0.2 * kSanitizerFactor);
  EXPECT_TRUE(stands.passed);
  EXPECT_LT(stands.metric, 1e-3);
  const conformance::CaseRun falls = runCase("masonry_arch/mu=0.2", "auto", 0.1);
  EXPECT_TRUE(falls.passed);
  EXPECT_GT(falls.metric, 0.1);
}
