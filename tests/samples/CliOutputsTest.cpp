// The `coulomb` CLI end to end: `run` with --solver/--stats/--contacts/--capture writes files with
// the documented columns and sane numbers, `compare` prints one row per solver, captured problems
// replay with `coulomb solve`, and bad solver names or files give a message naming them and a
// non-zero exit status. The scenes are written by the test (a 1 kg box resting on a plane).
#include <coulomb/solvers/io/Fc3dText.hpp>

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct CommandResult {
  int status = -1;
  std::string output;  // stdout and stderr
};

CommandResult runCoulomb(const std::string& arguments) {
  const std::string command =
      std::string(COULOMB_BINARY_DIR) + "/bin/coulomb " + arguments + " 2>&1";
  CommandResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr)
    result.output += buffer.data();
  const int raw = pclose(pipe);
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return result;
}

std::string boxOnPlaneScene(double friction) {
  std::ostringstream s;
  s << R"({"name": "cli_box", "time_step": 0.01, "steps": 100,
  "materials": {"m": {"friction": )"
    << friction << R"(, "restitution": 0.0}},
  "bodies": [
    {"name": "ground", "type": "static", "shapes": [{"type": "plane", "material": "m"}]},
    {"name": "box", "position": [0.0, 0.0, 0.1], "mass": 1.0,
     "inertia": [0.0066666666666666671, 0.0066666666666666671, 0.0066666666666666671],
     "shapes": [{"type": "box", "half_extents": [0.1, 0.1, 0.1], "material": "m"}]}]})";
  return s.str();
}

class CliOutputs : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(COULOMB_BINARY_DIR) / "tests" / "cli_outputs" / info->name();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string writeScene(double friction) {
    const fs::path path = dir_ / "box.json";
    std::ofstream(path) << boxOnPlaneScene(friction);
    return path.string();
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) fields.push_back(field);
  return fields;
}

