#pragma once
// Component coulomb::io (nlohmann-json, with urdf and meshes; docs/scene-format.md,
// docs/reliability.md): the JSON scene format and snapshots.
#include <coulomb/io/SceneLoader.hpp>
#include <coulomb/io/Snapshot.hpp>
#include <coulomb/world.hpp>

namespace coulomb {

using engine::io::buildWorld;     // Scene -> World
using engine::io::loadSceneFile;  // .json file -> Scene (errors name file:line and the key)
using engine::io::parseScene;     // JSON text -> Scene
using engine::io::Scene;
// Snapshots: the whole state as bytes, restored bit for bit into a World of the same scene.
using engine::io::loadSnapshotFile;
using engine::io::restoreSnapshot;
using engine::io::saveSnapshot;
using engine::io::saveSnapshotFile;

}  // namespace coulomb
