// docs/scene-specifications.md B11 double_loop: the run (progress, rolling share, Newton iterations
// per step) and its four conformance cases, one per friction coefficient.
#include "LoopCases.hpp"

#include "DoubleLoopTrack.hpp"
#include "scenes/SceneRegistry.hpp"

#include <coulomb/solvers/newton/AcNewtonSolver.hpp>
#include <coulomb/solvers/newton/NewtonFunction.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

namespace coulomb::conformance {
namespace {

constexpr double kFacTarget = 1e-20;  // ||f_AC||^2, AC11 section 5.1.5
constexpr int kNewtonCap = 50;
constexpr double kStickSpeed =
    1e-6;  // [m/s] |u_T| of a sticking contact (docs/scene-specifications.md B11)
constexpr double kLoop2End =
    13.101;  // [m] arc length of the end of loop 2 (docs/scene-specifications.md B11)

/// ||f_AC(r)||^2 = ||Phi||^2 of docs/solver-derivations.md (5.1), radius (5.2a), rho =
/// 1/lambda_max(sym W_cc).
double fAcSquared(const solvers::ContactProblem& problem, const Eigen::VectorXd& r,
                  const Eigen::VectorXd& u) {
  const solvers::AlartCurnierFunction function;
  const std::vector<int> offsets = problem.blockOffsets();
  double sum = 0.0;
  for (std::size_t b = 0; b < problem.blocks.size(); ++b) {
    const solvers::ConstraintBlock& block = problem.blocks[b];
    const int o = offsets[b];
    if (!block.isContact()) continue;  // the double loop has contacts only
    Eigen::Matrix3d W;
    for (int j = 0; j < 3; ++j) W.col(j) = problem.W.column(o + j).segment<3>(o);
    const Eigen::Matrix3d S = (W + W.transpose()) / 2;
    const double rho =
        1.0 / Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S).eigenvalues().maxCoeff();
    Eigen::Vector3d phi;
    Eigen::Matrix3d A, B;
    function.contact(r.segment<3>(o), u.segment<3>(o), block.mu, rho, rho, phi, A, B);
    sum += phi.squaredNorm();
  }
  return sum;
}

/// Newton iterations of ac_newton from the problem's warm start until ||f_AC||^2 < 1e-20
/// (kNewtonCap + 1 if not reached), and the ||f_AC||^2 of that iterate.
std::pair<int, double> newtonIterations(const solvers::ContactProblem& problem) {
  const solvers::AcNewtonSolver solver;
  solvers::SolverOptions options;
  options.tolerance = 1e-300;  // run exactly maxIterations (or until the solver stalls)
  double last = 0.0;
  for (int k = 1; k <= kNewtonCap; ++k) {
    options.maxIterations = k;
    const solvers::SolveOutcome outcome = solver.solve(problem, options);
    last = fAcSquared(problem, outcome.impulses, outcome.velocities);
    if (last < kFacTarget) return {k, last};
    if (outcome.report.iterations < k) break;  // stalled: more iterations will not help
  }
  return {kNewtonCap + 1, last};
}

}  // namespace

void setSceneFriction(engine::io::Scene& scene, double mu) {
  for (engine::BodyDesc& body : scene.bodies)
    for (engine::ShapeDesc& shape : body.shapes) shape.material.friction = mu;
}

