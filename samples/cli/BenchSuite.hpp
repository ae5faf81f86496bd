#pragma once
// `coulomb bench`, the benchmark suite (issue 12): parts (corpus, scenes, sweep, nu, joints,
// aba) at a size (quick or full), one BenchRecord per measured item, written as one CSV
// (scripts/plot_bench.py reads it) and a Markdown summary. Times are medians over repeats; every
// record also carries its errors (residual, drift, joint gap, energy change), never a time alone.
#include <cstddef>
#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace coulomb::cli {

/// One measured item. Unused figures stay NaN (written as empty CSV fields).
struct BenchRecord {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::string part;     // corpus, scenes, sweep, nu, joints, aba
  std::string item;     // problem, scene or chain name
  std::string solver;   // as requested ("auto", "pgs!", ...), or "" (aba)
  std::string variant;  // what was varied: "tol=1e-08", "max_iter=20", "predicted_state", ...
  int size = 0;         // contacts (corpus), dynamic bodies (scenes), links (joints, aba)
  int repeats = 0;      // runs behind the median time (nu: island solves in the bin)
  double ms = kNaN;     // [ms] per step (scenes, sweep, joints), per solve (corpus), per ABA (aba)
  double iterationsMean = kNaN;
  double iterationsMax = kNaN;
  double residualMean = kNaN;  // common relative residual (aba: |M qdd + h - tau|_inf)
  double residualMax = kNaN;
  double maxDrift = kNaN;  // [m] largest COM displacement of a dynamic body
  double energyChange =
      kNaN;  // [J] E(T) - E(0); joints: divided by S (docs/scene-specifications.md A6)
  double jointGap = kNaN;  // [m] largest joint anchor gap
  double nu = kNaN;    // nu (scenes, islands) or nu-hat (corpus), docs/solver-derivations.md (9.1)
  std::string status;  // solver status (corpus), "converged" share (nu), ...
  std::string note;    // "capped: simulated X of Y s", "time limit", ...
};

enum class BenchSize { Quick, Full };

struct SuiteOptions {
  std::vector<std::string> parts;  // subset of allBenchParts()
  BenchSize size = BenchSize::Quick;
  int repeats = 3;
  std::string corpus;                              // folder of .fc3d problems ("" = corpus skipped)
  std::optional<std::vector<std::string>> scenes;  // replaces the size's scene list
  std::optional<std::vector<std::string>> solvers;  // replaces auto,pgs,bgs,ac_newton
  std::optional<std::uint64_t> steps;  // replaces each scene's (and chain's) step count
  double timeCap = 10.0;   // [s] summed step time per run (docs/scene-specifications.md section 0)
  double timeLimit = 0.0;  // [s] per corpus solve; 0 = the size's
  std::vector<int> sweepIterations;  // empty = the size's
  double sweepTolerance = 1e-12;
};

/// corpus, scenes, sweep, nu, joints, aba: the order they run in.
const std::vector<std::string>& allBenchParts();

/// Prints "[part i/n, elapsed, ETA] item" lines on a stream (stderr): where a long run is.
class BenchProgress {
 public:
  BenchProgress(std::ostream& out, std::string part, std::size_t total);
  void next(const std::string& item);  // item i + 1 of n starts

 private:
  std::ostream& out_;
  std::string part_;
  std::size_t total_;
  std::size_t started_ = 0;
  double startSeconds_;
};

// The parts, one file each (BenchSuiteScenes.cpp, BenchSuiteCorpus.cpp, BenchSuiteJoints.cpp);
// each appends its records. Names are checked before anything runs (bad input fails at once).
void runScenesPart(const SuiteOptions& o, std::vector<BenchRecord>& out);
void runSweepPart(const SuiteOptions& o, std::vector<BenchRecord>& out);
void runNuScenesPart(const SuiteOptions& o, std::vector<BenchRecord>& out);
void runCorpusPart(const SuiteOptions& o, std::vector<BenchRecord>& out);  // records nu-hat too
void runJointsPart(const SuiteOptions& o, std::vector<BenchRecord>& out);
void runAbaPart(const SuiteOptions& o, std::vector<BenchRecord>& out);

struct ComparisonRow;
/// A scene-like run's record: the row's iterations, residuals, drift, energy change, joint gap,
/// applied solvers and note, with the median time `ms` over `repeats` runs.
BenchRecord recordOf(const std::string& part, const ComparisonRow& row, std::string variant,
                     int size, int repeats, double ms);

/// Wall clock [s] since an arbitrary origin (steady clock).
double benchNow();

void writeBenchCsv(std::ostream& out, const std::vector<BenchRecord>& records);
void writeBenchMarkdown(std::ostream& out, const std::vector<BenchRecord>& records);

}  // namespace coulomb::cli
