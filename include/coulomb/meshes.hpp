#pragma once
// Component coulomb::meshes (assimp, qhull; docs/embedding.md): triangle meshes from files and
// convex hulls from points, for BodyDesc shapes.
#include <coulomb/meshes/MakeConvexHull.hpp>
#include <coulomb/meshes/MeshLoader.hpp>
#include <coulomb/world.hpp>

namespace coulomb {

using geometry::loadTriangleMesh;  // STL, OBJ, COLLADA, ... -> TriangleMesh
using geometry::makeConvexHull;    // points -> ConvexHull with its faces (qhull)

}  // namespace coulomb
