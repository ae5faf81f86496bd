// The same pendulum in reduced coordinates (a one-link tree, ABA) and in maximal coordinates (a
// free body on a ball joint, predicted-state correction) follows the same trajectory
// (issue 10 item 6; docs/scene-specifications.md B8: 1 kg bob, 1 m, released horizontal,
// period 2.369025573 s).
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>

#include <cmath>

#include "scenes/SceneRegistry.hpp"

using namespace coulomb;

namespace {

// Angle of the bob below the horizontal, from its position (x, z) relative to the pivot.
double angleOf(const Eigen::Vector3d& bob) {
  return std::atan2(-bob.z(), bob.x());
}

}  // namespace

TEST(PendulumModels, TreeAndMaximalPendulumsSwingTogether) {
  engine::World maximal = engine::io::buildWorld(scenes::loadBuiltinScene("pendulum"));
  engine::World reduced = engine::io::buildWorld(scenes::loadBuiltinScene("pendulum_reduced"));
  const geometry::BodyId bob = maximal.findBody("bob");
  const geometry::BodyId link = reduced.findBody("pendulum/bob");
  ASSERT_TRUE(bob.valid());
  ASSERT_TRUE(link.valid());
  double worst = 0.0;
  for (int k = 1; k <= 237; ++k) {  // one period at dt = 0.01
    maximal.step();
    reduced.step();
    // The link proxy's frame is the joint frame at the pivot; its bob is 1 m along its x axis.
    const Eigen::Vector3d treeBob = reduced.pose(link).apply(Eigen::Vector3d(1.0, 0.0, 0.0));
    const double difference = std::abs(angleOf(maximal.pose(bob).position) - angleOf(treeBob));
    worst = std::max(worst, difference);
  }
  std::printf("pendulum, tree vs maximal: largest angle difference over one period %.3e rad\n",
              worst);
  EXPECT_LT(worst, 5e-3);
  // After one period both are back near the release angle (0 rad): the elliptic-integral period.
  EXPECT_LT(std::abs(angleOf(maximal.pose(bob).position)), 0.05);
}
