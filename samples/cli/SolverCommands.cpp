// `coulomb solvers` (the registry, one line each, then `auto` and its rules) and `coulomb solve
// FILE.fc3d` (one JSON line per solver: problem, contacts, solver, status, iterations, seconds,
// common residual).
#include <coulomb/solvers/AutomaticRules.hpp>
#include <coulomb/solvers/SolveWithFallback.hpp>
#include <coulomb/solvers/SolverChooser.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>
#include <coulomb/solvers/io/Fc3dText.hpp>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "Commands.hpp"

namespace coulomb::cli {

namespace {

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char b[8];
          std::snprintf(b, sizeof b, "\\u%04x", c);
          out += b;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string jsonNumber(double v) {
  if (!std::isfinite(v)) return "null";  // JSON has no inf/nan (never expected for residuals)
  char b[64];
  const auto res = std::to_chars(b, b + sizeof b, v);
  return std::string(b, res.ptr);
}

struct SolveArgs {
  std::string file;
  std::string solver = "all";
  double tolerance = 1e-8;
  int maxIterations = 0;
  double timeLimit = 60.0;
  std::string solutionPath;
  std::string startPath;
  bool history = false;
};

void runSolve(const SolveArgs& a) {
  const solvers::Fc3dReadResult read = solvers::readFc3dText(a.file);
  if (!read.problem)
    throw CommandError(read.error + "\n  (format: fc3d-text 1, see docs/solvers.md)");
  solvers::ContactProblem problem = *read.problem;
  if (!a.startPath.empty()) {  // a captured warm start: every solver begins from it
    std::string error;
    problem.warmStart = solvers::readVector(a.startPath, problem.q.size(), error);
    if (!problem.warmStart) throw CommandError("--start: " + error);
  }
  const solvers::SolverRegistry registry = solvers::SolverRegistry::builtIn();
  std::vector<std::string> names;
  const bool plan = a.solver == "auto" || a.solver.find(',') != std::string::npos ||
                    (!a.solver.empty() && a.solver.back() == '!');
  if (a.solver == "all") {
    names = registry.names();
    names.push_back("auto");
  } else if (plan) {
    names.push_back(a.solver);  // SolverChooser: auto, a chain "a,b" or "name!"
  } else if (registry.find(a.solver)) {
    names.push_back(a.solver);
  } else {
    std::string known;
    for (const std::string& n : registry.names()) known += " " + n;
    throw CommandError("unknown solver '" + a.solver + "'; known:" + known +
                       " (or all, auto, a chain a,b,c, or name! for no fallback)");
  }
  solvers::SolverOptions options;
  options.tolerance = a.tolerance;
  options.maxIterations = a.maxIterations;
  options.timeLimitSeconds = a.timeLimit;
  options.recordHistory = a.history;
  if (auto bad = solvers::validateOptions(options)) throw CommandError("bad option: " + *bad);
  Eigen::VectorXd bestR;
  double bestResidual = std::numeric_limits<double>::infinity();
  for (const std::string& name : names) {
    solvers::SolveOutcome out;
    std::string planFields;
    if (registry.find(name)) {
      out = registry.create(name)->solve(problem, options);
    } else {  // a plan: the chooser's primary and fallbacks (docs/solver-derivations.md section 9)
      std::string error;
      const std::optional<solvers::SolverChoice> choice = solvers::parseSolverChoice(name, error);
      if (!choice) throw CommandError("--solver: " + error);
      if (auto unknown = solvers::unknownSolver(*choice, registry))
        throw CommandError("unknown solver '" + *unknown + "' (see `coulomb solvers`)");
      const solvers::SolvePlan chosen =
          solvers::SolverChooser().choose(problem, {}, *choice, options);
      const solvers::PlanOutcome planned = solvers::solveWithFallback(problem, chosen, registry);
      out = planned.best;
      out.report.seconds = planned.seconds;
      out.report.iterations = planned.iterations();
      std::string tried;
      for (const solvers::SolverReport& attempt : planned.attempts)
        tried += (tried.empty() ? "" : ",") + jsonString(attempt.solver);
      planFields = ",\"attempts\":[" + tried + "],\"reason\":" + jsonString(chosen.reason());
    }
    const solvers::SolverReport& r = out.report;
    std::cout << "{\"problem\":" << jsonString(problem.name)
              << ",\"contacts\":" << problem.contactCount() << ",\"solver\":" << jsonString(name)
              << ",\"status\":" << jsonString(solvers::statusName(r.status))
              << ",\"iterations\":" << r.iterations << ",\"seconds\":" << jsonNumber(r.seconds)
              << ",\"residual\":" << jsonNumber(r.residual) << planFields;
    if (!r.message.empty()) std::cout << ",\"note\":" << jsonString(r.message);  // as run --stats
    if (a.history) {
      std::cout << ",\"history\":[";
      for (std::size_t k = 0; k < r.history.size(); ++k)
        std::cout << (k ? "," : "") << "[" << r.history[k].iteration << ","
                  << jsonNumber(r.history[k].seconds) << "," << jsonNumber(r.history[k].residual)
                  << "]";
      std::cout << "]";
    }
    std::cout << "}" << std::endl;
    if (r.status == solvers::SolverStatus::InvalidProblem)
      throw CommandError(a.file + ": invalid problem: " + r.message);
    if (bestR.size() == 0 || r.residual < bestResidual) {
      bestResidual = r.residual;
      bestR = out.impulses;
    }
  }
  if (!a.solutionPath.empty()) {
    std::ofstream f(a.solutionPath);
    if (!f) throw CommandError(a.solutionPath + ": cannot write the solution file");
    solvers::writeVector(bestR, f);
    if (!f) throw CommandError(a.solutionPath + ": write failed");
  }
}

}  // namespace

void registerSolverCommands(CLI::App& app) {
  app.add_subcommand("solvers",
                     "List the contact solvers of the registry, one line each, then auto (the "
                     "default) with the chain of solvers of each of its rules")
      ->callback([] {
        const solvers::SolverRegistry registry = solvers::SolverRegistry::builtIn();
        for (const solvers::SolverEntry& e : registry.entries())
          std::cout << e.name << "\t" << e.summary << "\n";
        std::cout << solvers::automaticListing();  // the default is no registry entry
      });

  auto args = std::make_shared<SolveArgs>();
  CLI::App* solve = app.add_subcommand(
      "solve",
      "Solve a frictional contact problem (fc3d-text file) with one or all solvers; "
      "prints one JSON line per solver");
  solve->add_option("file", args->file, "problem file in the fc3d-text 1 format")->required();
  solve
      ->add_option(
          "--solver", args->solver,
          "solver name (see `coulomb solvers`), all, auto (the default of simulations: a "
          "chain of solvers per problem by the rules `coulomb solvers` lists), a chain a,b,c, "
          "or name! (no fallback)")
      ->capture_default_str();
  solve->add_option("--tol", args->tolerance, "tolerance on the common relative residual")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  solve
      ->add_option("--max-iter", args->maxIterations,
                   "iteration budget (Newton steps or sweeps); 0 = each solver's default")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  solve->add_option("--time-limit", args->timeLimit, "wall-clock limit per solver [s]")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  solve->add_option("--solution", args->solutionPath,
                    "write r (3 numbers per contact) of the solver with the smallest residual");
  solve->add_option("--start", args->startPath,
                    "start every solver from this r (3 numbers per contact; `coulomb run "
                    "--capture` writes the step's warm start as <problem>.start)");
  solve->add_flag("--history", args->history,
                  "add each solver's [iteration, seconds, residual] after every iteration");
  solve->callback([args] { runSolve(*args); });
}

}  // namespace coulomb::cli
