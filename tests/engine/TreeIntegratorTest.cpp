// Reduced-coordinate chains between contact events (WorldSettings::treeIntegrator, docs/tuning.md
// "Tree integrators"): the 10- and 50-link chains of docs/scene-specifications.md A6 built as one
// articulation (ABA, spherical joints, 0.1 kg links of 0.1 m, released horizontal, no damping).
// With semi-implicit Euler they diverge; with the default Runge-Kutta step their energy stays
// within 10 % of the released energy at dt 0.002 and bounded at dt 0.01, and one sub-step of the
// method converges at least as h^2.
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>
#include <coulomb/integrators/ArticulationIntegrator.hpp>
#include <coulomb/joints/tree/TreeDynamics.hpp>
#include <coulomb/joints/tree/TreeKinematics.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include "bench/ShapeFixtures.hpp"

using namespace coulomb;

namespace {

// Largest |E(t) - E(0)| over the run as a fraction of the released energy (the potential energy
// between horizontal and hanging straight down: sum m g (0.05 + 0.1 i)), and the final error.
struct EnergyError {
  double worst = 0.0;
  double last = 0.0;
  double above = 0.0;  // largest E(t) - E(0) [J]
};

EnergyError run(int links, double h, double seconds, engine::TreeIntegrator integrator) {
  engine::WorldSettings settings;
  settings.treeIntegrator = integrator;
  engine::World world(settings);
  const geometry::ArticulationId id = world.createArticulation(samples::releasedChain(links));
  const auto& stage = world.articulations();
  auto energy = [&] {
    const joints::tree::Articulation& model = stage.model(id);
    const auto kinematics = joints::tree::forwardKinematics(model, stage.q(id));
    return joints::tree::kineticEnergy(model, kinematics, stage.qd(id)) +
           joints::tree::potentialEnergy(model, kinematics);
  };
  double released = 0.0;
  for (int i = 0; i < links; ++i) released += 0.1 * 9.81 * (0.05 + 0.1 * i);
  const double start = energy();
  EnergyError error;
  const int steps = static_cast<int>(std::lround(seconds / h));
  for (int k = 0; k < steps; ++k) {
    world.step(h);
    const double change = energy() - start;
    if (!std::isfinite(change)) return {INFINITY, INFINITY, INFINITY};
    error.worst = std::max(error.worst, std::abs(change) / released);
    error.above = std::max(error.above, change);
    error.last = change / released;
  }
  return error;
}

}  // namespace

TEST(TreeIntegrator, WhippingChainsKeepTheirEnergyWithRungeKutta) {
  for (const int links : {10, 50}) {
    const EnergyError fine = run(links, 0.002, 10.0, engine::TreeIntegrator::RungeKutta);
    const EnergyError coarse = run(links, 0.01, 10.0, engine::TreeIntegrator::RungeKutta);
    std::printf(
        "chain_%d Runge-Kutta: dt 0.002 worst %.3g last %.3g; dt 0.01 worst %.3g last %.3g\n",
        links, fine.worst, fine.last, coarse.worst, coarse.last);
    EXPECT_LT(fine.worst, 0.10) << links << " links at dt 0.002";
    EXPECT_LT(coarse.worst, 0.50) << links << " links at dt 0.01";
  }
}

TEST(TreeIntegrator, SemiImplicitEulerIsTheControlAndDiverges) {
  const EnergyError euler = run(10, 0.002, 10.0, engine::TreeIntegrator::SemiImplicitEuler);
  std::printf("chain_10 semi-implicit Euler at dt 0.002: worst %.3g\n", euler.worst);
  EXPECT_GT(euler.worst, 1.0);  // the failure this integrator fixes (docs/tuning.md)
}

TEST(TreeIntegrator, OneSubStepConvergesAtLeastAsTheSquareOfTheStep) {
  // With error control the energy error follows the tolerance, not dt; the method itself is
  // checked here: 0.04 s of the released 3-link chain in steps of h that each take one sub-step,
  // against the same run at h = 1e-4, for h = 0.01, 0.005, 0.0025.
  std::vector<joints::tree::TreeLink> links;
  for (const engine::ArticulationLinkDesc& link : samples::releasedChain(3).links)
    links.push_back({link.name, link.parent, link.joint, *link.inertia});
  const joints::tree::Articulation model(links);
  auto endState = [&](double h, bool oneSubStep) {
    Eigen::VectorXd q = model.neutralConfiguration(), qd = Eigen::VectorXd::Zero(model.nv());
    const Eigen::VectorXd tau = Eigen::VectorXd::Zero(model.nv());
    joints::tree::AbaWorkspace aba;
    integrators::TreeStepScratch scratch;
    const int steps = static_cast<int>(std::lround(0.04 / h));
    for (int k = 0; k < steps; ++k) {
      integrators::rungeKuttaStep(model, q, qd, tau, h, aba, scratch);
      if (oneSubStep) {
        EXPECT_EQ(scratch.substeps, 1) << "h " << h;
      }
    }
    return Eigen::VectorXd(qd);
  };
  const Eigen::VectorXd reference = endState(1e-4, false);
  double previous = 0.0;
  for (const double h : {0.01, 0.005, 0.0025}) {
    const double error = (endState(h, true) - reference).norm();
    std::printf("3-link chain, one sub-step per step: h %.4f, velocity error %.3g\n", h, error);
    if (previous > 0.0) {
      EXPECT_GT(previous / error, 3.5) << "h " << h;  // order 2 gives 4
    }
    previous = error;
  }
}
