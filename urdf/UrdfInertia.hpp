#pragma once
// Internal to the URDF loader: the inertia policy (docs/urdf.md, "Inertia policy").
// Reduced coordinates (ABA, RNEA, CRBA) need of each body a symmetric positive semidefinite
// tensor and, behind each moving joint, something with inertia; nothing more. So a tree keeps
// the file's tensor whenever the algorithms can use it, including tensors that break the
// triangle inequality (warned: no mass distribution has them, but they are common in
// CAD-exported files, and tools that check a model, DART or a Newton-Euler by hand, compute with
// them as written), and repairs only what the algorithms cannot use. A free rigid body
// (maximal coordinates, UrdfMaximal.hpp) needs a physical tensor: withTriangleInequality.
#include <coulomb/urdf/UrdfLoader.hpp>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace coulomb::engine::io {

/// Applies the tree's policy to the bodies after fusing (parent-first order): a massless subtree
/// behind a moving joint gets UrdfOptions::masslessSubtreeMass/Inertia; a tensor that is not
/// positive semidefinite has its principal moments below 1e-9 of the largest lifted to that
/// floor; everything else is kept. Sets UrdfBody::inertiaStatus and inertiaValid; appends the
/// warnings (repairs one per body, tensors kept although not physical in one line).
void applyTreeInertiaPolicy(std::vector<UrdfBody>& bodies, const UrdfOptions& options,
                            std::vector<std::string>& warnings);

/// The tensor with its two smaller principal moments raised by the same amount until
/// I1 + I2 >= I3, principal axes kept (unchanged if the inequality holds).
Eigen::Matrix3d withTriangleInequality(const Eigen::Matrix3d& inertia);

}  // namespace coulomb::engine::io
