// Corpus benchmark of the contact solvers (issue 5 item 6): every registered solver on every
// .fc3d problem of a folder, tolerance 1e-8 on the common residual, a time limit per solve,
// median seconds over repeats for small problems; prints a Markdown table next to the Siconos
// reference (SICONOS_REFERENCE.tsv of the folder, when present) and checks that
// solvers::commonResidual agrees with the reference fc3d_natural_map_residual.
//
// `auto` (SolverChooser + solveWithFallback, every attempt's time and iterations summed) is one
// more column; the summary compares it with the fastest converging solver of each problem.
//
//   SolverCorpusBench FOLDER [--solvers pgs,bgs,ac_newton,auto] [--tol 1e-8] [--time-limit 60]
//                     [--repeats 5] [--max-iter N] [--out table.md] [--only NAME]
#include <coulomb/solvers/Residual.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>

#include <bench/CorpusSolve.hpp>  // corpus listing and solving, shared with `coulomb bench`

#include <fc3d_text.hpp>  // reference reader + residual (tests/data/fc3d, copied from the corpus)

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace coulomb::solvers;

namespace {

struct Row {
  std::string problem;
  int contacts = 0;
  std::string solver;
  SolverReport report;
};

struct Reference {  // one line of SICONOS_REFERENCE.tsv
  std::map<std::string, std::string> field;
};

std::map<std::string, Reference> readReference(const fs::path& path) {
  std::map<std::string, Reference> out;
  std::ifstream f(path);
  std::string line;
  std::vector<std::string> header;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cols;
    std::stringstream s(line);
    std::string c;
    while (std::getline(s, c, '\t')) cols.push_back(c);
    if (header.empty()) {
      header = cols;
      continue;
    }
    Reference r;
    for (size_t i = 0; i < cols.size() && i < header.size(); ++i) r.field[header[i]] = cols[i];
    out[cols[0]] = r;
  }
  return out;
}

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: SolverCorpusBench FOLDER [--solvers a,b] [--tol X] [--time-limit S] "
                 "[--repeats N] [--max-iter N] [--out FILE.md] [--only NAME]\n";
    return 2;
  }
  const fs::path folder = argv[1];
  if (!fs::is_directory(folder)) {
    std::cerr << "SolverCorpusBench: '" << folder.string()
              << "' is not a folder of .fc3d problems (usage: SolverCorpusBench FOLDER ...)\n";
    return 2;
  }
  std::vector<std::string> solvers;
  double tol = 1e-8, timeLimit = 60;
  int repeats = 5, maxIterations = 0;
  std::string outPath, only;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--solvers") {
      std::stringstream s(v);
      std::string n;
      while (std::getline(s, n, ',')) solvers.push_back(n);
    } else if (a == "--tol")
      tol = std::atof(v.c_str());
    else if (a == "--time-limit")
      timeLimit = std::atof(v.c_str());
    else if (a == "--repeats")
      repeats = std::atoi(v.c_str());
    else if (a == "--max-iter")
      maxIterations = std::atoi(v.c_str());
    else if (a == "--out")
      outPath = v;
    else if (a == "--only")
      only = v;
    else {
      std::cerr << "unknown option " << a << "\n";
      return 2;
    }
  }
  const SolverRegistry registry = SolverRegistry::builtIn();
  if (solvers.empty()) {
    solvers = registry.names();
    solvers.push_back("auto");
  }
  std::vector<coulomb::samples::CorpusFile> files;
  try {
    files = coulomb::samples::listCorpus(folder, only);
  } catch (const std::exception& e) {
    std::cerr << "SolverCorpusBench: " << e.what() << "\n";
    return 1;
  }
  const auto reference = readReference(folder / "SICONOS_REFERENCE.tsv");

  SolverOptions options;
  options.tolerance = tol;
  options.timeLimitSeconds = timeLimit;
  options.maxIterations = maxIterations;
  std::vector<Row> rows;
  double worstResidualMismatch = 0;
  std::string worstMismatchAt;
  for (const coulomb::samples::CorpusFile& file : files) {
    const ContactProblem problem = coulomb::samples::readCorpusProblem(file.path);
    Fc3dProblem ref;
    fc3d_read(file.path.string(), ref);
    auto check = [&](const Eigen::VectorXd& r, const std::string& at) {
      // Compared as the number reported, e_rel = e_abs / (1 + ||q||): at an answer e_abs is
      // round-off, where the reference's std::hypot and our tangentNorm differ in their own
      // round-off (docs/solvers.md "Residual").
      const double ours = commonResidual(problem, r).absolute;
      const double theirs = fc3d_natural_map_residual(ref, r.data());
      const double d = std::abs(ours - theirs) / (1.0 + plainNorm(problem.q));
      if (d > worstResidualMismatch || worstMismatchAt.empty()) {
        worstResidualMismatch = std::max(worstResidualMismatch, d);
        worstMismatchAt = problem.name + " " + at;
      }
    };
    check(Eigen::VectorXd::Zero(problem.size()), "r = 0");
    for (const std::string& name : solvers) {
      if (name != "auto" && !registry.create(name)) {
        std::cerr << "unknown solver " << name << "\n";
        return 2;
      }
      const SolveOutcome first =
          coulomb::samples::solveMedian(problem, name, options, registry, repeats);
      check(first.impulses, name + " solution");
      std::cerr << problem.name << " " << name << " " << statusName(first.report.status) << " it "
                << first.report.iterations << " t " << first.report.seconds << " e "
                << first.report.residual << " | " << first.report.message << "\n";
      rows.push_back({problem.name, problem.contactCount(), name, first.report});
    }
  }

  std::ostringstream md;
  md << "| problem | contacts | solver | status | iterations | seconds | residual |\n";
  md << "|---|---:|---|---|---:|---:|---:|\n";
  std::string lastProblem;
  for (const Row& r : rows) {
    md << "| " << r.problem << " | " << r.contacts << " | " << r.solver << " | "
       << statusName(r.report.status) << " | " << r.report.iterations << " | "
       << fmt("%.3g", r.report.seconds) << " | " << fmt("%.2e", r.report.residual) << " |\n";
    const bool lastOfProblem = &r == &rows.back() || (&r + 1)->problem != r.problem;
    if (lastOfProblem && reference.count(r.problem)) {
      const auto& f = reference.at(r.problem).field;
      for (const char* s : {"NSN_AC", "NSGS"}) {
        const std::string p = s;
        md << "| " << r.problem << " | " << r.contacts << " | *Siconos " << p << "* | *"
           << f.at(p + "_status") << "* | *" << f.at(p + "_iter") << "* | *"
           << fmt("%.3g", std::atof(f.at(p + "_time_s").c_str())) << "* | *"
           << fmt("%.2e", std::atof(f.at(p + "_natmap_rel").c_str())) << "* |\n";
      }
    }
  }
  // Summary: converged counts and times against Siconos on the problems both converge on.
  md << "\n| solver | converged (e_rel <= " << fmt("%g", tol) << ") | total seconds |"
     << " vs Siconos NSN_AC on both-converged: ours / theirs (n) |"
     << " vs Siconos NSGS on both-converged: ours / theirs (n) |\n|---|---:|---:|---:|---:|\n";
  for (const std::string& name : solvers) {
    int conv = 0;
    double total = 0;
    double ours[2] = {0, 0}, theirs[2] = {0, 0};
    int both[2] = {0, 0};
    for (const Row& r : rows) {
      if (r.solver != name) continue;
      total += r.report.seconds;
      const bool ok = r.report.residual <= tol;
      conv += ok;
      if (!ok || !reference.count(r.problem)) continue;
      const auto& f = reference.at(r.problem).field;
      const char* refs[2] = {"NSN_AC", "NSGS"};
      for (int k = 0; k < 2; ++k) {
        const std::string p = refs[k];
        if (std::atof(f.at(p + "_natmap_rel").c_str()) <= tol) {
          ours[k] += r.report.seconds;
          theirs[k] += std::atof(f.at(p + "_time_s").c_str());
          ++both[k];
        }
      }
    }
    md << "| " << name << " | " << conv << " / " << files.size() << " | " << fmt("%.3g", total)
       << " | " << fmt("%.3g", ours[0]) << " / " << fmt("%.3g", theirs[0]) << " (" << both[0]
       << ") | " << fmt("%.3g", ours[1]) << " / " << fmt("%.3g", theirs[1]) << " (" << both[1]
       << ") |\n";
  }
  // auto against the fastest converging named solver of each problem (issue 6 target: 1.5x).
  if (std::find(solvers.begin(), solvers.end(), "auto") != solvers.end()) {
    double autoTotal = 0, bestTotal = 0;
    int counted = 0, autoConverged = 0;
    std::string slowest;
    double worstRatio = 0;
    for (const coulomb::samples::CorpusFile& file : files) {
      const std::string& problemName = file.name;
      double best = -1, mine = -1;
      bool mineOk = false;
      for (const Row& r : rows) {
        if (r.problem != problemName) continue;
        if (r.solver == "auto") {
          mine = r.report.seconds;
          mineOk = r.report.residual <= tol;
        } else if (r.report.residual <= tol && (best < 0 || r.report.seconds < best)) {
          best = r.report.seconds;
        }
      }
      autoConverged += mineOk;
      if (best < 0 || mine < 0) continue;
      ++counted;
      autoTotal += mine;
      bestTotal += best;
      if (mine / best > worstRatio) worstRatio = mine / best, slowest = problemName;
    }
    md << "\nauto: converged on " << autoConverged << " / " << files.size() << "; on the "
       << counted << " problems some named solver converges, auto took " << fmt("%.3g", autoTotal)
       << " s against " << fmt("%.3g", bestTotal)
       << " s for the fastest converging solver of each problem (ratio "
       << fmt("%.2f", bestTotal > 0 ? autoTotal / bestTotal : 0.0) << "; worst single problem "
       << fmt("%.1f", worstRatio) << "x, " << slowest << ").\n";
  }
  md << "\nResidual check: solvers::commonResidual vs fc3d_natural_map_residual, worst difference "
        "of e_rel "
     << fmt("%.2e", worstResidualMismatch) << " (" << worstMismatchAt << "), over r = 0 and every "
     << "solution above.\n";
  std::cout << md.str();
  if (!outPath.empty()) std::ofstream(outPath) << md.str();
  return 0;
}
