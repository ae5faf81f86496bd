// Mass properties of every shape against closed forms or an independent integration.
#include <gtest/gtest.h>
#include <coulomb/geometry/MassProperties.hpp>
#include <coulomb/meshes/MakeConvexHull.hpp>

#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>

using namespace coulomb::geometry;
constexpr double kPi = std::numbers::pi;

namespace {

TriangleMesh boxMesh(const Eigen::Vector3d& h, const Eigen::Vector3d& offset) {
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i)
    mesh.vertices.push_back(offset + Eigen::Vector3d((i & 1) ? h.x() : -h.x(),
                                                     (i & 2) ? h.y() : -h.y(),
                                                     (i & 4) ? h.z() : -h.z()));
  // Outward, counter-clockwise seen from outside.
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    mesh.triangles.emplace_back(f[0], f[1], f[2]);
    mesh.triangles.emplace_back(f[0], f[2], f[3]);
  }
  return mesh;
}

// Independent reference for solids of revolution about z: sum thin disks of radius a(z)
// (midpoint rule): dm = rho pi a^2 dz, dI_zz = dm a^2 / 2, dI_xx = dm (a^2 / 4 + z^2).
SpatialInertia revolve(const std::function<double(double)>& radiusAt, double zMax, double rho) {
  const int n = 200000;
  const double dz = 2.0 * zMax / n;
  double m = 0, ixx = 0, izz = 0;
  for (int k = 0; k < n; ++k) {
    const double z = -zMax + (k + 0.5) * dz, a = radiusAt(z);
    const double dm = rho * kPi * a * a * dz;
    m += dm;
    izz += dm * a * a / 2.0;
    ixx += dm * (a * a / 4.0 + z * z);
  }
  return {m, Eigen::Vector3d::Zero(), Eigen::Vector3d(ixx, ixx, izz).asDiagonal()};
}

void expectSame(const SpatialInertia& a, const SpatialInertia& b, double relative) {
  EXPECT_NEAR(a.mass, b.mass, relative * b.mass);
  EXPECT_LT((a.centerOfMass - b.centerOfMass).norm(), 1e-9 + relative);
  const double scale = b.inertiaAboutCom.norm();
  EXPECT_LT((a.inertiaAboutCom - b.inertiaAboutCom).norm(), relative * scale)
      << a.inertiaAboutCom << "\nvs\n"
      << b.inertiaAboutCom;
}

}  // namespace

TEST(MassProperties, SphereClosedForm) {
  const SpatialInertia s = computeMassProperties(Sphere{0.5}, 2000.0);
  const double m = 2000.0 * 4.0 / 3.0 * kPi * 0.125;
  EXPECT_NEAR(s.mass, m, 1e-12 * m);
  EXPECT_NEAR(s.inertiaAboutCom(0, 0), 0.4 * m * 0.25, 1e-12);
  EXPECT_TRUE(s.centerOfMass.isZero());
  expectSame(s,
             revolve([](double z) { return std::sqrt(std::max(0.0, 0.25 - z * z)); }, 0.5, 2000.0),
             1e-6);
}

TEST(MassProperties, BoxClosedForm) {
  const SpatialInertia b = computeMassProperties(Box{Eigen::Vector3d(0.5, 1.0, 1.5)}, 10.0);
  const double m = 10.0 * 1.0 * 2.0 * 3.0;  // full sides 1, 2, 3
  EXPECT_DOUBLE_EQ(b.mass, m);
  EXPECT_NEAR(b.inertiaAboutCom(0, 0), m / 12.0 * (4.0 + 9.0), 1e-12);
  EXPECT_NEAR(b.inertiaAboutCom(1, 1), m / 12.0 * (1.0 + 9.0), 1e-12);
  EXPECT_NEAR(b.inertiaAboutCom(2, 2), m / 12.0 * (1.0 + 4.0), 1e-12);
}

