// `coulomb conformance [--cases a,b] [--solvers a,b] [--scale X] [--markdown FILE]`: runs the
// conformance cases of docs/scene-specifications.md (samples/conformance) once per solver and
// prints one row each: verdict, metric against its criterion, ms per step, residual, iterations,
// fallbacks. The table of docs/conformance.md is this command's --markdown output.
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "Commands.hpp"
#include "SolverComparison.hpp"
#include "conformance/ConformanceCase.hpp"

namespace coulomb::cli {
namespace {

struct ConformanceOptions {
  std::string cases;    // comma-separated case names; empty = all
  std::string solvers;  // comma-separated; empty = conformance::tableSolvers()
  double scale = 1.0;   // horizon scale
  std::string markdown;
  bool list = false;
};

// As `coulomb run` prints it.
std::string hashText(std::uint64_t hash) {
  char text[32];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

std::string formatNumber(double value, const char* format) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

struct Row {
  const conformance::ConformanceCase* testCase;
  std::string solver;
  conformance::CaseRun run;
  std::string error;  // the run threw (solver refused the problem, ...)
};

std::string verdict(const Row& row) {
  if (!row.error.empty()) return "error";
  return row.run.passed ? "pass" : "FAIL";
}

void printRow(std::ostream& out, const Row& row) {
  out << row.testCase->name << "  " << row.solver << "  " << verdict(row) << "  "
      << row.testCase->metricName << " = " << formatNumber(row.run.metric, "%.6g") << " ("
      << row.testCase->criterion << ")  " << formatNumber(row.run.msPerStep, "%.3f")
      << " ms/step  residual " << formatNumber(row.run.maxResidual, "%.1e") << "  iterations "
      << formatNumber(row.run.meanIterations, "%.1f") << " (max " << row.run.maxIterations
      << ")  fallbacks " << row.run.fallbacks << "  state " << hashText(row.run.stateHash);
  if (!row.error.empty()) out << "  error: " << row.error;
  if (!row.run.detail.empty()) out << "  [" << row.run.detail << "]";
  out << "\n";
}

void writeMarkdown(const std::string& path, const std::vector<Row>& rows, double scale) {
  std::ofstream out(path);
  if (!out) throw CommandError("--markdown: cannot write '" + path + "'");
  out << "| case | docs/scene-specifications.md | solver | verdict | metric | value | criterion | "
         "ms/step | max "
         "residual "
         "| mean (max) iterations | fallbacks |\n";
  out << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& row : rows) {
    out << "| " << row.testCase->name << " | " << row.testCase->section << " | " << row.solver
        << " | " << (row.run.passed && row.error.empty() ? "pass" : "**" + verdict(row) + "**")
        << " | " << row.testCase->metricName << " | " << formatNumber(row.run.metric, "%.4g")
        << " | " << row.testCase->criterion << " | " << formatNumber(row.run.msPerStep, "%.3f")
        << " | " << formatNumber(row.run.maxResidual, "%.1e") << " | "
        << formatNumber(row.run.meanIterations, "%.1f") << " (" << row.run.maxIterations << ") | "
        << row.run.fallbacks << " |\n";
  }
  if (scale != 1.0) out << "\nHorizons scaled by " << scale << ".\n";
}

void runConformance(const ConformanceOptions& options) {
  if (options.list) {
    for (const conformance::ConformanceCase& c : conformance::allCases())
      std::cout << c.name << "  (" << c.section << ", scene " << c.scene << "): " << c.metricName
                << " " << c.criterion << "\n";
    return;
  }
  std::vector<const conformance::ConformanceCase*> selected;
  if (options.cases.empty()) {
    for (const conformance::ConformanceCase& c : conformance::allCases()) selected.push_back(&c);
  } else {
    for (const std::string& name : splitList(options.cases))
      selected.push_back(&conformance::findCase(name));
  }
  const std::vector<std::string> solvers =
      options.solvers.empty() ? conformance::tableSolvers() : splitList(options.solvers);
  std::vector<Row> rows;
  int failures = 0;
  for (const conformance::ConformanceCase* testCase : selected) {
    for (const std::string& solver : solvers) {
      Row row{testCase, solver, {}, {}};
      try {
        row.run = testCase->run(conformance::CaseOptions{solver, options.scale});
      } catch (const std::exception& e) {
        row.error = e.what();
      }
      if (!row.run.passed || !row.error.empty()) ++failures;
      printRow(std::cout, row);
      std::cout.flush();
      rows.push_back(std::move(row));
    }
  }
  if (!options.markdown.empty()) writeMarkdown(options.markdown, rows, options.scale);
  std::cout << rows.size() - static_cast<std::size_t>(failures) << " of " << rows.size()
            << " runs pass\n";
}

}  // namespace

void registerConformanceCommand(CLI::App& app) {
  auto options = std::make_shared<ConformanceOptions>();
  CLI::App* command =
      app.add_subcommand("conformance",
                         "Run the conformance cases of docs/scene-specifications.md "
                         "(docs/conformance.md) once per solver: verdict, "
                         "metric, ms/step, residual, iterations");
  command->add_option("--cases", options->cases,
                      "Comma-separated case names (default: all; --list shows them)");
  command->add_option("--solvers", options->solvers,
                      "Comma-separated solvers (default: auto and each solver alone: pgs!, bgs!, "
                      "ac_newton!, fb_newton!, staggered!, lemke!)");
  command
      ->add_option(
          "--scale", options->scale,
          "Run this fraction of each case's docs/scene-specifications.md duration (default 1)")
      ->check(CLI::PositiveNumber);
  command->add_option("--markdown", options->markdown, "Also write the table as Markdown to FILE");
  command->add_flag("--list", options->list, "List the cases and their criteria");
  command->callback([options] { runConformance(*options); });
}

}  // namespace coulomb::cli