TEST_F(CliOutputs, RunWritesContactsAndStatsWithExpectedColumnsAndSaneNumbers) {
  const std::string scene = writeScene(0.5);
  const CommandResult r = runCoulomb("run " + scene + " --solver pgs --steps 100 --stats " +
                                     path("stats.json") + " --contacts " + path("contacts.csv"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("solver pgs"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("iter_mean"), std::string::npos) << r.output;  // per-solver summary

  std::ifstream contacts(path("contacts.csv"));
  std::string line;
  ASSERT_TRUE(std::getline(contacts, line));
  EXPECT_EQ(line,
            "step,time,body_a,name_a,body_b,name_b,x,y,z,nx,ny,nz,depth,normal_impulse,"
            "tangent_impulse_1,tangent_impulse_2");
  std::vector<double> impulsePerStep(100, 0.0);
  int rows = 0;
  while (std::getline(contacts, line)) {
    const std::vector<std::string> f = splitCsv(line);
    ASSERT_EQ(f.size(), 16u) << line;
    ++rows;
    const int step = std::stoi(f[0]);
    ASSERT_GE(step, 0);
    ASSERT_LT(step, 100);
    EXPECT_TRUE((f[3] == "ground" && f[5] == "box") || (f[3] == "box" && f[5] == "ground")) << line;
    const double nz = std::stod(f[11]);
    EXPECT_NEAR(std::abs(nz), 1.0, 1e-9) << line;
    EXPECT_NEAR(std::stod(f[8]), 0.0, 1e-3) << line;  // on the ground plane
    EXPECT_LT(std::abs(std::stod(f[12])), 1e-2) << line;
    impulsePerStep[static_cast<std::size_t>(step)] += std::stod(f[13]);
  }
  EXPECT_EQ(rows, 4 * 100);  // 4 corners every step
  // The resting box's weight, m g h = 1 * 9.81 * 0.01 N s, carried at the last step.
  EXPECT_NEAR(impulsePerStep.back(), 0.0981, 0.0981 * 0.01);

  std::ifstream statsFile(path("stats.json"));
  const nlohmann::json stats = nlohmann::json::parse(statsFile);
  ASSERT_EQ(stats.at("per_step").size(), 100u);
  for (const auto& step : stats.at("per_step")) {
    ASSERT_EQ(step.at("islands").size(), 1u);
    const auto& island = step.at("islands")[0];
    EXPECT_EQ(island.at("contacts"), 4);
    EXPECT_FALSE(island.at("solver").get<std::string>().empty());
    EXPECT_TRUE(island.at("residual").is_number());
  }
  ASSERT_TRUE(stats.at("solvers").contains("pgs")) << stats.at("solvers").dump();
  const auto& pgs = stats.at("solvers").at("pgs");
  EXPECT_GT(pgs.at("islands").get<int>(), 0);
  EXPECT_LE(pgs.at("residual_max").get<double>(), 1e-6);
  EXPECT_GE(pgs.at("iterations_max").get<int>(), 1);
  EXPECT_GT(stats.at("ms_per_step_median").get<double>(), 0.0);
  EXPECT_LT(stats.at("max_drift").get<double>(), 1e-6);
  EXPECT_EQ(stats.at("steps"), 100);
  EXPECT_EQ(stats.at("solver"), "pgs");
}

// The stats say which start a solve kept: a fresh pyramid's first step is solved at its sticking
// start (docs/solvers.md), the next one from its warm start.
TEST_F(CliOutputs, StatsNameTheStickingStart) {
  const CommandResult r = runCoulomb("run pyramid_10 --steps 2 --stats " + path("stats.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream statsFile(path("stats.json"));
  const nlohmann::json stats = nlohmann::json::parse(statsFile);
  auto largestFirstAttempt = [&](int step) {
    const nlohmann::json* largest = nullptr;
    for (const auto& island : stats.at("per_step").at(step).at("islands"))
      if (!largest || island.at("unknowns") > largest->at("unknowns")) largest = &island;
    return largest->at("attempts").at(0);
  };
  const nlohmann::json first = largestFirstAttempt(0);
  EXPECT_EQ(first.at("iterations"), 0);
  EXPECT_NE(first.value("note", std::string()).find("sticking start"), std::string::npos);
  EXPECT_EQ(largestFirstAttempt(1).value("note", std::string()).find("sticking start"),
            std::string::npos);
}

TEST_F(CliOutputs, ComparePrintsOneRowPerSolver) {
  const std::string scene = writeScene(0.5);
  const CommandResult r =
      runCoulomb("compare " + scene + " --solvers pgs,bgs,ac_newton --steps 20");
  ASSERT_EQ(r.status, 0) << r.output;
  int pgs = 0, bgs = 0, newton = 0;
  std::istringstream lines(r.output);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind("pgs ", 0) == 0) ++pgs;
    if (line.rfind("bgs ", 0) == 0) ++bgs;
    if (line.rfind("ac_newton ", 0) == 0) ++newton;
  }
  EXPECT_EQ(pgs, 1) << r.output;
  EXPECT_EQ(bgs, 1) << r.output;
  EXPECT_EQ(newton, 1) << r.output;
  EXPECT_NE(r.output.find("ms/step"), std::string::npos) << r.output;
}

TEST_F(CliOutputs, JointDriftIsReportedByRunStatsAndCompare) {
  // The built-in pendulum (a ball joint, predicted-state correction): the stats give every step's
  // joint gap and the run's largest, `compare` a joint_gap_m column. A gap above 1e-6 m would be
  // a correction failure; a gap of exactly 0 would mean the figure is not measured at all.
  const CommandResult run = runCoulomb("run pendulum --steps 50 --stats " + path("stats.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("joints: max gap"), std::string::npos) << run.output;
  std::ifstream statsFile(path("stats.json"));
  const nlohmann::json stats = nlohmann::json::parse(statsFile);
  ASSERT_EQ(stats.at("per_step").size(), 50u);
  for (const auto& step : stats.at("per_step")) {
    const auto& joints = step.at("joints");
    EXPECT_EQ(joints.at("count").get<int>(), 1);
    EXPECT_LT(joints.at("max_linear_error").get<double>(), 1e-6) << joints.dump();
    EXPECT_TRUE(joints.at("correction_converged").get<bool>()) << joints.dump();
    EXPECT_LE(joints.at("energy_projections").get<int>(), 1) << joints.dump();  // one island
  }
  // The swinging pendulum's island is projected back to its energy on most steps (default).
  int projected = 0;
  for (const auto& step : stats.at("per_step"))
    projected += step.at("joints").at("energy_projections").get<int>();
  EXPECT_GT(projected, 25);
  const double runGap = stats.at("joints").at("max_linear_error").get<double>();
  EXPECT_GT(runGap, 0.0);
  EXPECT_LT(runGap, 1e-6);
  EXPECT_EQ(stats.at("joints").at("correction_failures").get<int>(), 0);

  const CommandResult compare = runCoulomb("compare pendulum --solvers ac_newton --steps 20");
  ASSERT_EQ(compare.status, 0) << compare.output;
  EXPECT_NE(compare.output.find("joint_gap_m"), std::string::npos) << compare.output;
}

TEST_F(CliOutputs, ConformanceRunsACaseOncePerSolverAndWritesTheTable) {
  // sphere_slide (docs/scene-specifications.md A1) with auto and pgs alone: one row each, both
  // pass, and the Markdown table has a header and the two rows. An unknown case is named with the
  // known ones.
  const CommandResult r = runCoulomb(
      "conformance --cases sphere_slide --solvers auto,pgs! "
      "--markdown " +
      path("table.md"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("sphere_slide  auto  pass"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("sphere_slide  pgs!  pass"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("2 of 2 runs pass"), std::string::npos) << r.output;
  std::ifstream table(path("table.md"));
  std::string line;
  int rows = 0;
  while (std::getline(table, line))
    if (line.rfind("| sphere_slide |", 0) == 0) ++rows;
  EXPECT_EQ(rows, 2);

  const CommandResult list = runCoulomb("conformance --list");
  ASSERT_EQ(list.status, 0) << list.output;
  EXPECT_NE(list.output.find("box_incline/C_flat_22.5deg"), std::string::npos) << list.output;

  const CommandResult bad = runCoulomb("conformance --cases sphere_slid");
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.output.find("no conformance case 'sphere_slid'"), std::string::npos) << bad.output;
}

TEST_F(CliOutputs, SnapshotContinuationPrintsTheUninterruptedStateHash) {
  // 30 steps, save; load and run 30 more: the state hash equals that of 60 steps in one run.
  const auto hashOf = [](const std::string& output) {
    const std::size_t at = output.find("state hash ");
    return at == std::string::npos ? std::string() : output.substr(at + 11, 16);
  };
  const std::string snapshot = path("stack.snap");
  const CommandResult first = runCoulomb("run box_stack_10 --steps 30 --save-snapshot " + snapshot);
  ASSERT_EQ(first.status, 0) << first.output;
  const CommandResult resumed =
      runCoulomb("run box_stack_10 --steps 30 --load-snapshot " + snapshot);
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  const CommandResult whole = runCoulomb("run box_stack_10 --steps 60");
  ASSERT_EQ(whole.status, 0) << whole.output;
  ASSERT_FALSE(hashOf(whole.output).empty()) << whole.output;
  EXPECT_EQ(hashOf(resumed.output), hashOf(whole.output)) << resumed.output;
  EXPECT_NE(hashOf(first.output), hashOf(whole.output));

  // A solver given with the snapshot runs the continuation (the snapshot's own was auto).
  const std::string stats = path("continued.json");
  const CommandResult pgs = runCoulomb("run box_stack_10 --steps 3 --solver pgs! --stats " + stats +
                                       " --load-snapshot " + snapshot);
  ASSERT_EQ(pgs.status, 0) << pgs.output;
  std::ifstream statsFile(stats);
  const nlohmann::json summary = nlohmann::json::parse(statsFile);
  ASSERT_EQ(summary.at("per_step").size(), 3u);
  for (const auto& step : summary.at("per_step"))
    for (const auto& island : step.at("islands")) EXPECT_EQ(island.at("solver"), "pgs") << island;

  const CommandResult wrongScene =
      runCoulomb("run pyramid_10 --steps 1 --load-snapshot " + snapshot);
  EXPECT_NE(wrongScene.status, 0);
  EXPECT_NE(wrongScene.output.find(snapshot), std::string::npos) << wrongScene.output;
}

TEST_F(CliOutputs, BadSolverNameIsNamedWithNonZeroExit) {
  const std::string scene = writeScene(0.5);
  const CommandResult run = runCoulomb("run " + scene + " --solver no_such_solver --steps 2");
  EXPECT_NE(run.status, 0);
  EXPECT_NE(run.output.find("no_such_solver"), std::string::npos) << run.output;
  const CommandResult compare =
      runCoulomb("compare " + scene + " --solvers pgs,no_such_solver --steps 2");
  EXPECT_NE(compare.status, 0);
  EXPECT_NE(compare.output.find("no_such_solver"), std::string::npos) << compare.output;
}

TEST_F(CliOutputs, BadFilesAreNamedWithNonZeroExit) {
  const CommandResult missing = runCoulomb("run " + path("missing.json") + " --steps 2");
  EXPECT_NE(missing.status, 0);
  EXPECT_NE(missing.output.find("missing.json"), std::string::npos) << missing.output;
  std::ofstream(path("broken.json")) << "{\"bodies\": [";
  const CommandResult broken = runCoulomb("compare " + path("broken.json") + " --steps 2");
  EXPECT_NE(broken.status, 0);
  EXPECT_NE(broken.output.find("broken.json"), std::string::npos) << broken.output;
  const std::string scene = writeScene(0.5);
  const CommandResult unwritable =
      runCoulomb("run " + scene + " --steps 2 --contacts " + path("no/such/dir/c.csv"));
  EXPECT_NE(unwritable.status, 0);
  EXPECT_NE(unwritable.output.find("c.csv"), std::string::npos) << unwritable.output;
}

void expectCaptureReplays(const std::string& scene, const fs::path& dir, double mu) {
  const fs::path captureDir = dir / "capture";
  const CommandResult r = runCoulomb("run " + scene + " --steps 5 --capture " +
                                     captureDir.string() + " --capture-step 3");
  ASSERT_EQ(r.status, 0) << r.output;
  const fs::path file = captureDir / "cli_box_step3_island0.fc3d";
  ASSERT_TRUE(fs::exists(file)) << r.output;
  // The problem, and beside it the warm start its solve began from (a resting box's last
  // impulses; none for frictionless contacts, whose padded rows have no start of their size).
  const fs::path start = captureDir / "cli_box_step3_island0.start";
  EXPECT_EQ(fs::exists(start), mu > 0.0);
  EXPECT_EQ(std::distance(fs::directory_iterator(captureDir), fs::directory_iterator{}),
            mu > 0.0 ? 2 : 1);
  const coulomb::solvers::Fc3dReadResult read = coulomb::solvers::readFc3dText(file.string());
  ASSERT_TRUE(read.problem) << read.error;
  EXPECT_EQ(read.problem->contactCount(), 4);
  for (const auto& block : read.problem->blocks) EXPECT_EQ(block.mu, mu);
  const CommandResult solve = runCoulomb("solve " + file.string() + " --solver bgs");
  ASSERT_EQ(solve.status, 0) << solve.output;
  EXPECT_NE(solve.output.find("\"status\":\"converged\""), std::string::npos) << solve.output;
  if (mu == 0.0) return;
  // Replayed from its warm start with the history of every sweep: the box rests, so the last
  // step's impulses are nearly the answer and bgs needs fewer sweeps than from r = 0.
  const CommandResult cold = runCoulomb("solve " + file.string() + " --solver bgs --history");
  const CommandResult warm =
      runCoulomb("solve " + file.string() + " --solver bgs --history --start " + start.string());
  ASSERT_EQ(warm.status, 0) << warm.output;
  const nlohmann::json coldLine =
      nlohmann::json::parse(cold.output.substr(0, cold.output.find('\n')));
  const nlohmann::json warmLine =
      nlohmann::json::parse(warm.output.substr(0, warm.output.find('\n')));
  EXPECT_EQ(warmLine.at("status"), "converged") << warm.output;
  EXPECT_LT(warmLine.at("iterations").get<int>(), coldLine.at("iterations").get<int>());
  EXPECT_EQ(coldLine.at("history").size(), coldLine.at("iterations").get<std::size_t>());
  // A start of the wrong size is an error naming the file.
  const fs::path shortStart = dir / "short.start";
  std::ofstream(shortStart) << "1 2 3\n";
  const CommandResult bad =
      runCoulomb("solve " + file.string() + " --solver bgs --start " + shortStart.string());
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.output.find("short.start: 3 numbers, expected 12"), std::string::npos)
      << bad.output;
}

// `coulomb solve` says what a solver did, as `run --stats` does for every attempt: a landing
// column of box_pile_1000 takes ac_newton through returns to its watchdog point (fixture:
// tests/data/problems/ORIGIN.md).
TEST_F(CliOutputs, SolveReportsWhatTheSolverDid) {
  const fs::path file =
      fs::path(COULOMB_TEST_DATA_DIR) / "problems" / "box_pile_1000_step60_island92.fc3d";
  const CommandResult r = runCoulomb("solve " + file.string() + " --solver ac_newton!");
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json line = nlohmann::json::parse(r.output.substr(0, r.output.find('\n')));
  EXPECT_EQ(line.at("status"), "converged") << r.output;
  EXPECT_NE(line.value("note", std::string()).find("returns to the watchdog point"),
            std::string::npos)
      << r.output;
}

TEST_F(CliOutputs, CaptureWritesFc3dThatSolveReadsBack) {
  expectCaptureReplays(writeScene(0.5), dir_, 0.5);
}

TEST_F(CliOutputs, FrictionlessIslandsAreCapturedAsMuZeroContacts) {
  expectCaptureReplays(writeScene(0.0), dir_, 0.0);
}

}  // namespace
