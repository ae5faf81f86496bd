#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <coulomb/geometry/MassProperties.hpp>
#include <coulomb/meshes/MakeConvexHull.hpp>

#include <cmath>
#include <stdexcept>

using namespace coulomb::geometry;

TEST(MakeConvexHull, OctahedronHasEightOutwardFaces) {
  std::vector<Eigen::Vector3d> points = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                         {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  const ConvexHull hull = makeConvexHull(points);
  EXPECT_EQ(hull.vertices.size(), points.size());
  ASSERT_EQ(hull.triangles.size(), 8u);
  for (const auto& t : hull.triangles) {
    const Eigen::Vector3d a = points[t[0]], b = points[t[1]], c = points[t[2]];
    EXPECT_GT((b - a).cross(c - a).dot(a + b + c), 0.0);  // normal points away from the centre
  }
  EXPECT_NEAR(shapeVolume(hull), 4.0 / 3.0, 1e-12);
  // A valid hull is a valid closed mesh too.
  EXPECT_FALSE(validateShape(TriangleMesh{hull.vertices, hull.triangles}).has_value());
}

TEST(MakeConvexHull, SphereSamplesApproachTheBallVolume) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 20; ++j) {
      const double theta = M_PI * (j + 0.5) / 20, phi = 2 * M_PI * i / 40;
      points.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                          std::cos(theta));
    }
  const double volume = shapeVolume(makeConvexHull(points));
  EXPECT_LT(volume, 4.0 / 3.0 * M_PI);
  EXPECT_GT(volume, 0.95 * 4.0 / 3.0 * M_PI);
}

TEST(MakeConvexHull, DegenerateInputIsRejectedWithAReason) {
  EXPECT_THROW(makeConvexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}), std::invalid_argument);
  try {
    makeConvexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5, 0.2, 0}});
    FAIL() << "coplanar points accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("degenerate"), std::string::npos) << e.what();
  }
  EXPECT_THROW(makeConvexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, NAN}}),
               std::invalid_argument);
}
