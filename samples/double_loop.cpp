// Sample: the ball in the double loop (docs/scene-specifications.md B11; Alart-Curnier 2011 figure
// 9). For each friction coefficient it prints how far along the track the ball gets, the share of
// steps rolling versus sliding, the ac_newton iterations per step to ||f_AC||^2 < 1e-20 (mean, max)
// and the world's own solver figures.
//   sample_double_loop [MU ...] [--steps N] [--solver NAME]   (default: 0.1 0.3 0.6 1.0, 500,
//   ac_newton)
#include <coulomb/engine/CoulombError.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "conformance/LoopCases.hpp"

int main(int argc, char** argv) {
  using namespace coulomb::conformance;
  std::vector<double> mus;
  std::size_t steps = 0;
  CaseOptions options{"ac_newton", 1.0};
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if ((arg == "--steps" || arg == "--solver") && i + 1 < argc) {
        const std::string value = argv[++i];
        if (arg == "--steps")
          steps = std::stoul(value);
        else
          options.solver = value;
      } else {
        std::size_t used = 0;
        const double mu = std::stod(arg, &used);
        if (used != arg.size() || !(mu >= 0.0)) throw std::invalid_argument(arg);
        mus.push_back(mu);
      }
    }
  } catch (const std::exception&) {
    std::fprintf(stderr, "usage: sample_double_loop [MU ...] [--steps N] [--solver NAME]\n");
    return 2;
  }
  if (mus.empty()) mus = {0.1, 0.3, 0.6, 1.0};
  std::printf(
      "double_loop (docs/scene-specifications.md B11): ball spinning at 180 rad/s on two rails of "
      "1720 "
      "capsules; track end at s = 15.101 m, loop tops at 3.275 and 9.826 m\n");
  try {
    for (const double mu : mus) {
      const DoubleLoopRun run = runDoubleLoop(mu, options, steps);
      std::printf(
          "%s\n  world solver (%s): residual max %.1e, %.1f iterations/step (max %d), "
          "%zu fallbacks, %.3f ms/step%s\n",
          describe(run).c_str(), options.solver.c_str(), run.run.maxResidual,
          run.run.meanIterations, run.run.maxIterations, run.run.fallbacks, run.run.msPerStep,
          run.finite ? "" : ", NON-FINITE STATE");
    }
  } catch (const coulomb::engine::CoulombError& e) {
    std::fprintf(stderr, "double_loop: %s\n", e.what());
    return 1;
  }
  return 0;
}
