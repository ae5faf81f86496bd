#pragma once
// The plain nonsmooth Newton loop (runNonsmoothNewton: no stall restart, no proximal loop) from
// r = 0 with default settings, for tests that look at the loop itself (its stall tests, the
// watchdog's factorizations).
#include <coulomb/solvers/newton/NonsmoothNewton.hpp>

namespace coulomb::solvers::fixtures {

struct PlainNewtonRun {
  NewtonSettings settings;
  NewtonWorkspace work{settings};
  SolverReport report;
};

inline void runPlainNewton(const ContactProblem& problem, double tolerance, int maxIterations,
                           PlainNewtonRun& run) {
  const PreparedProblem p = PreparedProblem::from(problem);
  SolverOptions o;
  o.tolerance = tolerance;
  const SolveContext context(o, SolveContext::Clock::now());
  Eigen::VectorXd r = Eigen::VectorXd::Zero(p.size());
  runNonsmoothNewton(p, AlartCurnierFunction{}, run.settings, context, maxIterations, r, run.report,
                     &run.work);
}

}  // namespace coulomb::solvers::fixtures
