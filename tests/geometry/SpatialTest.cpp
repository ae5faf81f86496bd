#include <gtest/gtest.h>
#include <coulomb/geometry/Spatial.hpp>

using namespace coulomb::geometry;

TEST(Spatial, SkewIsTheCrossProduct) {
  const Eigen::Vector3d a(1, 2, 3), b(-4, 0.5, 2);
  EXPECT_TRUE((skew(a) * b).isApprox(a.cross(b)));
}

TEST(Spatial, CrossProductsMatchTheirMatrices) {
  Vector6d m, n;
  m << 0.1, -0.4, 0.3, 1.0, 2.0, -1.5;
  n << 0.7, 0.2, -0.1, -0.3, 0.8, 0.5;
  EXPECT_TRUE(crossMotion(m, n).isApprox(crossMotionMatrix(m) * n));
  // x* = -(x)^T (Featherstone eq. 2.32)
  EXPECT_TRUE(crossForce(m, n).isApprox(-crossMotionMatrix(m).transpose() * n));
  // Power is invariant: (m x n) . f = -n . (m x* f)
  EXPECT_NEAR(crossMotion(m, n).dot(n), -n.dot(crossForce(m, n)), 1e-12);
}

TEST(Spatial, MotionTransformMovesTheReferencePoint) {
  // A pure translation r: linear velocity at the new origin is v - r x w... = v + w x r.
  const Eigen::Vector3d w(0, 0, 2), v(1, 0, 0), r(0, 1, 0);
  const Vector6d moved = motionTransform(Eigen::Matrix3d::Identity(), r) * motionVector(w, v);
  EXPECT_TRUE(angularPart(moved).isApprox(w));
  EXPECT_TRUE(linearPart(moved).isApprox(v + w.cross(r)));
}
