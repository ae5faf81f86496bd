#include "SceneRegistry.hpp"

#include <coulomb/engine/CoulombError.hpp>

#include <algorithm>
#include <filesystem>

namespace coulomb::scenes {
namespace {

std::size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace

engine::io::Scene loadBuiltinScene(std::string_view name) {
  const auto scenes = builtinScenes();
  const auto found = std::find_if(scenes.begin(), scenes.end(),
                                  [&](const BuiltinScene& s) { return s.name == name; });
  if (found != scenes.end()) {
    std::string source = "built-in scene '";
    source.append(name).append("'");
    // Paths in built-in scenes (URDF robots in samples/robots) resolve against the source tree's
    // samples/scenes, then COULOMB_ROBOT_PATH (docs/urdf.md, "In a scene").
    return engine::io::parseScene(found->json, source, COULOMB_BUILTIN_SCENE_DIR);
  }
  // Built with append: GCC 12 gives a false -Wrestrict on chained string_view concatenation.
  std::string message = "no built-in scene '";
  message.append(name).append("'");
  const auto nearest = std::min_element(scenes.begin(), scenes.end(), [&](auto& a, auto& b) {
    return editDistance(name, a.name) < editDistance(name, b.name);
  });
  if (nearest != scenes.end() && editDistance(name, nearest->name) <= 3)
    message.append("; did you mean '").append(nearest->name).append("'?");
  message.append(" (built-in:");
  for (const auto& scene : scenes) message.append(" ").append(scene.name);
  message.append("; or give a path to a .json scene file)");
  throw engine::CoulombError(message);
}

engine::io::Scene resolveScene(const std::string& nameOrPath) {
  const bool looksLikePath = nameOrPath.find('/') != std::string::npos ||
                             nameOrPath.ends_with(".json") || std::filesystem::exists(nameOrPath);
  if (looksLikePath) return engine::io::loadSceneFile(nameOrPath);
  return loadBuiltinScene(nameOrPath);
}

}  // namespace coulomb::scenes
