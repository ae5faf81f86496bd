#pragma once
// The built-in scenes (samples/scenes/*.json, embedded into the binary at build time), shared by
// the CLI, the samples, the tests and the benchmarks.
#include <coulomb/io/SceneLoader.hpp>

#include <span>
#include <string>
#include <string_view>

namespace coulomb::scenes {

struct BuiltinScene {
  std::string_view name;  // file stem, e.g. "projectile"
  std::string_view json;  // the file's text
};

/// Every built-in scene, sorted by name.
std::span<const BuiltinScene> builtinScenes();

/// The built-in scene `name`, parsed. Throws CoulombError listing the known names (and the
/// nearest one) if there is none.
engine::io::Scene loadBuiltinScene(std::string_view name);

/// A built-in scene name, or else a path to a JSON scene file.
engine::io::Scene resolveScene(const std::string& nameOrPath);

}  // namespace coulomb::scenes
