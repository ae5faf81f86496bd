#pragma once
// The Gauss-Seidel skeleton shared by pgs and bgs (docs/solver-derivations.md Algorithm 3.1): sweep
// the blocks in a fixed or seeded-shuffled order, give each contact its local free velocity q~_c =
// q_c + sum_{d != c} W_cd r_d (3.1) and let the solver's local rule propose r_c, relax the step
// (3.5), solve scalar rows exactly (10.1), check the common residual every few sweeps on u = W r +
// q recomputed, keep the best iterate, detect stalls.
#include <coulomb/solvers/BodySpaceDelassus.hpp>
#include <coulomb/solvers/FunctionRef.hpp>
#include <coulomb/solvers/PreparedProblem.hpp>
#include <coulomb/solvers/SolverReport.hpp>
#include <coulomb/solvers/SweepPartition.hpp>

#include <Eigen/Core>

#include <vector>

#include <cstdint>

namespace coulomb::solvers {

struct GaussSeidelSettings {
  double omega = 1.0;            // relaxation of the step (3.5), in (0, 2)
  double omegaAfterStall = 0.0;  // switch to this omega at the first stall (0: stop instead)
  int stallWindow = 500;         // [sweeps] window of the stall test
  double stallDecrease = 0.01;   // stalled if the best residual fell by less than this fraction
  bool shuffle = false;          // visit order reshuffled every sweep by a local seeded RNG
  std::uint64_t seed = 0;        // seed of that RNG (determinism rule 7)
  int residualInterval = 0;      // [sweeps] between residual checks; 0 = auto (1, then up to 5)
  int defaultMaxSweeps = 10000;  // when SolverOptions::maxIterations is 0
  // Nonsmooth nonlinear conjugate gradient (Silcowski, Erleben et al. 2015, Algorithm 2): after
  // every sweep add beta_k p_k (Fletcher-Reeves beta on the sweep steps, restart when beta > 1).
  bool conjugateGradient = false;
};

// Proposes a new r_c for contact block b given its local free velocity q~ (r holds r_c on entry).
// A non-owning reference to the solver's local rule (called once per contact per sweep: no
// std::function, no allocation); the rule must outlive the call of runGaussSeidel. With
// SolverOptions::parallel it is called for several blocks at once: it must only read shared data.
using ContactUpdate = FunctionRef<void(int, const Eigen::Vector3d&, Eigen::Vector3d&)>;

// What a visit of one block reads, copied in a split sweep's order (GaussSeidelLoop.cpp).
struct SweepBlock {
  int block = 0, offset = 0;
  bool contact = false;
  double mu = 0.0;
  double q[3] = {0, 0, 0};
  double diagonal[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};  // W_bb, row-major k x k
};

// The loop's vectors, kept by a solver between its solves so that a steady step allocates
// nothing (ContactSolver: one instance is not for two threads at once).
struct GaussSeidelWorkspace {
  std::vector<int> order;
  SweepPartition partition;  // SolverOptions::sweepPartBlocks
  // A split sweep's copies of what it reads, in its order (block i of sweepFactors is the
  // block at position i of `order`).
  BodySpaceDelassus sweepFactors{0, {}};
  std::vector<SweepBlock> blocks;
  std::vector<double> pieceSums;  // a split sweep's partial sums
  Eigen::VectorXd u, best, dv;
  Eigen::VectorXd previous, direction, previousDv, directionDv;  // conjugateGradient only
};

// Local free velocity of block b (3.1) from W's entries (problem.W): q~_b = q_b + sum over the
// other blocks d of W_bd r_d, written to qt[0 .. size of b). Also the start sweep's
// (StartSweep.hpp).
void localFreeVelocity(const PreparedProblem& problem, int b, const Eigen::VectorXd& r, double* qt);

void runGaussSeidel(const PreparedProblem& problem, const SolveContext& context,
                    const GaussSeidelSettings& settings, const ContactUpdate& update,
                    Eigen::VectorXd& r, SolverReport& report,
                    GaussSeidelWorkspace* workspace = nullptr);

}  // namespace coulomb::solvers
