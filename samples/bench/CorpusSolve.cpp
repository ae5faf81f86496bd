#include "CorpusSolve.hpp"

#include <coulomb/solvers/SolveWithFallback.hpp>
#include <coulomb/solvers/SolverChooser.hpp>
#include <coulomb/solvers/io/Fc3dText.hpp>

#include <Eigen/QR>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <tuple>

namespace coulomb::samples {

namespace fs = std::filesystem;

solvers::ContactProblem readCorpusProblem(const fs::path& path) {
  solvers::Fc3dReadResult read = solvers::readFc3dText(path.string());
  if (!read.problem) throw std::runtime_error(read.error);
  return std::move(*read.problem);
}

std::vector<CorpusFile> listCorpus(const fs::path& folder, const std::string& only) {
  if (!fs::is_directory(folder))
    throw std::runtime_error("'" + folder.string() + "' is not a folder of .fc3d problems");
  std::vector<CorpusFile> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    const fs::path& path = entry.path();
    if (path.extension() != ".fc3d" || (!only.empty() && path.stem() != only)) continue;
    files.push_back({path.stem().string(), path, readCorpusProblem(path).contactCount()});
  }
  std::sort(files.begin(), files.end(), [](const CorpusFile& a, const CorpusFile& b) {
    return std::tie(a.contacts, a.name) < std::tie(b.contacts, b.name);
  });
  return files;
}

solvers::SolveOutcome solveOnce(const solvers::ContactProblem& problem, const std::string& solver,
                                const solvers::SolverOptions& options,
                                const solvers::SolverRegistry& registry) {
  if (solver != "auto") {
    auto named = registry.create(solver);
    if (!named) throw std::runtime_error("unknown solver '" + solver + "'");
    return named->solve(problem, options);
  }
  const solvers::SolvePlan plan =
      solvers::SolverChooser().choose(problem, {}, solvers::SolverChoice::automatic(), options);
  const solvers::PlanOutcome planned = solvers::solveWithFallback(problem, plan, registry);
  solvers::SolveOutcome outcome = planned.best;
  outcome.report.solver = "auto";
  outcome.report.seconds = planned.seconds;
  outcome.report.iterations = planned.iterations();
  return outcome;
}

solvers::SolveOutcome solveMedian(const solvers::ContactProblem& problem, const std::string& solver,
                                  const solvers::SolverOptions& options,
                                  const solvers::SolverRegistry& registry, int repeats) {
  solvers::SolveOutcome first = solveOnce(problem, solver, options, registry);
  std::vector<double> times{first.report.seconds};
  const int runs = first.report.seconds < 0.5 ? repeats : 1;
  for (int k = 1; k < runs; ++k)
    times.push_back(solveOnce(problem, solver, options, registry).report.seconds);
  first.report.seconds = median(times);
  return first;
}

double estimatedNu(const solvers::ContactProblem& problem, int maxUnknowns) {
  const int n = problem.size();
  if (n == 0 || n > maxUnknowns) return std::numeric_limits<double>::quiet_NaN();
  Eigen::MatrixXd w(n, n);
  for (int j = 0; j < n; ++j) w.col(j) = problem.W.column(j);
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(w);
  qr.setThreshold(1e-10);  // relative to the largest pivot: W of a rigid stack is exactly singular
  const auto rank = static_cast<double>(qr.rank());
  return rank > 0 ? 3.0 * problem.contactCount() / rank : std::numeric_limits<double>::quiet_NaN();
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace coulomb::samples
