#pragma once
// Active edges of a triangle mesh (Jolt's "active edges", Bullet's btAdjustInternalEdgeContacts):
// an edge shared by two triangles that are coplanar or fold inwards (concave) is internal. A
// contact there must keep the face normal: a box sliding over a flat triangulated floor would
// otherwise meet sideways normals at every internal edge and bump (docs/fcl-notes.md 4.6).
// Boundary edges, edges of more than two triangles and convex creases stay active.
// Triangles joined by internal edges form one smooth patch: the surface a contact slides over
// without meeting a crease (a drum's inner wall, a triangulated floor).
#include <coulomb/geometry/Shape.hpp>

#include <cstdint>
#include <vector>

namespace coulomb::geometry {

/// Convex creases sharper than this [rad] are active; flatter ones count as flat.
inline constexpr double kActiveEdgeAngle = 1e-3;

struct MeshSurface {
  /// Per triangle t: bit k set = edge k (vertex k to vertex k+1) is active.
  std::vector<std::uint8_t> activeEdges;
  /// Per triangle: its smooth patch, numbered by the lowest triangle index in it.
  std::vector<std::uint32_t> patch;
};

MeshSurface meshSurface(const TriangleMesh& mesh);

}  // namespace coulomb::geometry
