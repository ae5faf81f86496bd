#include "ShapeMesh.hpp"

#include <coulomb/geometry/ContactManifold.hpp>
#include <coulomb/meshes/MakeConvexHull.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>
#include <variant>

namespace coulomb::viewer {
namespace {

void addVertex(Mesh& mesh, const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
  mesh.positions.insert(mesh.positions.end(), {static_cast<float>(p.x()), static_cast<float>(p.y()),
                                               static_cast<float>(p.z())});
  mesh.normals.insert(mesh.normals.end(), {static_cast<float>(n.x()), static_cast<float>(n.y()),
                                           static_cast<float>(n.z())});
}

void addFlatTriangle(Mesh& mesh, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                     const Eigen::Vector3d& c) {
  const Eigen::Vector3d cross = (b - a).cross(c - a);
  const double norm = cross.norm();
  if (norm <= 0.0 || !std::isfinite(norm)) return;  // degenerate: nothing to see
  const Eigen::Vector3d n = cross / norm;
  addVertex(mesh, a, n);
  addVertex(mesh, b, n);
  addVertex(mesh, c, n);
}

/// A point of a profile in the (radius, z) half-plane, with its outward normal there.
struct ProfilePoint {
  double r, z, nr, nz;
};

/// Revolves profile segments (consecutive pairs of `profile`) about z. Pairs marked by a jump
/// in the normal are separate segments, so cylinders keep sharp rims.
void lathe(Mesh& mesh, const std::vector<ProfilePoint>& profile, int slices) {
  const double step = 2.0 * std::numbers::pi / slices;
  for (std::size_t k = 0; k + 1 < profile.size(); ++k) {
    const ProfilePoint& a = profile[k];
    const ProfilePoint& b = profile[k + 1];
    if (a.r == b.r && a.z == b.z) continue;  // a rim: the normal changes, not the point
    for (int s = 0; s < slices; ++s) {
      const double c0 = std::cos(s * step), s0 = std::sin(s * step);
      const double c1 = std::cos((s + 1) * step), s1 = std::sin((s + 1) * step);
      auto point = [](const ProfilePoint& p, double c, double sn) {
        return Eigen::Vector3d(p.r * c, p.r * sn, p.z);
      };
      auto normal = [](const ProfilePoint& p, double c, double sn) {
        return Eigen::Vector3d(p.nr * c, p.nr * sn, p.nz);
      };
      // Quad (a0, a1, b1, b0), counter-clockwise seen from outside when a is below b.
      if (a.r > 0.0) {
        addVertex(mesh, point(a, c0, s0), normal(a, c0, s0));
        addVertex(mesh, point(a, c1, s1), normal(a, c1, s1));
        addVertex(mesh, point(b, c1, s1), normal(b, c1, s1));
      }
      if (b.r > 0.0) {
        addVertex(mesh, point(a, c0, s0), normal(a, c0, s0));
        addVertex(mesh, point(b, c1, s1), normal(b, c1, s1));
        addVertex(mesh, point(b, c0, s0), normal(b, c0, s0));
      }
    }
  }
}

/// Quarter or half circle of radius r centred at height zc, from angle a0 to a1 (measured from
/// the xy plane towards +z), as profile points with radial normals.
void arc(std::vector<ProfilePoint>& profile, double r, double zc, double a0, double a1, int n) {
  for (int i = 0; i <= n; ++i) {
    const double a = a0 + (a1 - a0) * i / n;
    const double cosine = std::cos(a);
    const double c = std::abs(cosine) < 1e-12 ? 0.0 : cosine;  // exact 0 at the poles: no slivers
    profile.push_back({r * c, zc + r * std::sin(a), c, std::sin(a)});
  }
}

void meshBox(Mesh& mesh, const Eigen::Vector3d& h) {
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign = -1; sign <= 1; sign += 2) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      auto corner = [&](double su, double sv) {
        Eigen::Vector3d p;
        p[axis] = sign * h[axis];
        p[u] = su * h[u];
        p[v] = sv * h[v];
        return p;
      };
      // (u, v, axis) is right-handed, so (-,-) (+,-) (+,+) is counter-clockwise seen from +axis.
      const Eigen::Vector3d a = corner(-1, -1), b = corner(1, -1), c = corner(1, 1),
                            d = corner(-1, 1);
      if (sign > 0) {
        addFlatTriangle(mesh, a, b, c);
        addFlatTriangle(mesh, a, c, d);
      } else {
        addFlatTriangle(mesh, a, c, b);
        addFlatTriangle(mesh, a, d, c);
      }
    }
  }
}

