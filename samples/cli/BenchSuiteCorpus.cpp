// `coulomb bench --parts corpus`: every solver on every fc3d problem of a folder at a ladder of
// tolerances (the work-precision curve of each problem: time against the common residual), with
// nu-hat of each problem (docs/solver-derivations.md section 9) for the iterations-against-nu
// figure.
#include <coulomb/solvers/SolverRegistry.hpp>

#include <cstdio>

#include "BenchSuite.hpp"
#include "Commands.hpp"
#include "bench/CorpusSolve.hpp"

namespace coulomb::cli {

void runCorpusPart(const SuiteOptions& o, std::vector<BenchRecord>& out) {
  const bool quick = o.size == BenchSize::Quick;
  std::vector<samples::CorpusFile> files;
  try {
    files = samples::listCorpus(o.corpus);
  } catch (const std::exception& e) {
    throw CommandError(std::string("--corpus: ") + e.what());
  }
  // Quick: the problems up to 100 contacts (seconds in all); full: every problem.
  if (quick) std::erase_if(files, [](const samples::CorpusFile& f) { return f.contacts > 100; });
  const std::vector<double> tolerances =
      quick ? std::vector<double>{1e-4, 1e-8} : std::vector<double>{1e-2, 1e-4, 1e-6, 1e-8, 1e-10};
  const std::vector<std::string> names =
      o.solvers ? *o.solvers : std::vector<std::string>{"pgs", "bgs", "ac_newton", "auto"};
  const solvers::SolverRegistry registry = solvers::SolverRegistry::builtIn();
  for (const std::string& name : names)
    if (name != "auto" && !registry.create(name))
      throw CommandError("--solvers: unknown solver '" + name + "' (see `coulomb solvers`)");
  solvers::SolverOptions options;
  options.timeLimitSeconds = o.timeLimit > 0 ? o.timeLimit : (quick ? 1.0 : 5.0);
  BenchProgress progress(std::cerr, "corpus", files.size() * names.size() * tolerances.size());
  for (const samples::CorpusFile& file : files) {
    const solvers::ContactProblem problem = samples::readCorpusProblem(file.path);
    const double nu = samples::estimatedNu(problem);
    for (const std::string& name : names)
      for (const double tolerance : tolerances) {
        char variant[32];
        std::snprintf(variant, sizeof variant, "tol=%.0e", tolerance);
        progress.next(file.name + " " + name + " " + variant);
        options.tolerance = tolerance;
        const solvers::SolveOutcome solved =
            samples::solveMedian(problem, name, options, registry, o.repeats);
        const solvers::SolverReport& report = solved.report;
        const auto iterations = static_cast<double>(report.iterations);
        out.push_back({.part = "corpus",
                       .item = file.name,
                       .solver = name,
                       .variant = variant,
                       .size = file.contacts,
                       .repeats = report.seconds < 0.5 ? o.repeats : 1,
                       .ms = report.seconds * 1e3,
                       .iterationsMean = iterations,
                       .iterationsMax = iterations,
                       .residualMean = report.residual,
                       .residualMax = report.residual,
                       .maxDrift = BenchRecord::kNaN,
                       .energyChange = BenchRecord::kNaN,
                       .jointGap = BenchRecord::kNaN,
                       .nu = nu,
                       .status = solvers::statusName(report.status),
                       .note = report.timeLimitReached ? "time limit" : ""});
      }
  }
}

}  // namespace coulomb::cli
