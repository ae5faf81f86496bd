#pragma once
// How a World solves its islands, as one typed value (docs/tuning.md, "The solve policy"):
//   choice     which solvers: the automatic rules, a preferred solver before the automatic
//              fallbacks, or an exact chain of attempts {solver, cap, stall window, tolerance};
//   options    what every attempt shares (tolerance, iteration cap, warm start, time limit);
//   chooser    the automatic rules' thresholds (docs/solver-derivations.md section 9);
//   promotion  the one rule that looks across steps (a fallback that finished a step goes first
//              in the next).
// Validated once (validate(), when a World takes it); settable between steps
// (World::setSolvePolicy) and saved in snapshots. The text form ("auto", "pgs", "pgs!", "a,b")
// exists only at the edges: the CLI's --solver and the scene JSON (parseSolverChoice).
#include <coulomb/solvers/SolvePlan.hpp>
#include <coulomb/solvers/SolverOptions.hpp>

#include <optional>
#include <string>
#include <vector>

namespace coulomb::solvers {

class SolverRegistry;

/// Thresholds of the automatic rules (each: unit, default, reason).
struct ChooserSettings {
  // [-] nu above which an island is a pile/tower and Gauss-Seidel goes first (AC11 section 5.2:
  // Newton still converges up to nu ~ 1.5-2; docs/solver-derivations.md section 9 table).
  // Default 2.
  double pileNu = 2.0;
  // [unknowns] Newton (dense/sparse LU per iteration) only up to this size; beyond it the
  // factorization dominates and Gauss-Seidel goes first. Default 3000 (docs/solver-derivations.md
  // section 9).
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
  // [sweeps] islands with a body-space W that are well-posed enough for Newton first get a bgs
  // try of this many sweeps. Default 0 = off: with 30 the 10-box tower's answers at 1e-6 (bgs)
  // instead of ~1e-7 (Newton) let its energy rise 2.5e-9 J above E(0), beyond the stability
  // case's 1e-9 E(0) bound (docs/benchmarks.md, "Body-space sweeps").
  int factoredTrySweeps = 0;
  // [-] mass ratio kappa above which Newton goes first whatever nu (Gauss-Seidel stagnates on
  // large mass ratios, docs/solver-derivations.md section 9). Default 1e3.
  double newtonMassRatio = 1e3;
  // [sweeps] stall window of pgs on piles and towers, where ac_newton is the fallback: pgs gives
  // way once its best residual fell by < 1 % over this many sweeps. Default 20: every pgs step
  // of the conformance runs that converges needs < 20 sweeps at a stall, while a stagnating pgs
  // would spend its whole cap before Newton (docs/benchmarks.md, "Long runs").
  int pileStallSweeps = 20;
  friend bool operator==(const ChooserSettings&, const ChooserSettings&) = default;
};

/// Promotion (docs/tuning.md, "The solve policy"): when an automatic plan's first attempt ended
/// near the tolerance without converging and a fallback then converged quickly, the warm start
/// the fallback leaves carries its one-off correction of the velocity error the first solver
/// left; warm-started from it, the next step starts off by that correction in the slow mode the
/// first solver could not reduce, and the two alternate. The rule runs the fallback once more,
/// first, in the island's next step. A rule of the policy, off for named solvers and chains.
/// Off by default: the alternation came from plain pgs stagnating just above the tolerance on
/// piles, and the pile plan's nncg converges there (docs/solvers.md, "nncg"); the rule stays for a
/// user's policy whose first solver does stagnate.
struct PromotionRule {
  bool enabled = false;
  // [-] the first attempt counts as a near miss when it ended within this factor of the
  // tolerance. Default 10 (the alternation's signature: pgs ends at 1-2x the tolerance).
  double nearMiss = 10.0;
  // [iterations] the fallback counts as a quick finish within this many iterations, and the
  // promoted attempt is capped at it. Default 5 (Newton needs 1-2 from such a start).
  int iterationCap = 5;
  // [-] the promoted attempt's tolerance as a fraction of the plan's: its start is just below
  // the plan's tolerance and must still be iterated. Default 0.01 (one Newton step: 1e-6 -> 1e-9).
  double toleranceScale = 0.01;
  // [unknowns] only islands with more unknowns are promoted: below, a Newton fallback is a small
  // dense LU and costs less than a promoted attempt changes. Default 300 (the Newton dense limit).
  int minUnknowns = 300;
  friend bool operator==(const PromotionRule&, const PromotionRule&) = default;
};

enum class ChoiceMode : std::uint8_t {
  Automatic,  // the chooser's rules pick the attempts per island
  Preferred,  // `attempts` first, then the automatic plan's other solvers as fallbacks
  Exactly,    // `attempts` alone, in order (one solver without fallback, or a user's chain)
};

struct SolverChoice {
  ChoiceMode mode = ChoiceMode::Automatic;
  std::vector<SolveAttempt> attempts;  // empty for Automatic

