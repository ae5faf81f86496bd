#pragma once
// What `coulomb urdf info` and `coulomb urdf dynamics` print (docs/urdf.md, "CLI"): a UrdfModel as
// text or JSON, and forward dynamics of a loaded model at a joint state given by joint name.
#include <coulomb/urdf/UrdfLoader.hpp>

#include <Eigen/Core>

#include <string>

namespace coulomb::engine::io {

/// Joint positions, velocities and torques in the model's DOF order (UrdfModel::dofNames).
struct UrdfJointState {
  Eigen::VectorXd q, qdot, tau;
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};
};

/// Parses {"q": {"joint": value, ...}, "qdot": {...}, "tau": {...}, "gravity": [gx, gy, gz]};
/// every key optional, missing joints are zero. Throws CoulombError "<source>: <key>: <problem>"
/// for an unknown joint (with the nearest name), a non-number, or an unknown key.
UrdfJointState parseUrdfJointState(const std::string& text, const std::string& source,
                                   const UrdfModel& model);

/// How `coulomb urdf dynamics` loads a robot: `options` with a fixed base, no joint damping (pure
/// rigid-body dynamics, as other tools' M, h and ABA) and no meshes.
UrdfOptions urdfDynamicsOptions(UrdfOptions options = {});

/// {"joints": [...], "qddot": [...], "mass_matrix": [[...]], "bias_forces": [...],
///  "inertias": {"as_written": bool, "repaired": [bodies], "not_physical_kept": [bodies]}} for a
/// model whose joints all have one DOF (fixed base), numbers in shortest round-trip form. The
/// inertias are the file's (docs/urdf.md, "Inertia policy") except the bodies listed repaired.
std::string urdfDynamicsJson(const UrdfModel& model, const UrdfJointState& state);

/// The tree for people: bodies with their joints, masses, inertia validity, fused links and
/// collision shapes, then mimic couplings, the <gazebo> extensions used and ignored, and
/// warnings.
std::string urdfInfoText(const UrdfModel& model);
/// The same as JSON, with "dofs" (velocity coordinates), "joints" (DOF joint names in order) and
/// "gazebo" ({"blocks", "friction": {link: mu1}, "used": {element: count}, "ignored": {...}}).
std::string urdfInfoJson(const UrdfModel& model);

}  // namespace coulomb::engine::io
