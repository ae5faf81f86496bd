#include <gtest/gtest.h>
#include <coulomb/geometry/Shape.hpp>

#include <limits>

using namespace coulomb::geometry;

TEST(Shape, ValidPrimitivesPass) {
  EXPECT_FALSE(validateShape(Sphere{1.0}).has_value());
  EXPECT_FALSE(validateShape(Box{}).has_value());
  EXPECT_FALSE(validateShape(Capsule{}).has_value());
  EXPECT_FALSE(validateShape(Cylinder{}).has_value());
  EXPECT_FALSE(validateShape(Plane{}).has_value());
}

TEST(Shape, DegeneratePrimitivesNameTheValue) {
  auto zeroBox = validateShape(Box{Eigen::Vector3d(1.0, 0.0, 1.0)});
  ASSERT_TRUE(zeroBox.has_value());
  EXPECT_NE(zeroBox->find("half_extents[1]"), std::string::npos);
  auto nanSphere = validateShape(Sphere{std::numeric_limits<double>::quiet_NaN()});
  ASSERT_TRUE(nanSphere.has_value());
  EXPECT_NE(nanSphere->find("radius"), std::string::npos);
  EXPECT_TRUE(validateShape(Plane{Eigen::Vector3d::Zero(), 0.0}).has_value());
}

TEST(Shape, KindNames) {
  EXPECT_STREQ(shapeKindName(Shape{Box{}}), "box");
  EXPECT_STREQ(shapeKindName(Shape{TriangleMesh{}}), "mesh");
}

TEST(Shape, HullMustSpanAVolume) {
  ConvexHull flat;
  flat.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  const auto coplanar = validateShape(flat);
  ASSERT_TRUE(coplanar.has_value());
  EXPECT_NE(coplanar->find("coplanar"), std::string::npos);
  ConvexHull line;
  line.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  EXPECT_NE(validateShape(line).value_or("").find("collinear"), std::string::npos);
  ConvexHull good = flat;
  good.vertices.emplace_back(0.3, 0.3, 1.0);
  EXPECT_FALSE(validateShape(good).has_value());
}

TEST(Shape, HullTrianglesMustReferToItsPoints) {
  ConvexHull hull;
  hull.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  hull.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  EXPECT_FALSE(validateShape(hull).has_value());
  hull.triangles[2] = {0, 4, 2};
  EXPECT_NE(validateShape(hull).value_or("").find("triangle 2"), std::string::npos);
  hull.triangles[2] = {0, -1, 2};
  EXPECT_TRUE(validateShape(hull).has_value());
}

namespace {
TriangleMesh tetrahedron() {
  TriangleMesh tetra;
  tetra.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tetra.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return tetra;
}
}  // namespace

TEST(Shape, MeshMustBeClosedOrientedAndEnclosingVolume) {
  EXPECT_FALSE(validateShape(tetrahedron()).has_value());

  TriangleMesh open = tetrahedron();
  open.triangles.pop_back();
  open.triangles.push_back({1, 2, 0});  // duplicate direction of an existing face
  EXPECT_TRUE(validateShape(open).has_value());

  TriangleMesh flipped = tetrahedron();
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  EXPECT_NE(validateShape(flipped).value_or("").find("oriented"), std::string::npos);

  TriangleMesh inward = tetrahedron();
  for (auto& t : inward.triangles) std::swap(t[1], t[2]);
  EXPECT_NE(validateShape(inward).value_or("").find("inward"), std::string::npos);

  TriangleMesh flat = tetrahedron();
  flat.vertices[3] = Eigen::Vector3d(0.2, 0.2, 0.0);
  EXPECT_NE(validateShape(flat).value_or("").find("no volume"), std::string::npos);

  TriangleMesh outOfRange = tetrahedron();
  outOfRange.triangles[2][1] = 9;
  EXPECT_NE(validateShape(outOfRange).value_or("").find("out of range"), std::string::npos);

  TriangleMesh repeated = tetrahedron();
  repeated.triangles[1] = Eigen::Vector3i(0, 0, 3);
  EXPECT_NE(validateShape(repeated).value_or("").find("repeats"), std::string::npos);
}

TEST(Shape, OpenMeshNamesTheBorderEdge) {
  TriangleMesh open = tetrahedron();
  open.triangles.push_back({0, 1, 2});  // 5 triangles, one sheet doubled
  open.triangles.erase(open.triangles.begin());
  const auto message = validateShape(open).value_or("");
  EXPECT_NE(message.find("edge"), std::string::npos) << message;
}
