#pragma once
// Solving fc3d corpus problems for the benchmarks (bench/SolverCorpusBench, `coulomb bench
// --parts corpus`): the folder's problems in size order, one solve by a registry name or by
// "auto" (SolverChooser + solveWithFallback, every attempt summed), the median time over repeats,
// and the well-posedness estimate nu-hat of a captured problem (docs/solver-derivations.md section
// 9).
#include <coulomb/solvers/ContactProblem.hpp>
#include <coulomb/solvers/ContactSolver.hpp>
#include <coulomb/solvers/SolverOptions.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>
#include <coulomb/solvers/SolverReport.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace coulomb::samples {

struct CorpusFile {
  std::string name;  // file stem, e.g. "Rover1039"
  std::filesystem::path path;
  int contacts = 0;
};

/// Every readable .fc3d problem of `folder` (only `only` when given), sorted by contacts then
/// name. Throws std::runtime_error naming the folder when it is not one, and the file and line of
/// a problem that does not parse.
std::vector<CorpusFile> listCorpus(const std::filesystem::path& folder,
                                   const std::string& only = {});

/// Reads one problem; throws std::runtime_error with the reader's "FILE:LINE: what" message.
solvers::ContactProblem readCorpusProblem(const std::filesystem::path& path);

/// One solve by `solver`: a registry name, or "auto" (the automatic plan with its fallbacks; the
/// report's seconds and iterations are those of every attempt together). Throws
/// std::runtime_error for an unknown name.
solvers::SolveOutcome solveOnce(const solvers::ContactProblem& problem, const std::string& solver,
                                const solvers::SolverOptions& options,
                                const solvers::SolverRegistry& registry);

/// solveOnce repeated `repeats` times when the first solve takes under 0.5 s (once otherwise);
/// the report's seconds are the median. The solvers are deterministic, so the rest is the same.
solvers::SolveOutcome solveMedian(const solvers::ContactProblem& problem, const std::string& solver,
                                  const solvers::SolverOptions& options,
                                  const solvers::SolverRegistry& registry, int repeats);

/// nu-hat = 3 n / rank(W) (docs/solver-derivations.md (9.1) for a problem without bodies: rank W <=
/// m, so nu-hat >= nu), by a column-pivoting QR of the dense W; NaN above `maxUnknowns` unknowns.
double estimatedNu(const solvers::ContactProblem& problem, int maxUnknowns = 1500);

/// The median of `values` (mean of the middle two for an even count; 0 when empty).
double median(std::vector<double> values);

}  // namespace coulomb::samples
