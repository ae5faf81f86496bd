#pragma once
// What the comparison needs from an engine: build a PeerScene, take one step of scene.dt, and
// report every body's state (in scene order; static bodies included, they do not move).
#include "PeerScene.hpp"

#include <Eigen/Geometry>

#include <memory>
#include <string>
#include <vector>

namespace coulomb::peers {

struct BodySample {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // COM, world
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d linearVelocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();
};

class PeerEngine {
 public:
  virtual ~PeerEngine() = default;
  /// Collision detection + solve + integration over one step of the scene's dt.
  virtual void step() = 0;
  /// State of body i (scene order) for every body.
  virtual void read(std::vector<BodySample>& out) const = 0;
  /// Anything the engine reported during the run (e.g. ODE's LCP messages), for the note column.
  [[nodiscard]] virtual std::string note() const { return {}; }
};

/// The engines compared (one file each): Coulomb's default (the scene's own settings, solver
/// auto), Bullet's btDiscreteDynamicsWorld with btSequentialImpulseConstraintSolver, and ODE
/// with dWorldQuickStep (`quickStep` true) or dWorldStep.
std::unique_ptr<PeerEngine> makeCoulomb(const PeerScene& scene);
std::unique_ptr<PeerEngine> makeBullet(const PeerScene& scene);
std::unique_ptr<PeerEngine> makeOde(const PeerScene& scene, bool quickStep);

}  // namespace coulomb::peers
