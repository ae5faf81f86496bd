#pragma once
// Collision and mass shapes, each in its own local frame (centred at the origin unless stated).
// Axis-aligned shapes (capsule, cylinder) use the local z axis, as FCL does.
// validateShape() is the single gate through which every shape enters a World.
#include <Eigen/Core>

#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace coulomb::geometry {

struct Sphere {
  double radius = 0.5;
};
struct Box {
  Eigen::Vector3d halfExtents = Eigen::Vector3d::Constant(0.5);
};
/// Segment from (0,0,-halfLength) to (0,0,+halfLength) swept by a ball of `radius`.
struct Capsule {
  double radius = 0.25;
  double halfLength = 0.5;
};
/// Solid cylinder of `radius` between z = -halfLength and z = +halfLength.
struct Cylinder {
  double radius = 0.5;
  double halfLength = 0.5;
};
/// Half-space {x : normal . x <= offset}; its surface is the plane normal . x = offset.
/// Infinite: only static bodies may carry it (it has no finite mass).
struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0.0;
};
/// Convex hull of a point cloud. `vertices` are the input points; the hull's faces are computed
/// when the shape is validated/used (outward-oriented triangles in `triangles`).
/// A polygonal face of a hull (coplanar triangles merged), in the hull's frame.
struct HullFace {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // outward, unit
  double offset = 0.0;                                // normal . x = offset on the face plane
  std::vector<int> loop;  // vertex indices, counter-clockwise seen from outside
};
struct ConvexHull {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;  // filled by makeConvexHull()
  // The faces and the unique edges (i < j), filled by makeConvexHull() from the triangles: the
  // features of the hull-hull manifolds (HullContacts.hpp), built once per shape instead of in
  // every query.
  std::vector<HullFace> faces;
  std::vector<std::pair<int, int>> edges;
};
/// Closed, consistently oriented (outward normals, counter-clockwise) triangle mesh.
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
};

using Shape = std::variant<Sphere, Box, Capsule, Cylinder, Plane, ConvexHull, TriangleMesh>;

/// Human-readable kind name ("sphere", "box", ...), as used in scene files and messages.
const char* shapeKindName(const Shape& shape);

/// Returns a message naming the first invalid value (non-finite, non-positive size, fewer than 4
/// non-coplanar hull points, open or degenerate mesh, zero plane normal), or nullopt when valid.
std::optional<std::string> validateShape(const Shape& shape);

}  // namespace coulomb::geometry