TEST(MassProperties, CylinderAgainstDiskIntegration) {
  const SpatialInertia c = computeMassProperties(Cylinder{0.3, 0.8}, 500.0);
  const double m = 500.0 * kPi * 0.09 * 1.6;
  EXPECT_NEAR(c.mass, m, 1e-12 * m);
  EXPECT_NEAR(c.inertiaAboutCom(2, 2), m * 0.09 / 2.0, 1e-12);
  EXPECT_NEAR(c.inertiaAboutCom(0, 0), m * (3 * 0.09 + 1.6 * 1.6) / 12.0, 1e-12);
  expectSame(c, revolve([](double) { return 0.3; }, 0.8, 500.0), 1e-6);
}

TEST(MassProperties, CapsuleAgainstDiskIntegration) {
  const double r = 0.25, h = 0.6;
  const SpatialInertia c = computeMassProperties(Capsule{r, h}, 800.0);
  const auto radius = [&](double z) {
    const double beyond = std::max(0.0, std::abs(z) - h);
    return std::sqrt(std::max(0.0, r * r - beyond * beyond));
  };
  expectSame(c, revolve(radius, h + r, 800.0), 1e-6);
  EXPECT_NEAR(c.mass, 800.0 * (kPi * r * r * 2 * h + 4.0 / 3.0 * kPi * r * r * r), 1e-9);
}

TEST(MassProperties, MeshOfABoxIsTheBox) {
  const Eigen::Vector3d half(0.5, 1.0, 1.5), offset(3.0, -2.0, 7.0);
  const SpatialInertia mesh = computeMassProperties(boxMesh(half, offset), 10.0);
  SpatialInertia box = computeMassProperties(Box{half}, 10.0);
  box.centerOfMass = offset;
  expectSame(mesh, box, 1e-12);
}

TEST(MassProperties, HullOfABoxsCornersIsTheBox) {
  const Eigen::Vector3d half(0.5, 1.0, 1.5);
  std::vector<Eigen::Vector3d> points = boxMesh(half, Eigen::Vector3d::Zero()).vertices;
  points.emplace_back(0.1, 0.2, -0.3);  // interior points change nothing
  points.emplace_back(0.0, 0.0, 0.0);
  const ConvexHull hull = makeConvexHull(points);
  expectSame(computeMassProperties(hull, 10.0), computeMassProperties(Box{half}, 10.0), 1e-12);
}

TEST(MassProperties, TetrahedronClosedForm) {
  // Unit corner tetrahedron at density 1: integral of x^a y^b z^c = a! b! c! / (a+b+c+3)!, so
  // V = 1/6, COM = (1/4, 1/4, 1/4), int x^2 = 1/60, int xy = 1/120, hence about the COM
  // I_xx = 2/60 - (1/6)(2/16) = 1/80 and I_xy = -(1/120 - (1/6)(1/16)) = 1/480.
  TriangleMesh tetra;
  tetra.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tetra.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const SpatialInertia t = computeMassProperties(tetra, 1.0);
  EXPECT_NEAR(t.mass, 1.0 / 6.0, 1e-15);
  EXPECT_TRUE(t.centerOfMass.isApprox(Eigen::Vector3d::Constant(0.25), 1e-14));
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(t.inertiaAboutCom(i, i), 1.0 / 80.0, 1e-15);
    EXPECT_NEAR(t.inertiaAboutCom(i, (i + 1) % 3), 1.0 / 480.0, 1e-15);
  }
}

TEST(MassProperties, InwardMeshHasNegativeVolume) {
  TriangleMesh mesh = boxMesh(Eigen::Vector3d::Constant(1.0), Eigen::Vector3d::Zero());
  for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  EXPECT_LT(polyhedronMassProperties(mesh.vertices, mesh.triangles, 1.0).mass, 0.0);
}

TEST(MassProperties, RejectsWhatHasNoMass) {
  EXPECT_THROW(computeMassProperties(Plane{}, 1.0), std::invalid_argument);
  EXPECT_THROW(computeMassProperties(Sphere{1.0}, 0.0), std::invalid_argument);
  EXPECT_THROW(computeMassProperties(Sphere{1.0}, std::nan("")), std::invalid_argument);
  EXPECT_THROW(computeMassProperties(ConvexHull{}, 1.0), std::invalid_argument);
  EXPECT_DOUBLE_EQ(shapeVolume(Box{Eigen::Vector3d::Constant(0.5)}), 1.0);
  EXPECT_EQ(shapeVolume(Plane{}), 0.0);
}
