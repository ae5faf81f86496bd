#include <coulomb/geometry/MassProperties.hpp>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace coulomb::geometry {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// clang before 17 lacks C++20 aggregate deduction (P1816): the C++17 guide keeps it compiling.
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

constexpr double kPi = std::numbers::pi;

SpatialInertia diagonal(double mass, double ixx, double iyy, double izz) {
  return {mass, Eigen::Vector3d::Zero(), Eigen::Vector3d(ixx, iyy, izz).asDiagonal()};
}

SpatialInertia sphere(const Sphere& s, double rho) {
  const double m = rho * 4.0 / 3.0 * kPi * std::pow(s.radius, 3);
  const double i = 0.4 * m * s.radius * s.radius;
  return diagonal(m, i, i, i);
}

SpatialInertia box(const Box& b, double rho) {
  const Eigen::Vector3d h = b.halfExtents, h2 = h.cwiseProduct(h);
  const double m = rho * 8.0 * h.prod();
  return diagonal(m, m * (h2.y() + h2.z()) / 3.0, m * (h2.x() + h2.z()) / 3.0,
                  m * (h2.x() + h2.y()) / 3.0);
}

SpatialInertia cylinder(double r, double h, double rho) {
  const double m = rho * kPi * r * r * 2.0 * h;
  const double transverse = m * (r * r / 4.0 + h * h / 3.0);  // m (3r^2 + L^2) / 12, L = 2h
  return diagonal(m, transverse, transverse, 0.5 * m * r * r);
}

SpatialInertia capsule(const Capsule& c, double rho) {
  const double r = c.radius, h = c.halfLength;
  const SpatialInertia tube = cylinder(r, h, rho);
  const double ms = rho * 4.0 / 3.0 * kPi * r * r * r;  // both hemispheres
  // Each hemisphere: I about its flat-face centre is (2/5)(ms/2) r^2, its COM sits 3r/8 from the
  // face; moving the axis to the capsule centre adds (ms/2)(h^2 + 2 h 3r/8).
  const double transverse = ms * (0.4 * r * r + h * h + 0.75 * h * r);
  const double axial = 0.4 * ms * r * r;
  return diagonal(tube.mass + ms, tube.inertiaAboutCom(0, 0) + transverse,
                  tube.inertiaAboutCom(1, 1) + transverse, tube.inertiaAboutCom(2, 2) + axial);
}

// Eberly (2002), "Subexpressions": f1 = sum w, f2 = sum of degree-2 monomials, f3 = degree 3,
// g_i = f2 + w_i (f1 + w_i).
struct Sub {
  double f1, f2, f3, g0, g1, g2;
};
Sub subexpressions(double w0, double w1, double w2) {
  const double t0 = w0 + w1, t1 = w0 * w0, t2 = t1 + w1 * t0;
  Sub s{};
  s.f1 = t0 + w2;
  s.f2 = t2 + w2 * s.f1;
  s.f3 = w0 * t1 + w1 * t2 + w2 * s.f2;
  s.g0 = s.f2 + w0 * (s.f1 + w0);
  s.g1 = s.f2 + w1 * (s.f1 + w1);
  s.g2 = s.f2 + w2 * (s.f1 + w2);
  return s;
}

}  // namespace

SpatialInertia polyhedronMassProperties(const std::vector<Eigen::Vector3d>& vertices,
                                        const std::vector<Eigen::Vector3i>& triangles,
                                        double density) {
  // Integrals of 1, x, y, z, x^2, y^2, z^2, xy, yz, zx over the solid (Eberly 2002, Compute()).
  double intg[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  // Shift to a point near the solid to reduce cancellation for meshes far from the origin.
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  for (const auto& v : vertices) origin += v;
  if (!vertices.empty()) origin /= static_cast<double>(vertices.size());
  for (const Eigen::Vector3i& t : triangles) {
    const Eigen::Vector3d p0 = vertices[t[0]] - origin, p1 = vertices[t[1]] - origin,
                          p2 = vertices[t[2]] - origin;
    const Eigen::Vector3d d = (p1 - p0).cross(p2 - p0);  // (d0, d1, d2) of Eberly
    const Sub x = subexpressions(p0.x(), p1.x(), p2.x());
    const Sub y = subexpressions(p0.y(), p1.y(), p2.y());
    const Sub z = subexpressions(p0.z(), p1.z(), p2.z());
    intg[0] += d.x() * x.f1;
    intg[1] += d.x() * x.f2;
    intg[2] += d.y() * y.f2;
    intg[3] += d.z() * z.f2;
    intg[4] += d.x() * x.f3;
    intg[5] += d.y() * y.f3;
    intg[6] += d.z() * z.f3;
    intg[7] += d.x() * (p0.y() * x.g0 + p1.y() * x.g1 + p2.y() * x.g2);
    intg[8] += d.y() * (p0.z() * y.g0 + p1.z() * y.g1 + p2.z() * y.g2);
    intg[9] += d.z() * (p0.x() * z.g0 + p1.x() * z.g1 + p2.x() * z.g2);
  }
  constexpr double kMult[10] = {1.0 / 6,  1.0 / 24, 1.0 / 24,  1.0 / 24,  1.0 / 60,
                                1.0 / 60, 1.0 / 60, 1.0 / 120, 1.0 / 120, 1.0 / 120};
  for (int i = 0; i < 10; ++i) intg[i] *= kMult[i] * density;
  const double m = intg[0];
  if (m == 0.0) return {};
  const Eigen::Vector3d c(intg[1] / m, intg[2] / m, intg[3] / m);
  Eigen::Matrix3d inertia;
  inertia(0, 0) = intg[5] + intg[6] - m * (c.y() * c.y() + c.z() * c.z());
  inertia(1, 1) = intg[4] + intg[6] - m * (c.z() * c.z() + c.x() * c.x());
  inertia(2, 2) = intg[4] + intg[5] - m * (c.x() * c.x() + c.y() * c.y());
  inertia(0, 1) = inertia(1, 0) = -(intg[7] - m * c.x() * c.y());
  inertia(1, 2) = inertia(2, 1) = -(intg[8] - m * c.y() * c.z());
  inertia(0, 2) = inertia(2, 0) = -(intg[9] - m * c.z() * c.x());
  return {m, c + origin, inertia};
}

SpatialInertia computeMassProperties(const Shape& shape, double density) {
  if (!std::isfinite(density) || density <= 0.0)
    throw std::invalid_argument("density must be finite and > 0 (got " + std::to_string(density) +
                                ")");
  return std::visit(
      Overloaded{[&](const Sphere& s) { return sphere(s, density); },
                 [&](const Box& b) { return box(b, density); },
                 [&](const Capsule& c) { return capsule(c, density); },
                 [&](const Cylinder& c) { return cylinder(c.radius, c.halfLength, density); },
                 [](const Plane&) -> SpatialInertia {
                   throw std::invalid_argument(
                       "a plane is infinite and has no mass: only static bodies may carry one");
                 },
                 [&](const ConvexHull& h) {
                   if (h.triangles.empty())
                     throw std::invalid_argument(
                         "convex_hull has no faces: build it with makeConvexHull");
                   return polyhedronMassProperties(h.vertices, h.triangles, density);
                 },
                 [&](const TriangleMesh& m) {
                   return polyhedronMassProperties(m.vertices, m.triangles, density);
                 }},
      shape);
}

double shapeVolume(const Shape& shape) {
  if (std::holds_alternative<Plane>(shape)) return 0.0;
  return computeMassProperties(shape, 1.0).mass;
}

}  // namespace coulomb::geometry
