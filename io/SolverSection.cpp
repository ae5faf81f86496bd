#include <coulomb/io/SolverSection.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>

#include <algorithm>
#include <optional>

namespace coulomb::engine::io {
namespace {

double nonNegative(const JsonNode& node) {
  const double value = node.number();
  if (value < 0.0) node.fail("must be >= 0");
  return value;
}

PenetrationMethod parsePenetrationMethod(const JsonNode& node) {
  const std::string method = node.string();
  if (method == "split_impulse") return PenetrationMethod::SplitImpulse;
  if (method == "baumgarte") return PenetrationMethod::Baumgarte;
  if (method == "none") return PenetrationMethod::None;
  std::string message = "unknown penetration method '" + method + "'";
  if (auto s = nearestName(method, {"split_impulse", "baumgarte", "none"}))
    message += "; did you mean '" + *s + "'?";
  node.fail(message + " (split_impulse, baumgarte or none)");
}

ImpactLaw parseImpactLaw(const JsonNode& node) {
  const std::string law = node.string();
  if (law == "simultaneous") return ImpactLaw::Simultaneous;
  if (law == "propagating") return ImpactLaw::Propagating;
  std::string message = "unknown impact law '" + law + "'";
  if (auto s = nearestName(law, {"simultaneous", "propagating"}))
    message += "; did you mean '" + *s + "'?";
  node.fail(message + " (simultaneous or propagating)");
}

void parsePenetration(const JsonNode& node, PenetrationSettings& settings) {
  node.allowOnly({"method", "beta", "slop", "iterations", "solver", "tolerance"});
  if (node.has("method")) settings.method = parsePenetrationMethod(node.child("method"));
  if (node.has("beta")) {
    settings.beta = node.child("beta").number();
    if (settings.beta < 0.0 || settings.beta > 1.0) node.child("beta").fail("must be in [0, 1]");
  }
  if (node.has("slop")) settings.slop = nonNegative(node.child("slop"));
  if (node.has("iterations")) {
    const std::uint64_t sweeps = node.child("iterations").unsignedInteger();
    if (sweeps < 1 || sweeps > 100000) node.child("iterations").fail("must be in [1, 100000]");
    settings.iterations = static_cast<int>(sweeps);
  }
  if (node.has("solver")) {
    const std::string name = node.child("solver").string();
    const std::vector<std::string> known = solvers::SolverRegistry::builtIn().names();
    if (std::find(known.begin(), known.end(), name) == known.end())
      node.child("solver").fail("unknown solver '" + name + "' (see `coulomb solvers`)");
    settings.solver = name;
  }
  if (node.has("tolerance")) settings.tolerance = node.child("tolerance").positiveNumber();
}

}  // namespace

solvers::SolverChoice parseSolverRequest(const JsonNode& node) {
  const std::string request = node.string();
  std::string error;
  std::optional<solvers::SolverChoice> choice = solvers::parseSolverChoice(request, error);
  if (!choice) node.fail(error);
  const std::vector<std::string> known = solvers::SolverRegistry::builtIn().names();
  for (const solvers::SolveAttempt& attempt : choice->attempts) {
    if (std::find(known.begin(), known.end(), attempt.solver) != known.end()) continue;
    std::string message = "unknown solver '" + attempt.solver + "'";
    std::vector<std::string> candidates = known;
    candidates.emplace_back("auto");
    if (auto s = nearestName(attempt.solver, candidates)) message += "; did you mean '" + *s + "'?";
    node.fail(message + " (see `coulomb solvers`)");
  }
  return *choice;
}

void parseSolverSection(const JsonNode& node, WorldSettings& settings) {
  node.allowOnly({"name", "tolerance", "max_iterations", "time_limit", "warm_start",
                  "restitution_threshold", "speculative_contacts", "speculative_margin",
                  "speculative_sweep", "penetration", "impact_law", "touching_tolerance",
                  "max_impact_sweeps", "elastic_turning", "promote_fallbacks", "sweep_part_blocks",
                  "sticking_start", "start_sweep"});
  solvers::SolverOptions& options = settings.solve.options;
  if (node.has("name")) settings.solve.choice = parseSolverRequest(node.child("name"));
  if (node.has("tolerance")) options.tolerance = node.child("tolerance").positiveNumber();
  if (node.has("max_iterations")) {
    const std::uint64_t iterations = node.child("max_iterations").unsignedInteger();
    if (iterations > 100000000) node.child("max_iterations").fail("must be <= 1e8");
    options.maxIterations = static_cast<int>(iterations);
  }
  if (node.has("sweep_part_blocks")) {
    const std::uint64_t blocks = node.child("sweep_part_blocks").unsignedInteger();
    if (blocks > 100000000) node.child("sweep_part_blocks").fail("must be <= 1e8 (0 = never)");
    options.sweepPartBlocks = static_cast<int>(blocks);
  }
  if (node.has("time_limit")) options.timeLimitSeconds = node.child("time_limit").positiveNumber();
  if (node.has("warm_start")) options.useWarmStart = node.child("warm_start").boolean();
  if (node.has("sticking_start")) options.stickingStart = node.child("sticking_start").boolean();
  if (node.has("start_sweep")) options.startSweep = node.child("start_sweep").boolean();
  if (node.has("promote_fallbacks"))
    settings.solve.promotion.enabled = node.child("promote_fallbacks").boolean();
  ContactSettings& contact = settings.contact;
  if (node.has("restitution_threshold"))
    contact.restitutionThreshold = nonNegative(node.child("restitution_threshold"));
  if (node.has("speculative_contacts"))
    contact.speculativeContacts = node.child("speculative_contacts").boolean();
  if (node.has("speculative_margin"))
    settings.collision.speculativeMargin = nonNegative(node.child("speculative_margin"));
  if (node.has("speculative_sweep"))
    settings.collision.speculativeSweep = nonNegative(node.child("speculative_sweep"));
  if (node.has("elastic_turning")) contact.elasticTurning = node.child("elastic_turning").boolean();
  if (node.has("impact_law")) contact.impactLaw = parseImpactLaw(node.child("impact_law"));
  if (node.has("touching_tolerance"))
    contact.touchingTolerance = nonNegative(node.child("touching_tolerance"));
  if (node.has("max_impact_sweeps")) {
    const std::uint64_t sweeps = node.child("max_impact_sweeps").unsignedInteger();
    if (sweeps < 1 || sweeps > 100000)
      node.child("max_impact_sweeps").fail("must be in [1, 100000]");
    contact.maxImpactSweeps = static_cast<int>(sweeps);
  }
  if (node.has("penetration")) parsePenetration(node.child("penetration"), contact.penetration);
}

void parseSleepSection(const JsonNode& node, SleepSettings& sleep) {
  node.allowOnly({"enabled", "linear_speed", "angular_speed", "time"});
  if (node.has("enabled")) sleep.enabled = node.child("enabled").boolean();
  if (node.has("linear_speed")) sleep.linearSpeed = nonNegative(node.child("linear_speed"));
  if (node.has("angular_speed")) sleep.angularSpeed = nonNegative(node.child("angular_speed"));
  if (node.has("time")) sleep.timeToSleep = nonNegative(node.child("time"));
}

}  // namespace coulomb::engine::io
