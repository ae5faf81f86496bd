// The same pendulum in reduced coordinates (a one-link tree, ABA) and in maximal coordinates (a
// free body on a ball joint, predicted-state correction) follows the exact swing, each to the
// accuracy of its integrator (issue 10 item 6; docs/scene-specifications.md B8: 1 kg bob, 1 m,
// released horizontal, period 2.369025573 s).
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "scenes/SceneRegistry.hpp"

using namespace coulomb;

namespace {

// Angle of the bob below the horizontal, from its position (x, z) relative to the pivot.
double angleOf(const Eigen::Vector3d& bob) {
  return std::atan2(-bob.z(), bob.x());
}

// The exact swing: (I + m L^2) phi'' = m g L cos(phi) for the angle phi below the horizontal, by
// classical Runge-Kutta at 1e-5 s (converged far below the tolerances checked), sampled every 0.01
// s.
std::vector<double> exactSwing(int samples) {
  const double inertia = 0.001 + 1.0, torque = 1.0 * 9.81 * 1.0;
  auto acceleration = [&](double phi) { return torque * std::cos(phi) / inertia; };
  std::vector<double> out;
  double phi = 0.0, rate = 0.0;
  const int perSample = 1000;
  const double h = 0.01 / perSample;
  for (int k = 1; k <= samples; ++k) {
    for (int n = 0; n < perSample; ++n) {
      const double a1 = acceleration(phi), v1 = rate;
      const double a2 = acceleration(phi + 0.5 * h * v1), v2 = rate + 0.5 * h * a1;
      const double a3 = acceleration(phi + 0.5 * h * v2), v3 = rate + 0.5 * h * a2;
      const double a4 = acceleration(phi + h * v3), v4 = rate + h * a3;
      phi += h / 6.0 * (v1 + 2 * v2 + 2 * v3 + v4);
      rate += h / 6.0 * (a1 + 2 * a2 + 2 * a3 + a4);
    }
    out.push_back(phi);
  }
  return out;
}

}  // namespace

TEST(PendulumModels, TreeAndMaximalPendulumsFollowTheExactSwing) {
  engine::World maximal = engine::io::buildWorld(scenes::loadBuiltinScene("pendulum"));
  engine::World reduced = engine::io::buildWorld(scenes::loadBuiltinScene("pendulum_reduced"));
  const geometry::BodyId bob = maximal.findBody("bob");
  const geometry::BodyId link = reduced.findBody("pendulum/bob");
  ASSERT_TRUE(bob.valid());
  ASSERT_TRUE(link.valid());
  const int steps = 237;  // one period at dt = 0.01
  const std::vector<double> exact = exactSwing(steps);
  // atan2 jumps by 2 pi where the bob crosses the horizontal on the far side: compare mod 2 pi.
  auto away = [](double a, double b) {
    return std::abs(std::remainder(a - b, 2.0 * std::numbers::pi));
  };
  double worstTree = 0.0, worstMaximal = 0.0;
  for (int k = 0; k < steps; ++k) {
    maximal.step();
    reduced.step();
    // The link proxy's frame is the joint frame at the pivot; its bob is 1 m along its x axis.
    const Eigen::Vector3d treeBob = reduced.pose(link).apply(Eigen::Vector3d(1.0, 0.0, 0.0));
    worstTree = std::max(worstTree, away(angleOf(treeBob), exact[static_cast<std::size_t>(k)]));
    worstMaximal = std::max(worstMaximal, away(angleOf(maximal.pose(bob).position),
                                               exact[static_cast<std::size_t>(k)]));
  }
  std::printf(
      "pendulum over one period, largest angle error against the exact swing: tree "
      "(Runge-Kutta) %.3e rad, maximal (semi-implicit, joint rows) %.3e rad\n",
      worstTree, worstMaximal);
  EXPECT_LT(worstTree, 1e-6);     // between contact events the tree step is accurate
  EXPECT_LT(worstMaximal, 5e-2);  // first order in h at dt 0.01
  // After one period both are back near the release angle (0 rad): the elliptic-integral period.
  EXPECT_LT(std::abs(angleOf(maximal.pose(bob).position)), 0.05);
  EXPECT_LT(std::abs(angleOf(reduced.pose(link).apply(Eigen::Vector3d(1.0, 0.0, 0.0)))), 0.05);
}
