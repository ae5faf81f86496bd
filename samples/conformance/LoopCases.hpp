#pragma once
// docs/scene-specifications.md B11 double_loop (the Alart-Curnier paper's figure 9, AC11
// section 5.1.5): a spinning ball on two rails of static capsules, run at one friction coefficient
// with every figure docs/scene-specifications.md asks `samples/double_loop` to report. Shared by
// the conformance cases
// ("double_loop/mu=0.1" ...), samples/double_loop.cpp and tests/conformance/DoubleLoopTest.cpp.
#include "ConformanceCase.hpp"

#include <coulomb/io/SceneLoader.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace coulomb::conformance {

/// Sets the friction of every shape of `scene` to mu (what `coulomb run --mu` does).
void setSceneFriction(engine::io::Scene& scene, double mu);

struct DoubleLoopRun {
  double mu = 0.0;
  double sMax = 0.0;             // [m] furthest progress along the track from the start
  double sFinal = 0.0;           // [m] progress at the end (frozen while off the rails)
  int loopsDone = 0;             // loop tops passed on the rails (0, 1, 2)
  bool leftRails = false;        // the ball was ever > 0.05 m off its path on the rails
  double tLeft = -1.0;           // [s] first time off the rails, -1 if never
  double pathLength = 0.0;       // [m] distance travelled by the centre
  std::size_t contactSteps = 0;  // steps with a ball-rail contact carrying an impulse
  double rollingShare = 0.0;     // steps in which every such contact sticks (|u_T| <= 1e-6 m/s)
  double slidingShare = 0.0;     // the other steps with contact
  // [m/s] the centre's speed in the step that carried it over each loop top on the rails, and
  // the least speed at which the rails still push there (DoubleLoopTrack::keepContactSpeed).
  std::vector<double> topSpeeds;
  double keepContactSpeed = 0.0;
  // ac_newton on each step's problem, from the step's warm start, counted until
  // ||f_AC||^2 < 1e-20 (AC11 section 5.1.5; f_AC = -Phi of docs/solver-derivations.md (5.1) with
  // the solver's spectral rho per contact (5.14)).
  double newtonMean = 0.0;
  int newtonMax = 0;
  std::size_t newtonUnreached = 0;  // steps where 50 iterations did not reach 1e-20
  double fAcSquaredMax = 0.0;       // largest ||f_AC||^2 at the counted iterate
  bool finite = true;
  CaseRun run;  // the world's own solver figures (residual, iterations, ms/step)
};

/// Runs double_loop at friction mu for `steps` steps (0 = the scene's 500) with `solver`.
DoubleLoopRun runDoubleLoop(double mu, const CaseOptions& options, std::size_t steps = 0);

/// One line with every figure of `run`.
std::string describe(const DoubleLoopRun& run);

}  // namespace coulomb::conformance
