#pragma once
// The global nonsmooth Newton loop on Phi(r) = 0 for any per-block NewtonFunction (Algorithm 5.1
// of docs/solver-derivations.md on the reduced form, unknown r only): generalized Jacobian J = A W
// + B (5.5), rows with J_i = e_i eliminated (5.7), the residual-scaled shift J_sigma = A (W + sigma
// I) + B (5.8) that keeps redundant contacts (rank-deficient W) solvable, dense or sparse LU,
// Goldstein-Price (Algorithm 5.2) or Armijo (5.11) line search, stopping by (5.12) on the common
// residual.
#include <coulomb/solvers/PreparedProblem.hpp>
#include <coulomb/solvers/SolverReport.hpp>
#include <coulomb/solvers/newton/BodySpaceNewtonSolve.hpp>
#include <coulomb/solvers/newton/NewtonFunction.hpp>
#include <coulomb/solvers/newton/NewtonLinearSolver.hpp>

#include <Eigen/Core>

#include <vector>

namespace coulomb::solvers {

struct NewtonSettings {
  // rho per contact (5.14) from sym(W_cc): Spectral 1/lambda_max (default, 28/30 in the
  // prototypes), SplitSpectral 1/S_NN and 1/lambda_max(S_TT), Constant `constantRho`.
  enum class Rho { Spectral, SplitSpectral, Constant };
  Rho rho = Rho::Spectral;
  double constantRho = 1.0;
  // (5.8): sigma = min(maxShift, max(minShift, e_rel)) * max_i W_ii; 0/0 disables the shift.
  double minShift = 1e-12, maxShift = 1e-4;
  // Line search: Goldstein-Price (Algorithm 5.2, default for Alart-Curnier, whose merit is only
  // piecewise smooth) or Armijo backtracking (5.11), preferred for Fischer-Burmeister (C^1 merit).
  enum class LineSearch { GoldsteinPrice, Armijo };
  LineSearch lineSearch = LineSearch::GoldsteinPrice;
  int lineSearchTrials = 30;  // Algorithm 5.2, global; also the Armijo halvings
  double m1 = 0.1, m2 = 0.9;  // (5.10)
  double armijoC = 1e-4;      // (5.11) sufficient-decrease constant
  // Watchdog (Chamberlain, Powell, Lemarechal and Pedersen, Math. Prog. Study 16, 1982;
  // docs/solvers.md "Watchdog Newton"): a full Newton step that the search would cut because psi
  // rises is taken as it is, and within this many steps the iterates must come below the point
  // where that began (by armijoC x its slope), or the iteration returns there and takes the
  // search. Near a degenerate answer (contacts on the cone's edge with no slip, four points per
  // face) every full step crosses kinks of Phi and raises psi a little, the monotone search cuts
  // it to 1/16..1/64 and Newton creeps (box_pile_1000's landing columns: 9e-6 after 200
  // iterations); let through, it lands on the right piece. A step the search would lengthen is
  // left to it (a 1e6:1 mass ratio). Measured on the 100 columns of one landing step, to 1e-6:
  // 5 solves 94, 10 all 100 (monotone: 73); each return costs this many iterations (Rover4493:
  // 4 -> 15). 0: monotone.
  int watchdogSteps = 10;
  // A return to the watchdog point ends the run as Stalled ("watchdog return"): for a caller with
  // a method for degenerate problems to hand over to (ac_newton's proximal loop, 5.9). The return
  // says the full steps led nowhere from there; the monotone search that would follow creeps
  // along the same kinks until the stall test ends it, 20 iterations later on box_pile_1000's
  // landing columns (docs/solvers.md "Watchdog Newton").
  bool watchdogReturnStalls = false;
  int stallIterations = 20;     // (5.12): Stalled when the best e_rel fell by < 1 % ...
  double stallDecrease = 0.01;  // ... over this many iterations
  // Linear solve of each step (NewtonLinearSolver): dense LU up to `denseThreshold` unknowns left
  // after elimination, or when W stores more than `sparseMaxDensity` n^2 entries; else sparse LU
  // (COLAMD), its symbolic analysis reused while the pattern holds. The crossover on a tower's
  // block-tridiagonal W is ~100 rows, but below 300 the dense partial-pivoting LU stays: with the
  // sparse LU from 100 rows the statically indeterminate masonry arch (216 rows) took another
  // Newton path and missed its abutment force by 0.15 % (docs/benchmarks.md, "Newton linear
  // solve"); correctness first.
  int denseThreshold = 300;
  double sparseMaxDensity = 0.5;
  // Solve the step in body space (BodySpaceNewtonSolve) when the problem keeps W's factors, the
  // shift is positive and that system is the cheaper (an island with more contact rows than
  // velocities: a column of boxes, four points per face); the contact-space LU otherwise, or when
  // the body-space answer misses the residual check. docs/solvers.md "The Newton step in body
  // space".
  bool bodySpaceSolve = true;
  int defaultMaxIterations = 200;  // AC11 section 5.2
};

// Runs at most `maxIterations` Newton steps from r (feasible start, prepared variables); r is the
// best iterate on exit. Fills status (Converged, MaxIterations, Stalled, NumericalFailure),
// adds to report.iterations, sets the native residual e_Phi (5.13) and the regularization notes.
// `linear`, when given, is used (and keeps its cached sparse pattern) instead of a solver of the
// run's own: the proximal subproblems (5.9) share one, since their W keep one structure.
// Everything one Newton solve needs besides the problem, kept by a solver between its solves
// (a steady step then allocates nothing on the dense path) and shared by the proximal
// subproblems of one solve (W + sigma I keeps W's structure, so the linear solver's sparse
// pattern and symbolic analysis carry over). Not for two solves at once.
struct NewtonWorkspace {
  explicit NewtonWorkspace(const NewtonSettings& settings)
      : linear(settings.denseThreshold, settings.sparseMaxDensity),
        bodySpaceSolve(settings.bodySpaceSolve) {}
  NewtonLinearSolver linear;
  bool bodySpaceSolve;
  BodySpaceNewtonSolve body;  // the body-space path and its factors
  bool bodyFactored = false;  // the last factorization was body's
  bool wdOfD = false;         // the last solve left W d in wd (body space: its residual check)
  int bodySpaceSolves = 0;    // factorizations in body space (tests, reports)
  Eigen::VectorXd bodyRhs, bodyX, bodyCheck;        // its right-hand side, answer and residual
  std::vector<double> rhoN, rhoT;                   // (5.14) per block
  std::vector<NewtonBlockJacobian> jac;             // A_b, B_b per block
  std::vector<int> index, kept;                     // rows kept after eliminating unit rows (5.7)
  std::vector<double> bestHistory;                  // best e_rel per iteration (5.12)
  Eigen::VectorXd watchR, watchU, watchD, watchWd;  // the watchdog point: r, u, d, W d
  Eigen::VectorXd u, phi, d, wd, jd, trialR, trialU, trialPhi, best;  // the iteration
  Eigen::VectorXd solveWd, solveJd, rhs, x, atphi, gradient;          // inside one step
  // The problem whose Jacobian (jac, kept, index, sigma) `linear` holds factored after a run that
  // converged on it, else null: newtonStepWithKeptFactors reuses them.
  const PreparedProblem* factoredFor = nullptr;
  double factoredSigma = 0.0;
};

// `workspace`: null for one made for this call.
void runNonsmoothNewton(const PreparedProblem& problem, const NewtonFunction& function,
                        const NewtonSettings& settings, const SolveContext& context,
                        int maxIterations, Eigen::VectorXd& r, SolverReport& report,
                        NewtonWorkspace* workspace = nullptr);

// One Newton step from r for the problem with u shifted to `uShifted` (u = W r + q' for another
// q'), with the Jacobian the converged run on `problem` factored last (no factorization: Phi, a
// product with W where rows were eliminated, two triangular solves). False when no such factors
// are kept (workspace.factoredFor != &problem) or the solve is not accurate; else `out` = r + d.
// For the steady part of a converged answer (ContactSolver::steadyAnswer, docs/solvers.md
// "Steady warm start"): the Jacobian is that of the last iterate before r, exact where r lies on
// the same piece of Phi (the same contacts sticking, sliding and open).
bool newtonStepWithKeptFactors(const PreparedProblem& problem, const NewtonFunction& function,
                               NewtonWorkspace& workspace, const Eigen::VectorXd& r,
                               const Eigen::VectorXd& uShifted, Eigen::VectorXd& out);

}  // namespace coulomb::solvers
