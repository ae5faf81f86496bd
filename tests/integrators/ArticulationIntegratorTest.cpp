// Semi-implicit Euler for articulations: pendulum periods (docs/scene-specifications.md B8), energy
// of a frictionless free-floating tree, momentum in free fall, and the joint-manifold position
// update.
#include <gtest/gtest.h>
#include <coulomb/integrators/ArticulationIntegrator.hpp>
#include <coulomb/joints/tree/TreeKinematics.hpp>

#include "../joints/RandomTrees.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

using namespace coulomb::joints::tree;
using coulomb::integrators::integrateConfiguration;
using coulomb::integrators::stepArticulation;

namespace {
/// docs/scene-specifications.md B8: bob 1 kg, I 0.001, COM 1 m from a pivot at the origin, hinge
/// about y.
Articulation compoundPendulum() {
  const coulomb::geometry::SpatialInertia bob{1.0, Eigen::Vector3d(1, 0, 0),
                                              0.001 * Eigen::Matrix3d::Identity()};
  return Articulation(
      {{"bob", -1, TreeJoint::revolute("pivot", {}, Eigen::Vector3d::UnitY()), bob}});
}

/// Period from the sign changes of x(t) - offset (linear interpolation), mean of t_{i+2} - t_i.
double measuredPeriod(const Articulation& pendulum, double q0, double offset, double h,
                      double duration) {
  Eigen::VectorXd q = Eigen::VectorXd::Constant(1, q0), qd = Eigen::VectorXd::Zero(1);
  const Eigen::VectorXd tau = Eigen::VectorXd::Zero(1);
  std::vector<double> crossings;
  double previous = q(0) - offset;
  const int steps = static_cast<int>(std::lround(duration / h));
  for (int k = 1; k <= steps; ++k) {
    stepArticulation(pendulum, q, qd, tau, h);
    const double value = q(0) - offset;
    if ((previous < 0.0) != (value < 0.0))
      crossings.push_back(h * (k - 1) + h * previous / (previous - value));
    previous = value;
  }
  double sum = 0.0;
  for (size_t i = 2; i < crossings.size(); ++i) sum += crossings[i] - crossings[i - 2];
  return sum / static_cast<double>(crossings.size() - 2);
}

double totalEnergy(const Articulation& tree, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  const TreeKinematics kin = forwardKinematics(tree, q);
  return kineticEnergy(tree, kin, qd) + potentialEnergy(tree, kin);
}

/// Largest |E(t) - E(0)| over a run of the frictionless tree (no damping, no armature).
double maxEnergyDrift(const Articulation& tree, Eigen::VectorXd q, Eigen::VectorXd qd, double h,
                      double duration) {
  const double e0 = totalEnergy(tree, q, qd);
  const Eigen::VectorXd tau = Eigen::VectorXd::Zero(tree.nv());
  double drift = 0.0;
  for (int k = 0; k < static_cast<int>(std::lround(duration / h)); ++k) {
    stepArticulation(tree, q, qd, tau, h);
    drift = std::max(drift, std::abs(totalEnergy(tree, q, qd) - e0));
  }
  return drift;
}
}  // namespace

TEST(ArticulationIntegrator, PendulumAtNinetyDegreesHasTheEllipticIntegralPeriod) {
  // q = 0: COM at (1, 0, 0), horizontal; it hangs at q = pi/2. T = 4 sqrt(l_eq/g) K(sin 45 deg).
  const Articulation pendulum = compoundPendulum();
  for (const double h : {0.01, 0.001}) {
    const double period = measuredPeriod(pendulum, 0.0, M_PI / 2, h, 10.0);
    EXPECT_NEAR(period / 2.369025573 - 1.0, 0.0, 1e-4) << "h = " << h;
  }
}

TEST(ArticulationIntegrator, PendulumAtSmallAmplitudeHasTheLinearPeriod) {
  const Articulation pendulum = compoundPendulum();
  const double period = measuredPeriod(pendulum, M_PI / 2 - 0.01, M_PI / 2, 0.001, 10.0);
  EXPECT_NEAR(period / 2.007069463 - 1.0, 0.0, 1e-4);
}

