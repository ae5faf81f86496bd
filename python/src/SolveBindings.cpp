// coulomb.solve and friends (docs/python.md "Solvers"): the same semantics as `coulomb solve`
// (a registry name runs that solver alone; "auto", a chain "a,b,c" or "name!" run the chooser's
// plan with its fallbacks), so a Python result is bit-identical to the CLI's. The GIL is released
// while a solver runs.
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/solvers/ContactSolver.hpp>
#include <coulomb/solvers/Residual.hpp>
#include <coulomb/solvers/SolveWithFallback.hpp>
#include <coulomb/solvers/SolverChooser.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>

#include <pybind11/stl.h>

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "Bindings.hpp"
#include "NumpyConversion.hpp"

namespace py = pybind11;
using coulomb::engine::CoulombError;
using coulomb::solvers::ContactProblem;
using coulomb::solvers::SolverReport;

namespace coulomb::python {
namespace {

struct SolveResult {
  solvers::SolveOutcome outcome;
  std::vector<std::string> attempts;  // the solvers that ran, in order
  std::string planReason;             // the chooser's rule and features; empty for a plain name
};

bool isPlan(const std::string& solver) {
  return solver == "auto" || solver.find(',') != std::string::npos ||
         (!solver.empty() && solver.back() == '!');
}

std::string knownSolvers(const solvers::SolverRegistry& registry) {
  std::string known;
  for (const std::string& n : registry.names()) known += " " + n;
  return known + " (or auto, a chain a,b,c, or name! for no fallback)";
}

SolveResult solve(const ContactProblem& problem, const std::string& solver, double tolerance,
                  int maxIterations, std::optional<double> timeLimit, bool useWarmStart,
                  const py::object& start, bool recordHistory) {
  solvers::SolverOptions options;
  options.tolerance = tolerance;
  options.maxIterations = maxIterations;
  if (timeLimit) options.timeLimitSeconds = *timeLimit;
  options.useWarmStart = useWarmStart || !start.is_none();
  options.recordHistory = recordHistory;
  if (auto bad = solvers::validateOptions(options)) throw CoulombError("solve: " + *bad);
  ContactProblem started = problem;  // shares W: the copy costs q and the blocks
  if (!start.is_none()) started.warmStart = toVector(start, "start", problem.size());

  const solvers::SolverRegistry registry = solvers::SolverRegistry::builtIn();
  SolveResult result;
  if (!isPlan(solver)) {
    std::unique_ptr<solvers::ContactSolver> made = registry.create(solver);
    if (!made)
      throw CoulombError("unknown solver '" + solver + "'; known:" + knownSolvers(registry));
    {
      py::gil_scoped_release released;
      result.outcome = made->solve(started, options);
    }
    result.attempts.push_back(solver);
    return result;
  }
  std::string error;
  const std::optional<solvers::SolverChoice> choice = solvers::parseSolverChoice(solver, error);
  if (!choice) throw CoulombError("solver: " + error);
  if (auto unknown = solvers::unknownSolver(*choice, registry))
    throw CoulombError("unknown solver '" + *unknown + "'; known:" + knownSolvers(registry));
  solvers::PlanOutcome planned;
  solvers::SolvePlan plan;
  {
    py::gil_scoped_release released;
    plan = solvers::SolverChooser().choose(started, {}, *choice, options);
    planned = solvers::solveWithFallback(started, plan, registry);
  }
  result.outcome = std::move(planned.best);
  result.outcome.report.seconds = planned.seconds;  // as `coulomb solve`: the whole plan
  result.outcome.report.iterations = planned.iterations();
  for (const SolverReport& attempt : planned.attempts) result.attempts.push_back(attempt.solver);
  result.planReason = plan.reason();
  return result;
}

py::array_t<double> historyArray(const SolverReport& r) {
  py::array_t<double> out({static_cast<py::ssize_t>(r.history.size()), py::ssize_t{3}});
  auto view = out.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < view.shape(0); ++i) {
    const solvers::IterationRecord& h = r.history[static_cast<std::size_t>(i)];
    view(i, 0) = h.iteration;
    view(i, 1) = h.seconds;
    view(i, 2) = h.residual;
  }
  return out;
}

}  // namespace

