#pragma once
// Scenes as Python gives them (a built-in name, a JSON or URDF file path, or a dict in the JSON
// scene format) with the CLI's overrides, for coulomb.run, run_batch and World.
#include <coulomb/io/SceneLoader.hpp>

#include <pybind11/pybind11.h>

#include <cstdint>
#include <optional>
#include <string>

#include "scenes/SceneOverrides.hpp"

namespace coulomb::python {

/// A Python object (dicts, lists, numbers, strings) as JSON text, for the engine's JSON readers.
std::string jsonText(const pybind11::handle& object);

/// A shape in the JSON scene format (docs/scene-format.md "Shape": type, keys, position,
/// orientation, inline material, filter, sensor), parsed as the one shape of a static body so
/// that every check of the scene loader applies; `what` names it in errors.
engine::ShapeDesc shapeDescFrom(const pybind11::dict& shape, const std::string& what);

/// As `coulomb run` prints a state hash: 16 hex digits.
std::string hashText(std::uint64_t hash);

scenes::SceneOverrides overridesFrom(std::optional<std::uint64_t> steps, std::optional<double> dt,
                                     std::optional<std::string> solver, std::optional<double> tol,
                                     std::optional<int> maxIterations, std::optional<double> mu,
                                     std::optional<std::string> jointEnergy);

/// The scene with the overrides applied. Needs the GIL; throws CoulombError (bad scene) or
/// ValueError (not a name, path or dict).
engine::io::Scene sceneFrom(const pybind11::handle& scene, const scenes::SceneOverrides& overrides);

}  // namespace coulomb::python
