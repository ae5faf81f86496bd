#pragma once
// Triangle meshes from STL, OBJ and COLLADA (.dae) files through assimp, as URDF <mesh> elements
// need them: every mesh of the file merged into one, node transforms applied, then `scale`
// applied per axis (URDF's scale="sx sy sz").
#include <coulomb/geometry/Shape.hpp>

#include <Eigen/Core>

#include <string>

namespace coulomb::geometry {

/// Throws std::runtime_error naming the file (and assimp's reason) when the file is missing,
/// unreadable, holds no triangles, or the scale is not finite and non-zero.
TriangleMesh loadTriangleMesh(const std::string& path,
                              const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());

}  // namespace coulomb::geometry
