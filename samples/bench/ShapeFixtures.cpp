#include "ShapeFixtures.hpp"

#include <coulomb/meshes/MakeConvexHull.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace coulomb::samples {

geometry::TriangleMesh gridSlab(int cells, double halfWidth, double thickness) {
  geometry::TriangleMesh mesh;
  const int n = cells;
  auto index = [n](int layer, int i, int j) { return layer * (n + 1) * (n + 1) + i * (n + 1) + j; };
  for (int layer = 0; layer < 2; ++layer)
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j)
        mesh.vertices.emplace_back(-halfWidth + 2.0 * halfWidth * i / n,
                                   -halfWidth + 2.0 * halfWidth * j / n,
                                   layer == 0 ? 0.0 : -thickness);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = index(0, i, j), b = index(0, i + 1, j), c = index(0, i + 1, j + 1),
                d = index(0, i, j + 1);
      mesh.triangles.push_back({a, b, c});  // top: counter-clockwise seen from +z
      mesh.triangles.push_back({a, c, d});
      const int e = index(1, i, j), f = index(1, i + 1, j), g = index(1, i + 1, j + 1),
                h = index(1, i, j + 1);
      mesh.triangles.push_back({e, g, f});  // bottom: seen from -z
      mesh.triangles.push_back({e, h, g});
    }
  // Sides: the top grid's boundary joined to the bottom's, walked counter-clockwise from above.
  std::vector<std::pair<int, int>> ring;
  for (int i = 0; i < n; ++i) ring.emplace_back(i, 0);
  for (int j = 0; j < n; ++j) ring.emplace_back(n, j);
  for (int i = n; i > 0; --i) ring.emplace_back(i, n);
  for (int j = n; j > 0; --j) ring.emplace_back(0, j);
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const auto [i0, j0] = ring[k];
    const auto [i1, j1] = ring[(k + 1) % ring.size()];
    mesh.triangles.push_back({index(1, i0, j0), index(1, i1, j1), index(0, i1, j1)});
    mesh.triangles.push_back({index(1, i0, j0), index(0, i1, j1), index(0, i0, j0)});
  }
  return mesh;
}

geometry::TriangleMesh ringWall(int facets, double innerRadius, double outerRadius, double height) {
  geometry::TriangleMesh mesh;
  // Vertex 4k + (outer ? 2 : 0) + (top ? 1 : 0) at angle 2 pi k / facets.
  for (int k = 0; k < facets; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / facets;
    for (const double radius : {innerRadius, outerRadius})
      for (const double z : {-0.5 * height, 0.5 * height})
        mesh.vertices.emplace_back(radius * std::cos(angle), radius * std::sin(angle), z);
  }
  auto at = [facets](int k, int corner) { return 4 * (k % facets) + corner; };
  for (int k = 0; k < facets; ++k) {
    const int i0 = at(k, 0), i1 = at(k, 1), o0 = at(k, 2), o1 = at(k, 3);
    const int j0 = at(k + 1, 0), j1 = at(k + 1, 1), p0 = at(k + 1, 2), p1 = at(k + 1, 3);
    mesh.triangles.push_back({i0, i1, j1});  // inner wall, facing the axis
    mesh.triangles.push_back({i0, j1, j0});
    mesh.triangles.push_back({o0, p0, p1});  // outer wall, facing away
    mesh.triangles.push_back({o0, p1, o1});
    mesh.triangles.push_back({i1, o1, p1});  // top, facing +z
    mesh.triangles.push_back({i1, p1, j1});
    mesh.triangles.push_back({i0, j0, p0});  // bottom, facing -z
    mesh.triangles.push_back({i0, p0, o0});
  }
  return mesh;
}

geometry::ConvexHull boxHull(const Eigen::Vector3d& halfExtents) {
  std::vector<Eigen::Vector3d> corners;
  for (int c = 0; c < 8; ++c)
    corners.emplace_back(c & 1 ? halfExtents.x() : -halfExtents.x(),
                         c & 2 ? halfExtents.y() : -halfExtents.y(),
                         c & 4 ? halfExtents.z() : -halfExtents.z());
  return geometry::makeConvexHull(corners);
}

engine::ArticulationDesc releasedChain(int links) {
  engine::ArticulationDesc desc;
  desc.name = "chain";
  for (int i = 0; i < links; ++i) {
    engine::ArticulationLinkDesc link;
    const std::string index = std::to_string(i);  // (GCC 12 -Wrestrict misfires on "x" + s)
    link.name = std::string("link").append(index);
    link.parent = i - 1;
    link.joint = joints::tree::TreeJoint::spherical(
        std::string("j").append(index),
        geometry::Pose::translation(i == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0.1, 0, 0)));
    link.inertia = geometry::SpatialInertia{
        0.1, {0.05, 0.0, 0.0}, Eigen::Vector3d(4.857143e-6, 7.557143e-5, 7.557143e-5).asDiagonal()};
    desc.links.push_back(link);
  }
  return desc;
}

}  // namespace coulomb::samples
