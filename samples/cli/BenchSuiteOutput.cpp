// The suite's outputs: the progress lines on stderr, one CSV of every record (the input of
// scripts/plot_bench.py) and a Markdown summary with one table per part.
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "BenchSuite.hpp"
#include "SolverComparison.hpp"

namespace coulomb::cli {

const std::vector<std::string>& allBenchParts() {
  static const std::vector<std::string> parts{"corpus", "scenes", "sweep", "nu", "joints", "aba"};
  return parts;
}

namespace {

std::string clock(double seconds) {
  char text[32];
  const long s = std::lround(seconds);
  std::snprintf(text, sizeof text, "%ld:%02ld", s / 60, s % 60);
  return text;
}

/// A number in 3 significant digits; "" for NaN (an unused figure).
std::string num(double value) {
  if (std::isnan(value)) return "";
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

/// A number in full (CSV): round-trip precision; "" for NaN.
std::string exact(double value) {
  if (std::isnan(value)) return "";
  char text[40];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

/// CSV field: quoted when it holds a comma or a quote.
std::string field(const std::string& text) {
  if (text.find_first_of(",\"") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace

BenchRecord recordOf(const std::string& part, const ComparisonRow& row, std::string variant,
                     int size, int repeats, double ms) {
  return {.part = part,
          .item = row.scene,
          .solver = row.solver,
          .variant = std::move(variant),
          .size = size,
          .repeats = repeats,
          .ms = ms,
          .iterationsMean = row.iterationsMean,
          .iterationsMax = static_cast<double>(row.iterationsMax),
          .residualMean = row.residualMean,
          .residualMax = row.residualMax,
          .maxDrift = row.maxDrift,
          .energyChange = row.energyChange,
          .jointGap = row.maxJointGap,
          .nu = BenchRecord::kNaN,
          .status = row.used,
          .note = row.note};
}

BenchProgress::BenchProgress(std::ostream& out, std::string part, std::size_t total)
    : out_(out), part_(std::move(part)), total_(total), startSeconds_(benchNow()) {}

void BenchProgress::next(const std::string& item) {
  const double elapsed = benchNow() - startSeconds_;
  out_ << "[" << part_ << " " << started_ + 1 << "/" << total_ << ", " << clock(elapsed)
       << " elapsed";
  if (started_ > 0)  // ETA from the mean time per item so far
    out_ << ", ETA "
         << clock(elapsed / static_cast<double>(started_) * static_cast<double>(total_ - started_));
  out_ << "] " << item << "\n" << std::flush;
  ++started_;
}

void writeBenchCsv(std::ostream& out, const std::vector<BenchRecord>& records) {
  out << "part,item,solver,variant,size,repeats,ms,iterations_mean,iterations_max,residual_mean,"
         "residual_max,max_drift,energy_change,joint_gap,nu,status,note\n";
  for (const BenchRecord& r : records)
    out << r.part << ',' << field(r.item) << ',' << field(r.solver) << ',' << field(r.variant)
        << ',' << r.size << ',' << r.repeats << ',' << exact(r.ms) << ',' << exact(r.iterationsMean)
        << ',' << exact(r.iterationsMax) << ',' << exact(r.residualMean) << ','
        << exact(r.residualMax) << ',' << exact(r.maxDrift) << ',' << exact(r.energyChange) << ','
        << exact(r.jointGap) << ',' << exact(r.nu) << ',' << field(r.status) << ',' << field(r.note)
        << '\n';
}

void writeBenchMarkdown(std::ostream& out, const std::vector<BenchRecord>& records) {
  std::set<std::string> present;
  for (const BenchRecord& r : records) present.insert(r.part);
  const auto rows = [&](const std::string& part, auto&& line) {
    for (const BenchRecord& r : records)
      if (r.part == part) out << line(r) << "\n";
  };
  if (present.count("corpus")) {
    out << "\n### Solver corpus (median ms per solve)\n\n"
           "| problem | contacts | nu-hat | solver | tolerance | status | iterations | ms | "
           "residual | note |\n|---|---:|---:|---|---|---|---:|---:|---:|---|\n";
    rows("corpus", [](const BenchRecord& r) {
      return "| " + r.item + " | " + std::to_string(r.size) + " | " + num(r.nu) + " | " + r.solver +
             " | " + r.variant.substr(4) + " | " + r.status + " | " + num(r.iterationsMax) + " | " +
             num(r.ms) + " | " + num(r.residualMax) + " | " + r.note + " |";
    });
    // Per solver and tolerance: how many problems reached it, and the summed time.
    std::map<std::pair<std::string, std::string>, std::pair<int, int>> reached;
    std::map<std::pair<std::string, std::string>, double> total;
    for (const BenchRecord& r : records)
      if (r.part == "corpus") {
        auto& [ok, n] = reached[{r.solver, r.variant}];
        ok += r.status == "converged";
        ++n;
        total[{r.solver, r.variant}] += r.ms;
      }
    out << "\n| solver | tolerance | converged | total ms |\n|---|---|---:|---:|\n";
    for (const auto& [key, count] : reached)
      out << "| " << key.first << " | " << key.second.substr(4) << " | " << count.first << " / "
          << count.second << " | " << num(total[key]) << " |\n";
  }
  const std::string sceneHeader =
      " | solver | bodies | ms/step | iterations mean / max | residual mean / max | max drift (m) "
      "| energy change (J) | joint gap (m) | applied / note |\n";
  const auto sceneLine = [](const BenchRecord& r) {
    return "| " + r.item + " | " + r.solver + (r.variant.empty() ? "" : " " + r.variant) + " | " +
           std::to_string(r.size) + " | " + num(r.ms) + " | " + num(r.iterationsMean) + " / " +
           num(r.iterationsMax) + " | " + num(r.residualMean) + " / " + num(r.residualMax) + " | " +
           num(r.maxDrift) + " | " + num(r.energyChange) + " | " + num(r.jointGap) + " | " +
           r.status + (r.note.empty() || r.status.empty() ? "" : "; ") + r.note + " |";
  };
  const std::string sceneRule = "|---|---|---:|---:|---|---|---:|---:|---:|---|\n";
  const auto sceneTable = [&](const std::string& part, const std::string& title) {
    if (!present.count(part)) return;
    out << "\n### " << title << sceneHeader << sceneRule;
    rows(part, sceneLine);
  };
  sceneTable("scenes", "Scenes (median ms/step over the repeats)\n\n| scene");
  sceneTable("sweep", "Iteration-cap sweep (each solver alone, tolerance tiny)\n\n| scene");
  if (present.count("nu")) {
    out << "\n### ac_newton iterations against nu (island solves binned by nu to 0.01)\n\n"
           "| scene | nu | solves | iterations mean / max | residual max | converged |\n"
           "|---|---:|---:|---|---:|---|\n";
    rows("nu", [](const BenchRecord& r) {
      return "| " + r.item + " | " + num(r.nu) + " | " + std::to_string(r.repeats) + " | " +
             num(r.iterationsMean) + " / " + num(r.iterationsMax) + " | " + num(r.residualMax) +
             " | " + r.status + " |";
    });
  }
  sceneTable(
      "joints",
      "Ball chains (docs/scene-specifications.md A6, dt 0.01; energy change / S)\n\n| chain");
  if (present.count("aba")) {
    out << "\n### ABA on serial chains\n\n| chain | links | ms per ABA | ns per link | "
           "abs(M qdd + h - tau) |\n|---|---:|---:|---:|---:|\n";
    rows("aba", [](const BenchRecord& r) {
      return "| " + r.item + " | " + std::to_string(r.size) + " | " + num(r.ms) + " | " +
             num(r.ms * 1e6 / r.size) + " | " + num(r.residualMax) + " |";
    });
  }
}

}  // namespace coulomb::cli
