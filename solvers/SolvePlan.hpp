#pragma once
// Which solvers an island gets, in order, and why (docs/architecture.md section 4,
// docs/solver-derivations.md section 9). SolverChooser fills it from the world's SolvePolicy
// (SolvePolicy.hpp); solveWithFallback runs it. A plan holds numbers and enums only: its reason is
// formatted when asked (reason()), never on the step's hot path.
#include <coulomb/solvers/SolverOptions.hpp>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace coulomb::solvers {

/// The cheap features of a problem the automatic choice reads (docs/solver-derivations.md section
/// 9), kept in the plan so that a report can show them next to the reason.
struct ProblemFeatures {
  int contacts = 0;          // Contact3D blocks
  int activeContacts = 0;    // q_N <= 0 or warm-start r_N > 0 (likely to carry load)
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
  bool warmStarted = false;  // some contact starts loaded (warm-start r_N > 0): not a cold start
};

/// One attempt of a plan: a registry solver with its own limits. A zero field takes the plan's
/// common option (SolverOptions), so {"pgs"} runs pgs with the world's tolerance and cap.
struct SolveAttempt {
  std::string solver;      // registry name (`coulomb solvers`)
  int maxIterations = 0;   // [iterations] 0 = SolverOptions::maxIterations
  int stallWindow = 0;     // [iterations] 0 = SolverOptions::stallWindow
  double tolerance = 0.0;  // [-] 0 = SolverOptions::tolerance (the plan's target)
  friend bool operator==(const SolveAttempt&, const SolveAttempt&) = default;
};

/// Which rule of the policy made the plan (SolverChooser::automatic, docs/solver-derivations.md
/// section 9).
enum class PlanRule : std::uint8_t {
  ZeroIsExact,        // every q_N >= 0, no equality or bounded rows: r = 0 is exact
  OneContact,         // one contact: bgs solves it exactly in one sweep
  EqualityRowsOnly,   // joint rows without bounds: one sparse LDL^T solve (linear on trees)
  JointRowsOnly,      // no cone: Newton solves the linear system plus bounds in 1-3 steps
  LargeIsland,        // above ChooserSettings::newtonMaxUnknowns: Gauss-Seidel only
  MassRatio,          // kappa above ChooserSettings::newtonMassRatio: Newton first
  PileByNu,           // nu above ChooserSettings::pileNu: pgs first, Newton as the fallback
  PileBySize,         // dofs unknown and many contacts: as PileByNu
  FactoredTry,        // body-space W: a short bgs try, then Newton
  FewActiveContacts,  // a short bgs try, then Newton
  WellPosed,          // Newton first
  Preferred,          // the policy names a solver first, the automatic fallbacks follow
  Exactly,            // the policy's own chain, nothing else
};
const char* planRuleName(PlanRule rule);

struct SolvePlan {
  std::vector<SolveAttempt> attempts;  // the primary first, then the fallbacks
  SolverOptions options;               // common options for every attempt (the plan's target)
  PlanRule rule = PlanRule::WellPosed;
  ProblemFeatures features;  // what the choice was based on
  bool promoted = false;     // attempts[0] is a promoted fallback (SolvePolicy.hpp)

  /// Human-readable: the rule, the features and the attempts (formatted on each call).
  [[nodiscard]] std::string reason() const;
  /// The attempt's options: the plan's with the attempt's non-zero limits.
  [[nodiscard]] SolverOptions optionsFor(const SolveAttempt& attempt) const;
};

/// What the chooser may know about an island besides its problem.
struct IslandFeatures {
  int degreesOfFreedom = 0;  // m of nu = 3 n / m (0 = unknown: nu is not used)
};

}  // namespace coulomb::solvers
