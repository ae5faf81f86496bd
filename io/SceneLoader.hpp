#pragma once
// JSON scenes (docs/scene-format.md): bodies, shapes, materials, gravity, time step and step
// count, with reserved sections (joints, solver, urdf) that later issues fill. Every error is a
// CoulombError "<file>: <JSON path>: <problem>", e.g. "drop.json: bodies[3].mass: must be > 0".
#include <coulomb/engine/ArticulationDesc.hpp>
#include <coulomb/engine/BodyDesc.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/engine/WorldSettings.hpp>
#include <coulomb/joints/JointDef.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace coulomb::engine::io {

/// A joint of the "joints" section: its ends as indices into Scene::bodies (-1 = the world) and
/// the definition with frames in the bodies' reference frames (World::createJoint's convention).
struct SceneJoint {
  int bodyA = -1;
  int bodyB = -1;
  joints::JointDef def;
};

struct Scene {
  std::string name;         // "name" key, else the file stem
  std::string description;  // free text
  std::string source;       // where it came from (file path or "built-in scene 'x'"), for messages
  WorldSettings settings;   // gravity and time step
  std::uint64_t steps = 1000;
  std::vector<BodyDesc> bodies;
  std::vector<ArticulationDesc> articulations;  // created after the bodies, in file order
  std::vector<SceneJoint> joints;               // created after the articulations, in file order
};

/// Reads and parses a scene file; mesh file paths are relative to the file's folder.
Scene loadSceneFile(const std::filesystem::path& file);

/// Parses scene text. `source` names it in messages; `baseDirectory` resolves mesh file paths.
Scene parseScene(std::string_view text, const std::string& source,
                 const std::filesystem::path& baseDirectory = {});

/// A joint in the "joints" format of docs/scene-format.md whose ends name live bodies of `world`
/// ("world" or absent = the world); frames given in world coordinates ("anchor", "axis",
/// "normal") are taken at the bodies' present poses. Returns the definition with its body ids,
/// ready for World::createJoint. Errors: CoulombError "<source>: joint.<path>: <problem>".
joints::JointDef parseLiveJoint(std::string_view text, const World& world,
                                const std::string& source);

/// A World holding the scene's bodies (in file order: body i gets slot i), articulations and joints
/// (joint i gets JointId {i, 0}). Creation errors are reported as "<source>: bodies[i]..." or
/// "<source>: joints[i]: ...".
World buildWorld(const Scene& scene);

}  // namespace coulomb::engine::io
