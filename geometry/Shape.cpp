#include <coulomb/geometry/Shape.hpp>

#include <cmath>
#include <sstream>

namespace coulomb::geometry {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};

bool positiveFinite(double x) { return std::isfinite(x) && x > 0.0; }

std::optional<std::string> positive(const char* what, double value) {
  if (positiveFinite(value)) return std::nullopt;
  std::ostringstream out;
  out << what << " must be finite and > 0 (got " << value << ")";
  return out.str();
}

}  // namespace

const char* shapeKindName(const Shape& shape) {
  return std::visit(Overloaded{[](const Sphere&) { return "sphere"; },
                               [](const Box&) { return "box"; },
                               [](const Capsule&) { return "capsule"; },
                               [](const Cylinder&) { return "cylinder"; },
                               [](const Plane&) { return "plane"; },
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
            for (const auto& v : h.vertices)
              if (!v.allFinite()) return "convex_hull has a non-finite point";
            return std::nullopt;
          },
          [](const TriangleMesh& m) -> std::optional<std::string> {
            if (m.vertices.size() < 4 || m.triangles.size() < 4)
              return "mesh needs at least 4 vertices and 4 triangles (a closed surface)";
            for (const auto& v : m.vertices)
              if (!v.allFinite()) return "mesh has a non-finite vertex";
            const int n = static_cast<int>(m.vertices.size());
            for (const auto& t : m.triangles)
              if (t.minCoeff() < 0 || t.maxCoeff() >= n) return "mesh triangle index out of range";
            return std::nullopt;
          }},
      shape);
}

}  // namespace coulomb::geometry
