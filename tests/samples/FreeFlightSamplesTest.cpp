// The free-flight samples measured against their closed forms and invariants.
#include <gtest/gtest.h>

#include <iostream>

#include "FreeFlightSamples.hpp"
#include "scenes/SceneRegistry.hpp"

using namespace coulomb;

TEST(FreeFlightSamples, ProjectileMatchesTheClosedForm) {
  const auto m = samples::measureProjectile(scenes::loadBuiltinScene("projectile"));
  samples::print(std::cout, m);
  // The whole error is semi-implicit Euler's known first-order term g h t / 2.
  EXPECT_NEAR(m.maxErrorVsClosedForm, m.expectedEulerOffset, 1e-9);
  EXPECT_LT(m.maxErrorAfterOffset, 1e-9);
}

TEST(FreeFlightSamples, SymmetricTopKeepsItsInvariants) {
  const auto m = samples::measureSymmetricTop(scenes::loadBuiltinScene("symmetric_top"));
  samples::print(std::cout, m);
  EXPECT_EQ(m.steps, 10000u);
  EXPECT_LT(m.maxMomentumDrift, 1e-9);
  EXPECT_LT(m.maxEnergyDrift, 1e-3);
  EXPECT_LT(m.maxConeAngleError, 1e-2);
}

TEST(FreeFlightSamples, OnlyTheIntermediateAxisFlips) {
  const auto m = samples::measureDzhanibekov(scenes::loadBuiltinScene("dzhanibekov"));
  samples::print(std::cout, m);
  EXPECT_GE(m.intermediateFlips, 2);
  EXPECT_LT(m.maxMinorAxisTilt, 0.05);  // the perturbation is 1e-3: tilt stays ~1e-3 rad
  EXPECT_LT(m.maxMajorAxisTilt, 0.05);
  EXPECT_LT(m.maxMomentumDrift, 1e-9);
}