DoubleLoopRun runDoubleLoop(double mu, const CaseOptions& options, std::size_t steps) {
  engine::io::Scene scene = scenes::loadBuiltinScene("double_loop");
  setSceneFriction(scene, mu);
  scene.settings.solve.choice = coulomb::solvers::solverChoice(options.solver);
  engine::World world = engine::io::buildWorld(scene);
  const geometry::BodyId ball = world.findBody("ball");
  std::optional<solvers::ContactProblem> captured;
  world.setProblemObserver(
      [&](std::int32_t, const solvers::ContactProblem& problem) { captured = problem; });

  const DoubleLoopTrack track;
  TrackProgress progress(track);
  DoubleLoopRun result;
  result.mu = mu;
  result.keepContactSpeed = DoubleLoopTrack::keepContactSpeed(-world.settings().gravity.z());
  RunRecorder recorder;
  const std::size_t n = scaledSteps(steps == 0 ? scene.steps : steps, options);
  std::size_t rolling = 0, newtonSum = 0, newtonSolves = 0;
  Eigen::Vector3d previous = world.pose(ball).position;
  for (std::size_t k = 1; k <= n; ++k) {
    captured.reset();
    recorder.step(world);
    const Eigen::Vector3d p = world.pose(ball).position;
    const Eigen::Vector3d v = world.linearVelocity(ball), w = world.angularVelocity(ball);
    if (!p.allFinite() || !v.allFinite() || !w.allFinite()) {
      result.finite = false;
      break;
    }
    result.pathLength += (p - previous).norm();
    progress.update(p, v.norm());
    if (!progress.onRails() && result.tLeft < 0.0)
      result.tLeft = static_cast<double>(k) * world.settings().timeStep;
    // Stick or slip of every contact that carried an impulse, with the step's (start-of-step)
    // contact geometry and the new velocity: the u_T the solver saw.
    bool any = false, allStick = true;
    for (const geometry::ContactManifold& m : world.contacts())
      for (const geometry::ContactPoint& point : m.activePoints()) {
        if (point.normalImpulse <= 0.0) continue;
        any = true;
        const Eigen::Vector3d u = v + w.cross(point.position - previous);
        allStick = allStick && (u - u.dot(m.normal) * m.normal).norm() <= kStickSpeed;
      }
    if (any) {
      ++result.contactSteps;
      if (allStick) ++rolling;
    }
    if (captured && captured->contactCount() > 0) {
      const auto [iterations, fAc] = newtonIterations(*captured);
      newtonSum += static_cast<std::size_t>(iterations);
      ++newtonSolves;
      result.newtonMax = std::max(result.newtonMax, iterations);
      if (iterations > kNewtonCap)
        ++result.newtonUnreached;
      else
        result.fAcSquaredMax = std::max(result.fAcSquaredMax, fAc);
    }
    previous = p;
  }
  recorder.finish(result.run);
  result.sMax = progress.sMax();
  result.sFinal = progress.s();
  result.loopsDone = progress.loopsDone();
  result.topSpeeds = progress.topSpeeds();
  result.leftRails = progress.everLeft();
  if (result.contactSteps > 0) {
    result.rollingShare = static_cast<double>(rolling) / static_cast<double>(result.contactSteps);
    result.slidingShare = 1.0 - result.rollingShare;
  }
  if (newtonSolves > 0)
    result.newtonMean = static_cast<double>(newtonSum) / static_cast<double>(newtonSolves);
  return result;
}

std::string describe(const DoubleLoopRun& r) {
  char text[512];
  std::snprintf(text, sizeof text,
                "mu %g: s_max %.3f m, s_end %.3f m, loops %d, %s, path %.3f m, rolling %.0f %% "
                "sliding %.0f %% of %zu contact steps, ac_newton %.2f its/step (max %d, %zu "
                "unreached) to ||f_AC||^2 < 1e-20 (max %.1e)",
                r.mu, r.sMax, r.sFinal, r.loopsDone,
                r.leftRails
                    ? ("left the rails at t=" + std::to_string(r.tLeft).substr(0, 4) + " s").c_str()
                    : "stayed on the rails",
                r.pathLength, 100.0 * r.rollingShare, 100.0 * r.slidingShare, r.contactSteps,
                r.newtonMean, r.newtonMax, r.newtonUnreached, r.fAcSquaredMax);
  std::string line = text;
  if (!r.topSpeeds.empty()) {
    line += "; over the loop tops at";
    for (const double v : r.topSpeeds) line.append(" ").append(std::to_string(v).substr(0, 5));
    line.append(" m/s (the rails push above ")
        .append(std::to_string(r.keepContactSpeed).substr(0, 5))
        .append(" m/s)");
  }
  return line;
}

void addLoopCases(std::vector<ConformanceCase>& cases) {
  // docs/scene-specifications.md B11 pass: ac_newton < 5 iterations per step, no NaN; mu 1.0
  // completes both loops (passes both tops and reaches the end of loop 2 on the rails: a ball that
  // passes the top of loop 2 in free fall has not completed it), the others pass no loop top
  // (reduced model: 0.1 and 0.3 stay in the first valley, 0.6 leaves the rails before the top of
  // loop 1). s_max rising with mu is checked across the cases by
  // tests/conformance/DoubleLoopTest.cpp.
  for (const double mu : {0.1, 0.3, 0.6, 1.0}) {
    char name[32];
    std::snprintf(name, sizeof name, "double_loop/mu=%.1f", mu);
    const bool completes = mu >= 1.0;
    const std::string criterion =
        std::string("no NaN, ac_newton < 5 iterations per step to ||f_AC||^2 < 1e-20, ") +
        (completes ? "completes both loops (s_max >= 13.101 m)" : "passes no loop top");
    cases.push_back({name, "double_loop", "B11", "s_max [m]", criterion,
                     [mu, completes](const CaseOptions& options) {
                       const DoubleLoopRun r = runDoubleLoop(mu, options);
                       CaseRun run = r.run;
                       run.metric = r.sMax;
                       run.detail = describe(r);
                       const bool loops =
                           completes ? r.loopsDone == 2 && r.sMax >= kLoop2End : r.loopsDone == 0;
                       // docs/scene-specifications.md asks for the mean (< 5), not for every step:
                       // a step where ac_newton stalls counts as kNewtonCap + 1 in the mean and is
                       // reported as unreached (docs/conformance.md, double loop).
                       run.passed = r.finite && r.newtonMean < 5.0 && loops;
                       return run;
                     }});
  }
}

}  // namespace coulomb::conformance
