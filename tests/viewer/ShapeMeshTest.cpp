// Shape meshing (samples/viewer/ShapeMesh): every vertex lies on the shape's surface, normals
// are unit and point outward, and the triangle counts follow the detail.
#include <gtest/gtest.h>

#include <coulomb/geometry/Shape.hpp>
#include <coulomb/geometry/SweptMargin.hpp>

#include <Eigen/Core>
#include <cmath>

#include "SceneBounds.hpp"
#include "ShapeMesh.hpp"

namespace coulomb::viewer {
namespace {

Eigen::Vector3d at(const std::vector<float>& v, std::size_t k) {
  return {v[3 * k], v[3 * k + 1], v[3 * k + 2]};
}

TEST(ShapeMesh, BoxHasTwelveOutwardTrianglesOnItsFaces) {
  const Mesh mesh = meshShape(geometry::Box{Eigen::Vector3d(0.1, 0.2, 0.3)});
  ASSERT_EQ(mesh.triangleCount(), 12u);
  for (std::size_t k = 0; k < mesh.vertexCount(); ++k) {
    const Eigen::Vector3d p = at(mesh.positions, k), n = at(mesh.normals, k);
    EXPECT_NEAR(p.cwiseAbs().cwiseQuotient(Eigen::Vector3d(0.1, 0.2, 0.3)).maxCoeff(), 1.0, 1e-6);
    EXPECT_NEAR(n.norm(), 1.0, 1e-6);
    EXPECT_GT(n.dot(p), 0.0);  // outward
  }
}

TEST(ShapeMesh, SphereVerticesOnTheRadiusWithRadialNormals) {
  const MeshDetail detail{16, 8, 10.0};
  const Mesh mesh = meshShape(geometry::Sphere{0.25}, detail);
  // Each of the 8 stacks gives 16 quads, the two polar stacks one triangle per quad.
  EXPECT_EQ(mesh.triangleCount(), 16u * (2 * 8 - 2));
  for (std::size_t k = 0; k < mesh.vertexCount(); ++k) {
    const Eigen::Vector3d p = at(mesh.positions, k), n = at(mesh.normals, k);
    EXPECT_NEAR(p.norm(), 0.25, 1e-6);
    EXPECT_NEAR((n - p / 0.25).norm(), 0.0, 1e-5);
  }
}

TEST(ShapeMesh, CapsuleAndCylinderStayOnTheirSurfaces) {
  const Mesh capsule = meshShape(geometry::Capsule{0.1, 0.4});
  ASSERT_GT(capsule.triangleCount(), 0u);
  for (std::size_t k = 0; k < capsule.vertexCount(); ++k) {
    const Eigen::Vector3d p = at(capsule.positions, k);
    const Eigen::Vector3d axis(0.0, 0.0, std::clamp(p.z(), -0.4, 0.4));  // nearest segment point
    EXPECT_NEAR((p - axis).norm(), 0.1, 1e-6);
  }
  const Mesh cylinder = meshShape(geometry::Cylinder{0.3, 0.2});
  ASSERT_GT(cylinder.triangleCount(), 0u);
  for (std::size_t k = 0; k < cylinder.vertexCount(); ++k) {
    const Eigen::Vector3d p = at(cylinder.positions, k);
    const bool onCap =
        std::abs(std::abs(p.z()) - 0.2) < 1e-6 && std::hypot(p.x(), p.y()) <= 0.3 + 1e-6;
    const bool onSide =
        std::abs(std::hypot(p.x(), p.y()) - 0.3) < 1e-6 && std::abs(p.z()) <= 0.2 + 1e-6;
    EXPECT_TRUE(onCap || onSide) << p.transpose();
  }
}

TEST(ShapeMesh, HullWithoutFacesIsTriangulatedAndMeshKeepsItsTriangles) {
  geometry::ConvexHull hull;  // a tetrahedron given as points only
  hull.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const Mesh hullMesh = meshShape(hull);
  EXPECT_EQ(hullMesh.triangleCount(), 4u);
  const Eigen::Vector3d centroid(0.25, 0.25, 0.25);
  for (std::size_t k = 0; k < hullMesh.vertexCount(); ++k)
    EXPECT_GT(at(hullMesh.normals, k).dot(at(hullMesh.positions, k) - centroid), 0.0);

  geometry::TriangleMesh tri;
  tri.vertices = hull.vertices;
  tri.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  EXPECT_EQ(meshShape(tri).triangleCount(), 4u);
}

TEST(ShapeMesh, PlaneIsASquareOnItsSurface) {
  const Mesh mesh = meshShape(geometry::Plane{Eigen::Vector3d::UnitZ(), 0.5}, {24, 12, 3.0});
  ASSERT_EQ(mesh.triangleCount(), 2u);
  for (std::size_t k = 0; k < mesh.vertexCount(); ++k) {
    EXPECT_NEAR(at(mesh.positions, k).z(), 0.5, 1e-6);
    EXPECT_NEAR(at(mesh.positions, k).head<2>().cwiseAbs().maxCoeff(), 3.0, 1e-6);
    EXPECT_NEAR(at(mesh.normals, k).z(), 1.0, 1e-6);
  }
  EXPECT_EQ(geometry::boundingRadius(geometry::Plane{}), 0.0);  // never framed by the camera
}

}  // namespace
}  // namespace coulomb::viewer
