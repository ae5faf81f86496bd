// `coulomb bench`: the benchmark suite (docs/benchmarks.md "The benchmark suite"): parts, sizes,
// medians over repeats, CSV + Markdown, progress on stderr; and `--guard FILE`, the regression
// guard on error metrics (BenchGuard.cpp).
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <set>
#include <sstream>

#include "BenchGuard.hpp"
#include "BenchSuite.hpp"
#include "Commands.hpp"
#include "RunOutputs.hpp"
#include "SolverComparison.hpp"

namespace coulomb::cli {
namespace {

struct BenchCommandOptions {
  std::string parts;  // "" = every part
  std::string size = "quick";
  int repeats = 3;
  std::string corpus;
  std::string scenes, solvers;
  std::optional<std::uint64_t> steps;
  double timeCap = 10.0;
  double timeLimit = 0.0;
  std::string sweepIterations;
  double sweepTolerance = 1e-12;
  std::string csvPath, markdownPath;
  std::string guardPath;
  bool guardUpdate = false;
};

/// The corpus a plain `coulomb bench` uses: the shared fc3d folder beside the checkout, if any.
std::string defaultCorpus() {
  const std::filesystem::path folder =
      std::filesystem::path(COULOMB_REPO_DIR) / ".." / "shared" / "fc3d";
  return std::filesystem::is_directory(folder) ? folder.lexically_normal().string() : "";
}

std::vector<int> parseCaps(const std::string& text) {
  std::vector<int> caps;
  for (const std::string& item : splitList(text)) {
    std::size_t used = 0;
    int value = 0;
    try {
      value = std::stoi(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || value <= 0)
      throw CommandError("--sweep-iterations: '" + item + "' is not a positive integer");
    caps.push_back(value);
  }
  return caps;
}

void bench(const BenchCommandOptions& c) {
  if (c.repeats < 1) throw CommandError("--repeats must be >= 1");
  if (!c.guardPath.empty()) {
    runBenchGuard(c.guardPath, c.corpus, c.guardUpdate);
    return;
  }
  SuiteOptions o;
  if (c.size != "quick" && c.size != "full")
    throw CommandError("--size: '" + c.size + "' is neither quick nor full");
  o.size = c.size == "full" ? BenchSize::Full : BenchSize::Quick;
  o.repeats = c.repeats;
  o.steps = c.steps;
  o.timeCap = c.timeCap;
  o.timeLimit = c.timeLimit;
  o.sweepTolerance = c.sweepTolerance;
  o.sweepIterations = parseCaps(c.sweepIterations);
  if (!c.scenes.empty()) o.scenes = splitList(c.scenes);
  if (!c.solvers.empty()) o.solvers = splitList(c.solvers);
  const bool partsGiven = !c.parts.empty();
  o.parts = partsGiven ? splitList(c.parts) : allBenchParts();
  for (const std::string& part : o.parts)
    if (std::find(allBenchParts().begin(), allBenchParts().end(), part) == allBenchParts().end()) {
      std::ostringstream known;
      for (const std::string& p : allBenchParts()) known << " " << p;
      throw CommandError("--parts: unknown part '" + part + "' (known:" + known.str() + ")");
    }
  o.corpus = c.corpus.empty() ? defaultCorpus() : c.corpus;
  const std::set<std::string> wanted(o.parts.begin(), o.parts.end());
  if (wanted.count("corpus") && o.corpus.empty()) {
    if (partsGiven) throw CommandError("--parts corpus needs --corpus DIR (a folder of .fc3d)");
    std::cerr << "bench: no --corpus and no ../shared/fc3d beside the checkout: corpus skipped\n";
  }
  const double start = benchNow();
  std::vector<BenchRecord> records;
  for (const std::string& part : allBenchParts()) {  // fixed order, whatever --parts says
    if (!wanted.count(part)) continue;
    if (part == "corpus" && !o.corpus.empty()) runCorpusPart(o, records);
    if (part == "scenes") runScenesPart(o, records);
    if (part == "sweep") runSweepPart(o, records);
    if (part == "nu") runNuScenesPart(o, records);
    if (part == "joints") runJointsPart(o, records);
    if (part == "aba") runAbaPart(o, records);
  }
  std::ostringstream markdown;
  markdown << "Made by `coulomb bench --size " << c.size << " --repeats " << c.repeats
           << " --time-cap " << c.timeCap
           << (c.timeLimit > 0 ? " --time-limit " + std::to_string(c.timeLimit) : "") << "` in "
           << std::lround(benchNow() - start) << " s"
           << (o.corpus.empty() ? "" : "; corpus " + o.corpus) << ".\n";
  writeBenchMarkdown(markdown, records);
  std::cout << markdown.str();
  if (!c.csvPath.empty()) {
    std::ofstream out = openOutputFile(c.csvPath, "results");
    writeBenchCsv(out, records);
    if (!out) throw CommandError("writing '" + c.csvPath + "' failed");
  }
  if (!c.markdownPath.empty()) {
    std::ofstream out = openOutputFile(c.markdownPath, "Markdown");
    out << markdown.str();
    if (!out) throw CommandError("writing '" + c.markdownPath + "' failed");
  }
}

}  // namespace

void registerBenchCommand(CLI::App& app) {
  auto o = std::make_shared<BenchCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "bench",
      "The benchmark suite: solver corpus, scenes, iteration sweep, ac_newton against nu, joint "
      "chains, ABA; medians over repeats, CSV and Markdown; progress on stderr. With --guard: "
      "the regression guard on error metrics");
  command->add_option("--parts", o->parts,
                      "Comma-separated subset of corpus,scenes,sweep,nu,joints,aba (default: all)");
  command->add_option("--size", o->size, "quick (a minute or two) or full")->capture_default_str();
  command->add_option("--repeats", o->repeats, "Runs per item; times are their median")
      ->capture_default_str();
  command->add_option("--corpus", o->corpus,
                      "Folder of .fc3d problems (default: ../shared/fc3d beside the checkout)");
  command->add_option("--scenes", o->scenes, "Comma-separated scenes (replaces the size's)");
  command->add_option("--solvers", o->solvers, "Comma-separated solvers (replaces the part's)");
  command->add_option("--steps", o->steps, "Steps per scene or chain run (default: the size's)")
      ->check(CLI::PositiveNumber);
  command
      ->add_option("--time-cap", o->timeCap,
                   "Stop a run when its summed step time exceeds this [s] "
                   "(docs/scene-specifications.md section 0)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command->add_option("--time-limit", o->timeLimit,
                      "Time limit per corpus solve [s] (default 1 quick, 5 full)");
  command->add_option("--sweep-iterations", o->sweepIterations,
                      "Iteration caps of the sweep (default 5,20,100 quick; 5,...,200 full)");
  command
      ->add_option("--sweep-tol", o->sweepTolerance,
                   "Tolerance in the sweep (tiny, so that each solve spends its cap)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command->add_option("--out", o->csvPath, "Write every record as CSV (scripts/plot_bench.py)");
  command->add_option("--markdown", o->markdownPath, "Write the summary tables as Markdown");
  command->add_option(
      "--guard", o->guardPath,
      "Run the regression guard of this threshold file (bench/guard_thresholds.json; "
      "fc3d entries are read from --corpus) and fail if a metric is worse");
  command->add_flag("--guard-update", o->guardUpdate,
                    "With --guard: write the measured values into the file (margins kept)");
  command->callback([o] { bench(*o); });
}

}  // namespace coulomb::cli
