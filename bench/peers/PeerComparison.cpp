// Coulomb's default against Bullet and ODE on the conformance scenes of part A
// (docs/conformance.md), in one process run (issue 12 item 3; docs/benchmarks.md "Peers in the same
// run").
//   PeerComparison [--scenes a,b] [--engines coulomb,bullet,ode_quickstep,ode_step]
//                  [--time-cap S] [--csv FILE] [--markdown FILE]
// Every step is timed alone (steady clock; collision + solve + integration, reading the state
// excluded); ms/step is the median after min(20, steps/10) warm-up steps. A run stops when its
// summed step time passes the cap or a body leaves |x| <= 1000 m, |v| <= 1000 m/s
// (docs/benchmarks.md "Peers in the same run").
#include "CommaList.hpp"
#include "PeerEngine.hpp"
#include "PeerMetrics.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace coulomb::peers;

namespace {

struct Run {
  std::string engine, scene;
  double dt = 0, tSim = 0, msPerStep = 0;
  std::size_t steps = 0;
  std::vector<Metric> metrics;
  std::string note;
};

using Factory = std::function<std::unique_ptr<PeerEngine>(const PeerScene&)>;

const std::map<std::string, std::pair<std::string, Factory>>& engines() {
  static const std::map<std::string, std::pair<std::string, Factory>> all = {
      {"coulomb", {"coulomb auto", makeCoulomb}},
      {"bullet", {"bullet si", makeBullet}},
      {"ode_quickstep", {"ode quickstep", [](const PeerScene& s) { return makeOde(s, true); }}},
      {"ode_step", {"ode dworldstep", [](const PeerScene& s) { return makeOde(s, false); }}}};
  return all;
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

bool diverged(const std::vector<BodySample>& x) {
  for (const BodySample& b : x)
    if (!b.position.allFinite() || !b.linearVelocity.allFinite() ||
        !b.angularVelocity.allFinite() || !b.rotation.coeffs().allFinite() ||
        b.position.norm() > 1000 || b.linearVelocity.norm() > 1000)
      return true;
  return false;
}

Run runOne(const std::string& label, const Factory& make, const PeerScene& scene, double cap) {
  Run run;
  run.engine = label;
  run.scene = scene.name;
  run.dt = scene.dt;
  std::unique_ptr<PeerEngine> engine = make(scene);
  Trajectory samples(1);
  engine->read(samples[0]);
  std::vector<double> ms;
  double total = 0.0;
  for (std::size_t k = 0; k < scene.steps; ++k) {
    const auto start = std::chrono::steady_clock::now();
    engine->step();
    const std::chrono::duration<double, std::milli> took = std::chrono::steady_clock::now() - start;
    ms.push_back(took.count());
    total += took.count() / 1000.0;
    samples.emplace_back();
    engine->read(samples.back());
    if (diverged(samples.back())) {
      run.note = "DIVERGED at t=" + fmt(static_cast<double>(k + 1) * scene.dt);
      samples.pop_back();  // metrics cover the finite part
      break;
    }
    if (total > cap && k + 1 < scene.steps) {
      run.note = "time cap: simulated " + fmt(static_cast<double>(k + 1) * scene.dt) + " of " +
                 fmt(static_cast<double>(scene.steps) * scene.dt) + " s";
      break;
    }
  }
  if (const std::string note = engine->note(); !note.empty())
    run.note += (run.note.empty() ? "" : "; ") + note;
  run.steps = ms.size();
  run.tSim = static_cast<double>(samples.size() - 1) * scene.dt;
  const std::size_t warm = std::min<std::size_t>(20, scene.steps / 10);
  std::vector<double> timed(ms.begin() + static_cast<long>(std::min(warm, ms.size() - 1)),
                            ms.end());
  std::nth_element(timed.begin(), timed.begin() + static_cast<long>(timed.size() / 2), timed.end());
  run.msPerStep = timed[timed.size() / 2];
  run.metrics = sceneMetrics(scene, samples);
  return run;
}

double metric(const Run& run, const std::string& name) {
  for (const Metric& m : run.metrics)
    if (m.name == name) return m.value;
  return std::numeric_limits<double>::quiet_NaN();
}

void writeCsv(std::ostream& out, const std::vector<Run>& runs) {
  out << "engine,scene,dt,t_sim,steps,ms_per_step";
  for (int i = 1; i <= 7; ++i) out << ",m" << i << "_name,m" << i;
  out << ",note\n";
  for (const Run& r : runs) {
    out << r.engine << ',' << r.scene << ',' << r.dt << ',' << r.tSim << ',' << r.steps << ','
        << r.msPerStep;
    for (std::size_t i = 0; i < 7; ++i)
      if (i < r.metrics.size())
        out << ',' << r.metrics[i].name << ',' << r.metrics[i].value;
      else
        out << ",,";
    out << ',' << r.note << '\n';
  }
}

// Per scene: ms/step with its ratio to the fastest peer (Bullet/ODE) and the key metrics.
void writeMarkdown(std::ostream& out, const std::vector<Run>& runs,
                   const std::vector<std::string>& labels) {
  out << "| scene | quantity |";
  for (const auto& l : labels) out << ' ' << l << " |";
  out << "\n|---|---|";
  for (std::size_t i = 0; i < labels.size(); ++i) out << "---|";
  out << '\n';
  std::vector<std::string> scenes;
  for (const Run& r : runs)
    if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end()) scenes.push_back(r.scene);
  for (const std::string& scene : scenes) {
    const auto find = [&](const std::string& label) -> const Run* {
      for (const Run& r : runs)
        if (r.scene == scene && r.engine == label) return &r;
      return nullptr;
    };
    double fastest = std::numeric_limits<double>::infinity();
    for (const auto& l : labels)
      if (const Run* r = find(l); r && l.rfind("coulomb", 0) != 0 && std::isfinite(r->msPerStep))
        fastest = std::min(fastest, r->msPerStep);
    out << "| " << scene << " | ms/step (x fastest peer) |";
    for (const auto& l : labels) {
      const Run* r = find(l);
      const bool timed = r && std::isfinite(r->msPerStep);
      out << ' ' << (timed ? fmt(r->msPerStep) + " (" + fmt(r->msPerStep / fastest) + "x)" : "-")
          << " |";
    }
    out << '\n';
    for (const std::string& name : keyMetrics(scene)) {
      out << "| | " << name << " |";
      for (const auto& l : labels)
        out << ' ' << (find(l) ? fmt(metric(*find(l), name)) : "") << " |";
      out << '\n';
    }
    bool anyNote = false;
    for (const auto& l : labels) anyNote = anyNote || (find(l) && !find(l)->note.empty());
    if (!anyNote) continue;
    out << "| | note |";
    for (const auto& l : labels) out << ' ' << (find(l) ? find(l)->note : "") << " |";
    out << '\n';
  }
}

int usage() {
  std::fprintf(stderr,
               "usage: PeerComparison [--scenes a,b] [--engines coulomb,bullet,ode_quickstep,"
               "ode_step] [--time-cap S] [--csv FILE] [--markdown FILE]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> scenes = {"box_stack_20",
                                     "pyramid_10",
                                     "pyramid_20",
                                     "box_incline_A_stick",
                                     "box_incline_B_slide",
                                     "box_incline_C_flat_22_5deg",
                                     "mass_ratio_1000kg_on_1kg",
                                     "chain_50",
                                     "newton_cradle"};
  std::vector<std::string> names = {"coulomb", "bullet", "ode_quickstep"};
  double cap = 10.0;
  std::string csvPath, markdownPath;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) return usage();
    const std::string value = argv[++i];
    if (arg == "--scenes") {
      scenes = coulomb::samples::splitCommaList(value);
    } else if (arg == "--engines") {
      names = coulomb::samples::splitCommaList(value);
    } else if (arg == "--time-cap") {
      cap = std::strtod(value.c_str(), nullptr);
      if (!(cap > 0)) return usage();
    } else if (arg == "--csv") {
      csvPath = value;
    } else if (arg == "--markdown") {
      markdownPath = value;
    } else {
      return usage();
    }
  }
  std::vector<std::string> labels;
  for (const std::string& n : names) {
    if (!engines().count(n)) {
      std::fprintf(stderr, "--engines: unknown engine '%s'\n", n.c_str());
      return usage();
    }
    labels.push_back(engines().at(n).first);
  }
  std::vector<Run> runs;
  std::set<std::string> skipped;  // "engine/scene family"
  for (const std::string& name : scenes) {
    try {
      const PeerScene scene = loadPeerScene(name);
      // docs/benchmarks.md "Peers in the same run": a run reaching < 10 % of its duration skips the
      // larger sizes of that scene family (pyramid_10 -> pyramid_20) for that engine.
      const std::string family = name.substr(0, name.find_last_of('_'));
      for (const std::string& n : names) {
        const auto& [label, make] = engines().at(n);
        if (skipped.count(label + "/" + family)) {
          Run skip;
          skip.engine = label;
          skip.scene = name;
          skip.dt = scene.dt;
          skip.msPerStep = std::numeric_limits<double>::quiet_NaN();
          skip.note = "skipped (cheaper run capped)";
          runs.push_back(skip);
          continue;
        }
        std::fprintf(stderr, "%s / %s ...\n", name.c_str(), label.c_str());
        runs.push_back(runOne(label, make, scene, cap));
        if (runs.back().tSim < 0.1 * static_cast<double>(scene.steps) * scene.dt)
          skipped.insert(label + "/" + family);
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
      return 1;
    }
  }
  writeCsv(std::cout, runs);
  if (!csvPath.empty()) {
    std::ofstream file(csvPath);
    writeCsv(file, runs);
  }
  std::ostringstream table;
  writeMarkdown(table, runs, labels);
  std::cout << '\n' << table.str();
  if (!markdownPath.empty()) std::ofstream(markdownPath) << table.str();
  return 0;
}
