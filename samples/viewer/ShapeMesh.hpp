#pragma once
// Triangles for drawing a shape, in the shape's own frame (geometry/Shape.hpp conventions: capsule
// and cylinder along local z, a plane as a finite square around its point nearest the origin).
// A triangle soup with one normal per vertex, ready for glDrawArrays(GL_TRIANGLES).
#include <coulomb/geometry/Shape.hpp>

#include <cstddef>
#include <vector>

namespace coulomb::viewer {

struct Mesh {
  std::vector<float> positions;  // x, y, z per vertex; 3 vertices per triangle
  std::vector<float> normals;    // unit outward normal per vertex
  [[nodiscard]] std::size_t vertexCount() const { return positions.size() / 3; }
  [[nodiscard]] std::size_t triangleCount() const { return vertexCount() / 3; }
};

struct MeshDetail {
  int slices = 24;              // around the z axis (spheres, capsules, cylinders)
  int stacks = 12;              // pole to pole (spheres; half of it per capsule cap)
  double planeHalfSize = 10.0;  // [m] half side of the square drawn for a plane
};

/// Smooth normals on curved surfaces, flat ones on boxes, hulls and meshes. A hull without
/// triangles gets them from geometry::makeConvexHull.
Mesh meshShape(const geometry::Shape& shape, const MeshDetail& detail = {});

}  // namespace coulomb::viewer