void bindSolve(py::module_& m) {
  py::class_<SolveResult>(m, "SolveResult", "What a solve returns (docs/python.md \"Solvers\")")
      .def_property_readonly(
          "impulses", [](const SolveResult& s) { return toNumpy(s.outcome.impulses); },
          "r [N s], always finite")
      .def_property_readonly(
          "velocities", [](const SolveResult& s) { return toNumpy(s.outcome.velocities); },
          "u = W r + q [m/s]")
      .def_property_readonly(
          "solver", [](const SolveResult& s) { return s.outcome.report.solver; },
          "the solver whose answer this is")
      .def_property_readonly(
          "status",
          [](const SolveResult& s) {
            return std::string(solvers::statusName(s.outcome.report.status));
          },
          "converged, max_iterations, stalled, numerical_failure, invalid_problem or "
          "not_applicable")
      .def_property_readonly("converged",
                             [](const SolveResult& s) { return s.outcome.report.converged(); })
      .def_property_readonly(
          "iterations", [](const SolveResult& s) { return s.outcome.report.iterations; },
          "Newton steps or sweeps (summed over a plan's attempts)")
      .def_property_readonly("seconds",
                             [](const SolveResult& s) { return s.outcome.report.seconds; })
      .def_property_readonly(
          "residual", [](const SolveResult& s) { return s.outcome.report.residual; },
          "common relative residual e_rel (docs/solvers.md)")
      .def_property_readonly("absolute_residual",
                             [](const SolveResult& s) { return s.outcome.report.absoluteResidual; })
      .def_property_readonly("native_residual",
                             [](const SolveResult& s) { return s.outcome.report.nativeResidual; })
      .def_property_readonly(
          "native_residual_name",
          [](const SolveResult& s) { return s.outcome.report.nativeResidualName; })
      .def_property_readonly("time_limit_reached",
                             [](const SolveResult& s) { return s.outcome.report.timeLimitReached; })
      .def_property_readonly("message",
                             [](const SolveResult& s) { return s.outcome.report.message; })
      .def_property_readonly(
          "history", [](const SolveResult& s) { return historyArray(s.outcome.report); },
          "(k, 3) array of (iteration, seconds, e_rel) when record_history=True")
      .def_readonly("attempts", &SolveResult::attempts, "the solvers that ran, in order")
      .def_readonly("plan_reason", &SolveResult::planReason,
                    "why the chooser picked this plan (auto, chains); empty for a plain name")
      .def("__repr__", [](const SolveResult& s) {
        const SolverReport& r = s.outcome.report;
        return "<coulomb.SolveResult " + r.solver + ": " + solvers::statusName(r.status) + ", " +
               std::to_string(r.iterations) + " iterations, residual " +
               py::str(py::float_(r.residual)).cast<std::string>() + ">";
      });

  m.def("solve", &solve, py::arg("problem"), py::arg("solver") = "auto", py::kw_only(),
        py::arg("tol") = 1e-8, py::arg("max_iterations") = 0, py::arg("time_limit") = py::none(),
        py::arg("use_warm_start") = true, py::arg("start") = py::none(),
        py::arg("record_history") = false,
        "Solves the problem. solver: a name of coulomb.solvers() (that solver alone), 'auto', a "
        "chain 'a,b,c' or 'name!'. tol: target of the common relative residual; max_iterations: 0 "
        "= the solver's default; time_limit [s]; start: initial impulses (used as a warm start).");

  m.def(
      "solvers",
      [] {
        std::map<std::string, std::string> table;
        const solvers::SolverRegistry registry = solvers::SolverRegistry::builtIn();
        for (const solvers::SolverEntry& e : registry.entries()) table[e.name] = e.summary;
        table["auto"] =
            "the default: per problem, a chain of solvers chosen by the rules `coulomb solvers` "
            "lists, tried in order until one converges";
        return table;
      },
      "The solvers by name, with a one-line summary each");

  m.def(
      "residual",
      [](const ContactProblem& p, const py::object& r, bool absolute) {
        const solvers::ResidualValue value = solvers::commonResidual(p, toVector(r, "r", p.size()));
        return absolute ? value.absolute : value.relative;
      },
      py::arg("problem"), py::arg("r"), py::arg("absolute") = false,
      "The common residual of r (docs/solvers.md): e_rel, or e_abs with absolute=True");
  m.def(
      "velocity",
      [](const ContactProblem& p, const py::object& r) {
        Eigen::VectorXd u(p.size());
        p.W.velocity(toVector(r, "r", p.size()), p.q, u);
        return toNumpy(u);
      },
      py::arg("problem"), py::arg("r"), "u = W r + q");
}

}  // namespace coulomb::python
