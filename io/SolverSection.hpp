#pragma once
// The "solver" section of a JSON scene (docs/scene-format.md "Solver"): the world's contact solver
// and its common options, and the contact settings of the step (restitution threshold,
// speculative contacts, penetration correction). Internal to io (it reads JsonNode).
#include <coulomb/engine/WorldSettings.hpp>
#include <coulomb/io/JsonReader.hpp>

#include <string>

namespace coulomb::engine::io {

/// Reads `node` (an object) into `settings`; keys that are absent keep their defaults. Errors name
/// the JSON path, e.g. "scene.json: solver.penetration.beta: must be in [0, 1] (got 2)".
void parseSolverSection(const JsonNode& node, WorldSettings& settings);

/// Parses a solver request ("auto", a built-in solver name, "NAME!" or a chain "A,B,C") at
/// `node` into the typed choice, suggesting the nearest built-in name for a typo.
solvers::SolverChoice parseSolverRequest(const JsonNode& node);

/// The top-level "sleep" section: enabled, linear_speed [m/s], angular_speed [rad/s], time [s].
void parseSleepSection(const JsonNode& node, SleepSettings& sleep);

}  // namespace coulomb::engine::io
