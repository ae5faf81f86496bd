#pragma once
// URDF robots in scenes (docs/scene-format.md "urdf", docs/urdf.md "In a scene"): the JSON
// scene's `urdf` section and a scene made of one URDF file on a floor (`coulomb run robot.urdf`).
// Each robot becomes an ArticulationDesc (reduced coordinates) with its initial joint positions,
// motors (position or velocity targets with an effort bound) and mimic couplings.
#include <coulomb/engine/ArticulationDesc.hpp>
#include <coulomb/io/SceneLoader.hpp>
#include <coulomb/urdf/UrdfLoader.hpp>
#include <coulomb/urdf/UrdfMaximal.hpp>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace coulomb::engine::io {

class JsonNode;

/// A motor of a URDF scene, by joint name.
struct UrdfMotorSpec {
  JointMotorMode mode = JointMotorMode::Position;
  double target = 0.0;
  std::optional<double> maxEffort;  // nullopt: the joint's <limit effort>, else the scene default
  double positionGain = 0.2;
};

/// One robot of a scene: what the JSON `urdf` entries hold.
struct UrdfPlacement {
  std::filesystem::path file;  // resolved (exists)
  std::string name;            // articulation name (link proxies "name/link")
  UrdfOptions options;         // base, pose, package path, fusing
  /// Lift the robot so that its lowest collision shape rests `clearance` above z = 0 (the pose's
  /// z is then ignored). Used for `coulomb run robot.urdf`; a JSON entry sets "on_floor".
  std::optional<double> clearance;
  std::map<std::string, double> q;  // initial joint positions by name (others 0)
  std::map<std::string, UrdfMotorSpec> motors;
  /// Constant joint torques [N m] or forces [N] by joint name, applied every step.
  std::map<std::string, double> torques;
  /// Position motors holding every 1-DOF joint without a motor at its initial position.
  bool holdAllJoints = false;
  double defaultMaxEffort = 100.0;  // [N m or N] when a joint gives no <limit effort>
  bool mimicCouplings = true;       // URDF <mimic> as coupling rows
  bool selfCollision = false;
  /// Free bodies and maximal-coordinate joints instead of a tree (UrdfMaximal.hpp): velocity
  /// motors only (JointDef::motor), no torques, no mimic couplings (the followers stay free).
  bool maximal = false;
};

/// Where a scene's `file` is looked for: the scene's folder, then each folder of the environment
/// variable COULOMB_ROBOT_PATH (':'-separated), the path as written and then without its leading
/// "../" parts. Throws CoulombError listing the candidates.
std::filesystem::path resolveRobotFile(const std::string& file,
                                       const std::filesystem::path& sceneDirectory,
                                       const std::string& where);

/// Loads the robot and builds its articulation. Errors name `where` (file, JSON path).
ArticulationDesc placeUrdf(const UrdfPlacement& placement, const std::string& where);

/// The robot in maximal coordinates (placement.maximal): bodies at the link poses of the initial
/// q (lifted to the floor as placeUrdf does), hinge/prismatic joints with friction, limits and
/// velocity motors. Errors name `where` and what needs reduced coordinates.
UrdfMaximal placeUrdfMaximal(const UrdfPlacement& placement, const std::string& where);

/// The `urdf` array of a JSON scene, entries in order: trees, and the bodies and joints of the
/// robots loaded with "coordinates": "maximal" (joint ends index `bodies`, -1 = the world).
struct UrdfSection {
  std::vector<ArticulationDesc> articulations;
  std::vector<BodyDesc> bodies;
  std::vector<SceneJoint> joints;
};
/// `materialFriction`: the scene's materials by name (friction), for URDF visual materials of the
/// same name (UrdfOptions::materialFriction).
UrdfSection parseUrdfSection(const JsonNode& node, const std::filesystem::path& sceneDirectory,
                             const std::map<std::string, double>& materialFriction = {});

/// A scene of one URDF file: a static floor (plane z = 0, friction 0.8) and the robot resting on
/// it (fixed base: lowest shape on the floor; floating: dropped from 5 cm), joints held by
/// position motors at their initial positions when `hold` is set. `maximal`: free bodies and
/// maximal joints instead of a tree (UrdfMaximal.hpp; cannot be combined with `hold`).
Scene urdfFileScene(const std::filesystem::path& file, UrdfBase base, bool hold,
                    const std::vector<std::filesystem::path>& packagePath = {},
                    bool maximal = false);

}  // namespace coulomb::engine::io
