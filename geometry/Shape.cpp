#include <coulomb/geometry/MassProperties.hpp>
#include <coulomb/geometry/Shape.hpp>

#include <cmath>
#include <map>
#include <sstream>
#include <utility>

namespace coulomb::geometry {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// clang before 17 lacks C++20 aggregate deduction (P1816): the C++17 guide keeps it compiling.
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

bool positiveFinite(double x) {
  return std::isfinite(x) && x > 0.0;
}

std::optional<std::string> positive(const char* what, double value) {
  if (positiveFinite(value)) return std::nullopt;
  std::ostringstream out;
  out << what << " must be finite and > 0 (got " << value << ")";
  return out.str();
}

double boundingBoxDiagonal(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d lo = points.front(), hi = points.front();
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

// The points must span 3D: pick the farthest pair, the point farthest from that line, then the
// point farthest from that plane; each distance is compared with the cloud's extent.
std::optional<std::string> checkSpansVolume(const std::vector<Eigen::Vector3d>& points) {
  const double extent = boundingBoxDiagonal(points);
  const double tolerance = 1e-9 * extent;
  const Eigen::Vector3d a = points.front();
  Eigen::Vector3d b = a;
  for (const auto& p : points)
    if ((p - a).squaredNorm() > (b - a).squaredNorm()) b = p;
  if ((b - a).norm() <= tolerance) return "convex_hull points all coincide";
  const Eigen::Vector3d direction = (b - a).normalized();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double farthest = 0.0;
  for (const auto& p : points) {
    const Eigen::Vector3d offset = (p - a) - direction * direction.dot(p - a);
    if (offset.norm() > farthest) {
      farthest = offset.norm();
      normal = direction.cross(offset).normalized();
    }
  }
  if (farthest <= tolerance) return "convex_hull points are collinear (no volume)";
  double height = 0.0;
  for (const auto& p : points) height = std::max(height, std::abs(normal.dot(p - a)));
  if (height <= tolerance) return "convex_hull points are coplanar (no volume)";
  return std::nullopt;
}

// Closed and consistently oriented: every directed edge (a, b) occurs exactly once and its twin
// (b, a) occurs exactly once, so each edge joins two triangles that traverse it oppositely.
std::optional<std::string> checkClosedAndOriented(const std::vector<Eigen::Vector3i>& triangles) {
  std::map<std::pair<int, int>, int> directedEdges;
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) ++directedEdges[{t[k], t[(k + 1) % 3]}];
  for (const auto& [edge, count] : directedEdges) {
    const std::string name =
        "edge (" + std::to_string(edge.first) + ", " + std::to_string(edge.second) + ")";
    if (count > 1)
      return "mesh is not consistently oriented (or not manifold): " + name + " is traversed " +
             std::to_string(count) + " times in the same direction";
    if (directedEdges.find({edge.second, edge.first}) == directedEdges.end())
      return "mesh is not closed: " + name + " belongs to only one triangle";
  }
  return std::nullopt;
}

}  // namespace

const char* shapeKindName(const Shape& shape) {
  return std::visit(
      Overloaded{[](const Sphere&) { return "sphere"; }, [](const Box&) { return "box"; },
                 [](const Capsule&) { return "capsule"; },
                 [](const Cylinder&) { return "cylinder"; }, [](const Plane&) { return "plane"; },
                 [](const ConvexHull&) { return "convex_hull"; },
                 [](const TriangleMesh&) { return "mesh"; }},
      shape);
}

std::optional<std::string> validateShape(const Shape& shape) {
  return std::visit(
      Overloaded{
          [](const Sphere& s) { return positive("sphere radius", s.radius); },
          [](const Box& b) -> std::optional<std::string> {
            const char* names[] = {"box half_extents[0]", "box half_extents[1]",
                                   "box half_extents[2]"};
            for (int i = 0; i < 3; ++i)
              if (auto e = positive(names[i], b.halfExtents[i])) return e;
            return std::nullopt;
          },
          [](const Capsule& c) -> std::optional<std::string> {
            if (auto e = positive("capsule radius", c.radius)) return e;
            if (!std::isfinite(c.halfLength) || c.halfLength < 0.0)
              return "capsule half_length must be finite and >= 0";
            return std::nullopt;
          },
          [](const Cylinder& c) -> std::optional<std::string> {
            if (auto e = positive("cylinder radius", c.radius)) return e;
            return positive("cylinder half_length", c.halfLength);
          },
          [](const Plane& p) -> std::optional<std::string> {
            if (!p.normal.allFinite() || !std::isfinite(p.offset))
              return "plane normal and offset must be finite";
            if (p.normal.norm() < 1e-12) return "plane normal must be non-zero";
            return std::nullopt;
          },
          [](const ConvexHull& h) -> std::optional<std::string> {
            if (h.vertices.size() < 4) return "convex_hull needs at least 4 points";
            for (std::size_t i = 0; i < h.vertices.size(); ++i)
              if (!h.vertices[i].allFinite())
                return "convex_hull point " + std::to_string(i) + " is not finite";
            // Given triangles (a hull built by hand) are read by the contact queries as they are.
            const auto n = static_cast<int>(h.vertices.size());
            for (std::size_t t = 0; t < h.triangles.size(); ++t)
              if (h.triangles[t].minCoeff() < 0 || h.triangles[t].maxCoeff() >= n)
                return "convex_hull triangle " + std::to_string(t) +
                       " refers to a point outside [0, " + std::to_string(n) + ")";
            return checkSpansVolume(h.vertices);
          },
          [](const TriangleMesh& m) -> std::optional<std::string> {
            if (m.vertices.size() < 4 || m.triangles.size() < 4)
              return "mesh needs at least 4 vertices and 4 triangles (a closed surface)";
            for (const auto& v : m.vertices)
              if (!v.allFinite()) return "mesh has a non-finite vertex";
            const int n = static_cast<int>(m.vertices.size());
            for (std::size_t i = 0; i < m.triangles.size(); ++i) {
              const Eigen::Vector3i& t = m.triangles[i];
              if (t.minCoeff() < 0 || t.maxCoeff() >= n)
                return "mesh triangle " + std::to_string(i) + " has a vertex index out of range";
              if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
                return "mesh triangle " + std::to_string(i) + " repeats a vertex";
            }
            if (auto e = checkClosedAndOriented(m.triangles)) return e;
            const double volume = polyhedronMassProperties(m.vertices, m.triangles, 1.0).mass;
            const double extent = boundingBoxDiagonal(m.vertices);
            if (std::abs(volume) <= 1e-12 * extent * extent * extent)
              return "mesh encloses no volume (got " + std::to_string(volume) + " m^3)";
            if (volume < 0.0)
              return "mesh triangles face inward (volume " + std::to_string(volume) +
                     " m^3): reverse their vertex order";
            return std::nullopt;
          }},
      shape);
}

}  // namespace coulomb::geometry
