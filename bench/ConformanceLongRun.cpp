// Runs conformance cases (samples/conformance) at their full horizon, or a scaled one, for the
// long runs that do not fit in CI (issue 8 item 5; docs/conformance.md "Long-run stability").
//   ConformanceLongRun [--solvers auto,pgs] [--scale 1] box_stack/N=20 pyramid/base=10 ...
//   ConformanceLongRun --list
// One line per case and solver: verdict, metric, ms/step, residual, iterations, fallbacks and the
// case's detail line. Exit status 1 if any run failed or threw.
#include "CommaList.hpp"
#include "conformance/ConformanceCase.hpp"

#include <coulomb/engine/CoulombError.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <string>
#include <vector>

using namespace coulomb;

namespace {

int usage() {
  std::fprintf(stderr, "usage: ConformanceLongRun [--solvers a,b] [--scale X] CASE... | --list\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> solvers = {"auto"};
  double scale = 1.0;
  std::vector<std::string> names;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--list") {
      for (const conformance::ConformanceCase& c : conformance::allCases())
        std::printf("%s  (%s, scene %s): %s %s\n", c.name.c_str(), c.section.c_str(),
                    c.scene.c_str(), c.metricName.c_str(), c.criterion.c_str());
      return 0;
    }
    if ((arg == "--solvers" || arg == "--scale") && i + 1 >= argc) return usage();
    if (arg == "--solvers") {
      solvers = coulomb::samples::splitCommaList(argv[++i]);
    } else if (arg == "--scale") {
      char* end = nullptr;
      scale = std::strtod(argv[++i], &end);
      if (end == nullptr || *end != '\0' || !(scale > 0.0)) {
        std::fprintf(stderr, "--scale: expected a number > 0, got '%s'\n", argv[i]);
        return 2;
      }
    } else if (!arg.empty() && arg[0] == '-') {
      return usage();
    } else {
      names.push_back(arg);
    }
  }
  if (names.empty() || solvers.empty()) return usage();
  bool allPassed = true;
  for (const std::string& name : names) {
    for (const std::string& solver : solvers) {
      try {
        const conformance::ConformanceCase& c = conformance::findCase(name);
        const conformance::CaseRun run = c.run({solver, scale});
        allPassed = allPassed && run.passed;
        std::printf(
            "%s  %s  %s  %s = %.6g (%s)  steps %zu  %.3f ms/step  residual %.1e  iterations "
            "%.1f (max %d)  fallbacks %zu  [%s]\n",
            name.c_str(), solver.c_str(), run.passed ? "pass" : "FAIL", c.metricName.c_str(),
            run.metric, c.criterion.c_str(), run.steps, run.msPerStep, run.maxResidual,
            run.meanIterations, run.maxIterations, run.fallbacks, run.detail.c_str());
      } catch (const std::exception& e) {
        allPassed = false;
        std::printf("%s  %s  error: %s\n", name.c_str(), solver.c_str(), e.what());
      }
      std::fflush(stdout);
    }
  }
  return allPassed ? 0 : 1;
}