TEST(ArticulationIntegrator, PendulumEnergyDriftShrinksWithTheStep) {
  const Articulation pendulum = compoundPendulum();
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(1), qd = Eigen::VectorXd::Zero(1);
  const double coarse = maxEnergyDrift(pendulum, q, qd, 1e-3, 3.0);
  const double fine = maxEnergyDrift(pendulum, q, qd, 1e-4, 3.0);
  EXPECT_LT(fine / 9.81, 2e-4);  // relative to m g l
  EXPECT_LT(fine, 0.2 * coarse);
}

TEST(ArticulationIntegrator, FreeFloatingTreeConservesEnergyAndMomentum) {
  randomtree::RandomSource random(21);
  Articulation tree = randomtree::randomTree(random, {7, true, false});
  const Articulation weightless(tree.links(), Eigen::Vector3d::Zero());
  Eigen::VectorXd q = randomtree::randomConfiguration(weightless, random);
  Eigen::VectorXd qd = randomtree::randomVector(weightless.nv(), random, 1.0);
  const double e0 = totalEnergy(weightless, q, qd);
  const double coarse = maxEnergyDrift(weightless, q, qd, 1e-3, 1.0);
  const double fine = maxEnergyDrift(weightless, q, qd, 1e-4, 1.0);
  EXPECT_LT(fine / e0, 1e-3);
  EXPECT_LT(fine, 0.2 * coarse);
  // With gravity the energy is conserved the same way.
  EXPECT_LT(maxEnergyDrift(tree, q, qd, 1e-4, 1.0) / e0, 1e-2);
  // Free flight without gravity: the spatial momentum about the world origin is constant in the
  // continuous motion; semi-implicit Euler keeps it to O(h).
  const coulomb::geometry::Vector6d p0 =
      spatialMomentum(weightless, forwardKinematics(weightless, q), qd);
  const Eigen::VectorXd tau = Eigen::VectorXd::Zero(weightless.nv());
  for (int k = 0; k < 10000; ++k) stepArticulation(weightless, q, qd, tau, 1e-4);
  const coulomb::geometry::Vector6d p1 =
      spatialMomentum(weightless, forwardKinematics(weightless, q), qd);
  EXPECT_LT((p1 - p0).norm(), 1e-3 * p0.norm());
}

TEST(ArticulationIntegrator, FloatingJointFollowsTheTwistExponential) {
  const coulomb::geometry::SpatialInertia body{1.0, Eigen::Vector3d::Zero(),
                                               Eigen::Matrix3d::Identity()};
  const Articulation free({{"body", -1, TreeJoint::floating("free"), body}});
  Eigen::VectorXd qd(6);
  qd << 0.0, 0.0, 2.0, 1.0, 0.0, 0.0;  // spin about z at 2 rad/s, body-frame velocity 1 m/s along x
  // A constant body twist traces a circle of radius v / omega = 0.5 about (0, 0.5, 0).
  Eigen::VectorXd oneStep = free.neutralConfiguration(), manySteps = oneStep;
  integrateConfiguration(free, oneStep, qd, M_PI / 2);
  for (int k = 0; k < 1000; ++k) integrateConfiguration(free, manySteps, qd, M_PI / 2000);
  EXPECT_LE((oneStep.head<3>() - Eigen::Vector3d(0.0, 1.0, 0.0)).norm(), 1e-14);
  EXPECT_LE((oneStep - manySteps).norm(), 1e-12);
  EXPECT_NEAR(oneStep.segment<4>(3).norm(), 1.0, 1e-15);
  Eigen::VectorXd q = free.neutralConfiguration();
  EXPECT_THROW(integrateConfiguration(free, q, qd, std::nan("")), std::invalid_argument);
  EXPECT_THROW(integrateConfiguration(free, q, Eigen::VectorXd::Zero(5), 0.1),
               std::invalid_argument);
}