void meshTriangles(Mesh& mesh, const std::vector<Eigen::Vector3d>& vertices,
                   const std::vector<Eigen::Vector3i>& triangles) {
  const int n = static_cast<int>(vertices.size());
  for (const Eigen::Vector3i& t : triangles) {
    if ((t.array() < 0).any() || (t.array() >= n).any()) continue;  // validated shapes never do
    addFlatTriangle(mesh, vertices[t[0]], vertices[t[1]], vertices[t[2]]);
  }
}

void meshPlane(Mesh& mesh, const geometry::Plane& plane, double half) {
  const Eigen::Vector3d n = plane.normal.normalized();
  Eigen::Vector3d t1, t2;
  geometry::makeTangentFrame(n, t1, t2);  // n x t1 = t2: (t1, t2) counter-clockwise about n
  const Eigen::Vector3d c = plane.offset * n;
  addFlatTriangle(mesh, c + half * (-t1 - t2), c + half * (t1 - t2), c + half * (t1 + t2));
  addFlatTriangle(mesh, c + half * (-t1 - t2), c + half * (t1 + t2), c + half * (-t1 + t2));
}

}  // namespace

Mesh meshShape(const geometry::Shape& shape, const MeshDetail& detail) {
  Mesh mesh;
  const int slices = std::max(3, detail.slices);
  const int stacks = std::max(2, detail.stacks);
  const double pi = std::numbers::pi;
  std::visit(
      [&](const auto& s) {
        using T = std::decay_t<decltype(s)>;
        std::vector<ProfilePoint> profile;
        if constexpr (std::is_same_v<T, geometry::Sphere>) {
          arc(profile, s.radius, 0.0, -0.5 * pi, 0.5 * pi, stacks);
          lathe(mesh, profile, slices);
        } else if constexpr (std::is_same_v<T, geometry::Capsule>) {
          const int half = std::max(1, stacks / 2);
          arc(profile, s.radius, -s.halfLength, -0.5 * pi, 0.0, half);
          arc(profile, s.radius, s.halfLength, 0.0, 0.5 * pi, half);  // the band joins the caps
          lathe(mesh, profile, slices);
        } else if constexpr (std::is_same_v<T, geometry::Cylinder>) {
          const double r = s.radius, h = s.halfLength;
          profile = {{0.0, -h, 0.0, -1.0}, {r, -h, 0.0, -1.0}, {r, -h, 1.0, 0.0},
                     {r, h, 1.0, 0.0},     {r, h, 0.0, 1.0},   {0.0, h, 0.0, 1.0}};
          lathe(mesh, profile, slices);
        } else if constexpr (std::is_same_v<T, geometry::Box>) {
          meshBox(mesh, s.halfExtents);
        } else if constexpr (std::is_same_v<T, geometry::Plane>) {
          meshPlane(mesh, s, detail.planeHalfSize);
        } else if constexpr (std::is_same_v<T, geometry::ConvexHull>) {
          if (!s.triangles.empty()) {
            meshTriangles(mesh, s.vertices, s.triangles);
          } else {
            try {
              const geometry::ConvexHull hull = geometry::makeConvexHull(s.vertices);
              meshTriangles(mesh, hull.vertices, hull.triangles);
            } catch (const std::invalid_argument&) {
              // not a valid hull: nothing to draw (a World never holds one)
            }
          }
        } else if constexpr (std::is_same_v<T, geometry::TriangleMesh>) {
          meshTriangles(mesh, s.vertices, s.triangles);
        }
      },
      shape);
  return mesh;
}

}  // namespace coulomb::viewer
