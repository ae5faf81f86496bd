// Meshes from STL, OBJ and COLLADA fixtures in tests/data/meshes (origins in ORIGIN.md).
#include <coulomb/meshes/MeshLoader.hpp>

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace coulomb::geometry {
namespace {

const std::string kDir = std::string(COULOMB_TEST_DATA_DIR) + "/meshes/";

Eigen::Vector3d extent(const TriangleMesh& m) {
  Eigen::Vector3d lo = m.vertices[0], hi = m.vertices[0];
  for (const auto& v : m.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  return hi - lo;
}

TEST(MeshLoader, ObjCubeWithScale) {
  const TriangleMesh m = loadTriangleMesh(kDir + "unit_cube.obj", {2.0, 1.0, 0.5});
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(m.vertices.size(), 8u);
  EXPECT_TRUE(extent(m).isApprox(Eigen::Vector3d(2.0, 1.0, 0.5)));
  EXPECT_FALSE(validateShape(Shape{m}).has_value());
}

TEST(MeshLoader, BinaryStlFromTheUrdfCorpus) {
  const TriangleMesh m = loadTriangleMesh(kDir + "RS2-266_convex_hull.stl");
  EXPECT_EQ(m.triangles.size(), 74u);
  EXPECT_LT(m.vertices.size(), 3u * 74u);  // identical vertices welded
  const auto problem = validateShape(Shape{m});
  EXPECT_FALSE(problem.has_value()) << *problem;
}

TEST(MeshLoader, ColladaWithNodeTransforms) {
  const TriangleMesh m = loadTriangleMesh(kDir + "battery.dae");
  EXPECT_GT(m.triangles.size(), 0u);
  EXPECT_TRUE(extent(m).allFinite());
  EXPECT_GT(extent(m).minCoeff(), 0.0);
  const TriangleMesh half = loadTriangleMesh(kDir + "battery.dae", Eigen::Vector3d::Constant(0.5));
  EXPECT_TRUE(extent(half).isApprox(0.5 * extent(m), 1e-9));
}

TEST(MeshLoader, MissingFileNamesTheFile) {
  try {
    loadTriangleMesh(kDir + "no_such_mesh.stl");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_mesh.stl"), std::string::npos) << e.what();
  }
}

TEST(MeshLoader, ZeroScaleIsRejected) {
  EXPECT_THROW(loadTriangleMesh(kDir + "unit_cube.obj", {1.0, 0.0, 1.0}), std::runtime_error);
}

}  // namespace
}  // namespace coulomb::geometry