  static SolverChoice automatic() { return {}; }
  static SolverChoice preferred(std::string solver);            // "NAME" in the text form
  static SolverChoice only(std::string solver);                 // "NAME!"
  static SolverChoice chain(std::vector<std::string> solvers);  // "A,B,C"
  [[nodiscard]] bool isAutomatic() const { return mode == ChoiceMode::Automatic; }
  /// The text form: "auto", "NAME", "NAME!" or "A,B,C" (per-attempt limits are not shown).
  [[nodiscard]] std::string text() const;
  friend bool operator==(const SolverChoice&, const SolverChoice&) = default;
};

struct SolvePolicy {
  // [blocks] The World's SolverOptions::sweepPartBlocks: the sweeps of islands of at least
  // twice this many blocks (contacts and joint rows) are split into parts, so that they can use
  // the World's threads. Smaller parts give more parallelism and more blocks between parts,
  // which cost more per visit (docs/tuning.md "Parallel sweeps"); below ~2 000 blocks a sweep is
  // too short (~0.2 ms) to gain from threads, so smaller islands keep the block order.
  static constexpr int kSweepPartBlocks = 2048;
  SolverChoice choice;
  // Default tolerance 1e-6 on the common relative residual (far below what changes a trajectory
  // visibly, and reached in a few warm-started sweeps on stacks); at most 200 iterations per
  // attempt (ac_newton's own cap, so it only shortens Gauss-Seidel and staggered: a cold-started
  // stack needs thousands of sweeps, seconds per step on 200+ boxes; the fallbacks and the warm
  // start carry the rest, docs/benchmarks.md "Contact step performance"); an answer worse than
  // its start is never applied (SolverOptions::neverWorseThanStart).
  SolverOptions options = simulationOptions();
  ChooserSettings chooser;
  PromotionRule promotion;

  static SolverOptions simulationOptions() {
    SolverOptions o;
    o.tolerance = 1e-6;
    o.maxIterations = 200;
    o.neverWorseThanStart = true;
    o.sweepPartBlocks = kSweepPartBlocks;
    o.stickingStart = true;
    o.startSweep = true;
    return o;
  }
  /// nullopt if usable, else the first problem: an empty chain, a bad option or threshold, and
  /// (when `registry` is given) an unknown solver, named with the registry's list.
  [[nodiscard]] std::optional<std::string> validate(const SolverRegistry* registry) const;
};

/// The text form at the edges: "auto" | "NAME" | "NAME!" | "A,B,C" (no '!' inside a chain, no
/// empty names). Syntax only; the names are checked against a registry by validate().
/// nullopt with `error` set on a malformed text.
std::optional<SolverChoice> parseSolverChoice(const std::string& text, std::string& error);

/// parseSolverChoice for text known to be well-formed (command lines, tests): throws
/// std::invalid_argument with the parser's message otherwise.
SolverChoice solverChoice(const std::string& text);

/// The first unknown solver of `choice` in `registry`, or nullopt.
std::optional<std::string> unknownSolver(const SolverChoice& choice,
                                         const SolverRegistry& registry);

}  // namespace coulomb::solvers
