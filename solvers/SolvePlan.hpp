#pragma once
// Which solvers an island gets, in order, and why (ARCHITECTURE.md section 4, SOLVERS.md section
// 9). SolverChooser fills it (automatically or from a named solver or chain); solveWithFallback
// runs it.
#include <coulomb/solvers/SolverOptions.hpp>

#include <limits>
#include <string>
#include <vector>

namespace coulomb::solvers {

/// The cheap features of a problem the automatic choice reads (SOLVERS.md section 9), kept in the
/// plan so that a report can show them next to the reason.
struct ProblemFeatures {
  int contacts = 0;          // Contact3D blocks
  int activeContacts = 0;    // q_N < 0 or warm-start r_N > 0 (likely to carry load)
  int equalityRows = 0;      // bilateral (joint) rows
  int boundedRows = 0;       // motors, joint friction with a constant bound
  int unilateralRows = 0;    // limits, frictionless contacts
  int unknowns = 0;          // 3 contacts + scalar rows
  int degreesOfFreedom = 0;  // m from the assembler, 0 = unknown (captured problems)
  // nu' = (3 n_active + rows) / m (9.1 with the joint-row extension); NaN when m is unknown.
  double nu = std::numeric_limits<double>::quiet_NaN();
  // kappa = max / min of W_NN over the active contacts (mass-ratio estimate); NaN when W is
  // matrix-free (its diagonal costs one product per unknown) or there is no active contact.
  double massRatio = std::numeric_limits<double>::quiet_NaN();
  bool zeroIsExact = false;  // all q_N >= 0 (contacts, unilateral rows) and no equality/bounded
  bool factored = false;     // W is body-space (BodySpaceDelassus): a sweep costs O(contacts)
};

struct SolvePlan {
  std::vector<std::string> solvers;  // registry names: the primary first, then the fallbacks
  std::string reason;                // human-readable: why this primary (for the StepReport)
  SolverOptions options;             // common options for every attempt
  // Per-attempt iteration caps, parallel to `solvers` (missing or 0 = options.maxIterations), e.g.
  // a short Gauss-Seidel try before Newton on tiny problems.
  std::vector<int> iterationCaps;
  // Per-attempt stall windows (SolverOptions::stallWindow), parallel to `solvers` (missing or 0 =
  // options.stallWindow), e.g. a pgs that gives way to Newton as soon as it stagnates.
  std::vector<int> stallWindows;
  // Per-attempt tolerances, parallel to `solvers` (missing or 0 = options.tolerance), e.g. a
  // tighter one for a solver that must iterate from a start just below the plan's tolerance
  // (engine/SolverPromotion). An attempt that ends above its own tolerance but within the plan's
  // counts as converged.
  std::vector<double> tolerances;
  ProblemFeatures features;  // what the choice was based on (auto plans)
};

/// What the chooser may know about an island besides its problem.
struct IslandFeatures {
  int degreesOfFreedom = 0;  // m of nu = 3 n / m (0 = unknown: nu is not used)
};

}  // namespace coulomb::solvers
