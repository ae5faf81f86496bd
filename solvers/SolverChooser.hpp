#pragma once
// The per-island plan (SOLVERS.md section 9, tuned on the corpus: docs/solvers.md "Choosing a
// solver"). `requested` is one of
//   "auto"          the primary and its fallbacks from cheap features of the problem (contacts,
//                   scalar rows, nu = 3n/m when the dof count m is known, the mass-ratio estimate
//                   kappa from W's diagonal, size), with the reason written into the plan;
//   "NAME"          that registry solver first, then the fallbacks of the automatic policy (so
//                   a failure never leaves an island unsolved; the report says which ran);
//   "NAME!"         that solver alone, no fallback;
//   "A,B,C"         exactly this chain, in this order (a user's own fallbacks).
#include <coulomb/solvers/ContactProblem.hpp>
#include <coulomb/solvers/SolvePlan.hpp>

#include <string>

namespace coulomb::solvers {

/// Thresholds of the automatic policy (each: unit, default, reason).
struct ChooserSettings {
  // [-] nu above which an island is a pile/tower and Gauss-Seidel goes first (AC11 section 5.2:
  // Newton still converges up to nu ~ 1.5-2; SOLVERS.md section 9 table). Default 2.
  double pileNu = 2.0;
  // [unknowns] Newton (dense/sparse LU per iteration) only up to this size; beyond it the
  // factorization dominates and Gauss-Seidel goes first. Default 3000 (SOLVERS.md section 9).
  int newtonMaxUnknowns = 3000;
  // [contacts] when the dof count is unknown (captured problems), islands with at least this many
  // contacts are treated as piles (Gauss-Seidel first, Newton as the fallback). Default 500: on
  // the corpus the only such problem (KaplasTower, 570) is solved 2.7x faster by pgs than by
  // ac_newton, while every smaller one is fastest or close to fastest with ac_newton.
  int pileContactsWithoutDofs = 500;
  // [contacts] at most this many active contacts: a short bgs try (`smallTrySweeps`) before
  // Newton. Default 3: on the corpus bgs is exact in 1-2 sweeps there (2x faster than ac_newton),
  // while 4-5 strongly coupled Rover contacts need 11-18 sweeps (ac_newton 1.7x faster).
  int smallActiveContacts = 3;
  // [sweeps] cap of that bgs try. Default 50: a failed try costs about what one Newton step does.
  int smallTrySweeps = 50;
  // [sweeps] islands with a body-space W (large islands of free bodies) that are well-posed
  // enough for Newton first get a bgs try of this many sweeps: a warm-started resting stack is
  // solved in a few sweeps of O(contacts) each, where one Newton step factorizes W (a dense
  // 240 x 240 LU on the 20-box tower). Default 0 = off: with 30, the 10-box tower's answers at
  // 1e-6 (bgs) instead of ~1e-7 (Newton) let its energy rise 2.5e-9 J above E(0), beyond the
  // stability case's 1e-9 E(0) bound (docs/benchmarks.md, "Body-space sweeps").
  int factoredTrySweeps = 0;
  // [-] mass ratio kappa above which Newton goes first whatever nu (Gauss-Seidel stagnates on
  // large mass ratios, SOLVERS.md section 9). Default 1e3.
  double newtonMassRatio = 1e3;
  // [sweeps] stall window of pgs on piles and towers, where ac_newton is the fallback: pgs gives
  // way once its best residual fell by < 1 % over this many sweeps. Default 20: on a 55-box
  // pyramid after ~4 500 steps pgs stagnates just above the tolerance every other step and spent
  // its 200-sweep cap (~6 ms) before Newton's one iteration; every pgs step of the conformance
  // runs that converges needs < 20 sweeps at a stall (docs/benchmarks.md, "Long runs").
  int pileStallSweeps = 20;
};

/// Measures the features of SOLVERS.md section 9 (one pass over q and W's diagonal blocks).
ProblemFeatures measureProblemFeatures(const ContactProblem& problem,
                                       const IslandFeatures& features);

class SolverChooser {
 public:
  explicit SolverChooser(ChooserSettings settings = {}) : settings_(settings) {}

  [[nodiscard]] SolvePlan choose(const ContactProblem& problem, const IslandFeatures& features,
                                 const std::string& requested, const SolverOptions& options) const;

  [[nodiscard]] const ChooserSettings& settings() const { return settings_; }

 private:
  [[nodiscard]] SolvePlan automatic(const ProblemFeatures& f) const;
  ChooserSettings settings_;
};

}  // namespace coulomb::solvers
