#include <coulomb/geometry/Shape.hpp>
#include <gtest/gtest.h>

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
