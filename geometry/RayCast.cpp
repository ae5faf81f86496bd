#include <coulomb/geometry/RayCast.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <variant>

namespace coulomb::geometry {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kParallel = 1e-12;  // |direction component| below which a ray is parallel

// Entry of a ray that starts outside a ball: the smaller root of |o + t d - c|^2 = R^2, t >= 0.
std::optional<double> enterBall(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                                const Eigen::Vector3d& centre, double radius) {
  const Eigen::Vector3d m = o - centre;
  const double b = m.dot(d), c = m.squaredNorm() - radius * radius;
  const double disc = b * b - c;
  if (disc < 0) return std::nullopt;
  const double t = -b - std::sqrt(disc);
  if (t < 0) return std::nullopt;
  return t;
}

// t interval [t0, t1] of the ray inside the infinite cylinder x^2 + y^2 <= R^2 (empty: false).
bool infiniteCylinder(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double radius, double& t0,
                      double& t1) {
  const double a = d.x() * d.x() + d.y() * d.y();
  const double b = o.x() * d.x() + o.y() * d.y();
  const double c = o.x() * o.x() + o.y() * o.y() - radius * radius;
  if (a < kParallel * kParallel) {  // parallel to the axis: inside everywhere or nowhere
    t0 = -kInf, t1 = kInf;
    return c <= 0;
  }
  const double disc = b * b - a * c;
  if (disc < 0) return false;
  const double root = std::sqrt(disc);
  t0 = (-b - root) / a, t1 = (-b + root) / a;
  return true;
}

struct LocalHit {
  double t = kInf;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // local frame
  bool inside = false;                                // the ray starts inside the solid
};

LocalHit sphere(const Sphere& s, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  LocalHit hit;
  if (o.squaredNorm() <= s.radius * s.radius) return hit.inside = true, hit;
  if (auto t = enterBall(o, d, Eigen::Vector3d::Zero(), s.radius))
    hit.t = *t, hit.normal = (o + *t * d) / s.radius;
  return hit;
}

LocalHit box(const Box& b, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  LocalHit hit;
  const Eigen::Vector3d& h = b.halfExtents;
  if ((o.cwiseAbs().array() <= h.array()).all()) return hit.inside = true, hit;
  double enter = -kInf, leave = kInf;
  int axis = -1;
  double side = 1.0;
  for (int i = 0; i < 3; ++i) {  // slabs (Kay-Kajiya)
    if (std::abs(d[i]) < kParallel) {
      if (std::abs(o[i]) > h[i]) return hit;
      continue;
    }
    double t1 = (-h[i] - o[i]) / d[i], t2 = (h[i] - o[i]) / d[i];
    if (t1 > t2) std::swap(t1, t2);
    if (t1 > enter) enter = t1, axis = i, side = d[i] > 0 ? -1.0 : 1.0;
    leave = std::min(leave, t2);
    if (enter > leave) return hit;
  }
  if (axis < 0 || enter < 0) return hit;
  hit.t = enter;
  hit.normal = side * Eigen::Vector3d::Unit(axis);
  return hit;
}

LocalHit capsule(const Capsule& c, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  LocalHit hit;
  const Eigen::Vector3d onAxis(0, 0, std::clamp(o.z(), -c.halfLength, c.halfLength));
  if ((o - onAxis).squaredNorm() <= c.radius * c.radius) return hit.inside = true, hit;
  // The capsule is the union of its side and two balls: the first entry into the union is the
  // first entry into any of them (the flat ends of the side lie inside the balls).
  double t0 = 0, t1 = 0;
  if (infiniteCylinder(o, d, c.radius, t0, t1) && t0 >= 0 && std::isfinite(t0) &&
      std::abs(o.z() + t0 * d.z()) <= c.halfLength) {
    const Eigen::Vector3d p = o + t0 * d;
    hit.t = t0, hit.normal = Eigen::Vector3d(p.x(), p.y(), 0) / c.radius;
  }
  for (double end : {-c.halfLength, c.halfLength}) {
    const Eigen::Vector3d centre(0, 0, end);
    if (auto t = enterBall(o, d, centre, c.radius); t && *t < hit.t)
      hit.t = *t, hit.normal = (o + *t * d - centre) / c.radius;
  }
  return hit;
}

LocalHit cylinder(const Cylinder& c, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  LocalHit hit;
  if (o.x() * o.x() + o.y() * o.y() <= c.radius * c.radius && std::abs(o.z()) <= c.halfLength)
    return hit.inside = true, hit;
  double t0 = 0, t1 = 0;
  if (!infiniteCylinder(o, d, c.radius, t0, t1)) return hit;
  double z0 = -kInf, z1 = kInf;
  if (std::abs(d.z()) < kParallel) {
    if (std::abs(o.z()) > c.halfLength) return hit;
  } else {
    z0 = (-c.halfLength - o.z()) / d.z(), z1 = (c.halfLength - o.z()) / d.z();
    if (z0 > z1) std::swap(z0, z1);
  }
  const double enter = std::max(t0, z0), leave = std::min(t1, z1);
  if (enter > leave || enter < 0 || !std::isfinite(enter)) return hit;
  hit.t = enter;
  if (z0 >= t0) {
    hit.normal = Eigen::Vector3d(0, 0, d.z() > 0 ? -1.0 : 1.0);
  } else {
    const Eigen::Vector3d p = o + enter * d;
    hit.normal = Eigen::Vector3d(p.x(), p.y(), 0) / c.radius;
  }
  return hit;
}

LocalHit plane(const Plane& p, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  LocalHit hit;
  const double norm = p.normal.norm();
  const Eigen::Vector3d n = p.normal / norm;
  const double above = n.dot(o) - p.offset / norm;
  if (above <= 0) return hit.inside = true, hit;
  const double along = n.dot(d);
  if (along >= -kParallel) return hit;
  hit.t = -above / along;
  hit.normal = n;
  return hit;
}

// Cyrus-Beck clipping against the face planes of the hull.
LocalHit hull(const ConvexHull& h, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  LocalHit hit;
  double enter = -kInf, leave = kInf;
  Eigen::Vector3d enterNormal = Eigen::Vector3d::UnitZ();
  bool outside = false;
  auto clip = [&](const Eigen::Vector3d& n, double offset) {
    const double gap = offset - n.dot(o);  // >= 0 on the inner side of this face
    const double along = n.dot(d);
    if (gap < 0) outside = true;
    if (std::abs(along) < kParallel) {
      if (gap < 0) enter = kInf;  // parallel and outside this face: no hit
      return;
    }
    const double t = gap / along;
    if (along < 0) {
      if (t > enter) enter = t, enterNormal = n;
    } else {
      leave = std::min(leave, t);
    }
  };
  if (!h.faces.empty()) {
    for (const HullFace& f : h.faces) clip(f.normal, f.offset);
  } else {
    for (const Eigen::Vector3i& tri : h.triangles) {
      const Eigen::Vector3d& a = h.vertices[tri[0]];
      Eigen::Vector3d n = (h.vertices[tri[1]] - a).cross(h.vertices[tri[2]] - a);
      if (n.norm() == 0) continue;
      n.normalize();
      clip(n, n.dot(a));
    }
  }
  if (!outside) return hit.inside = true, hit;
  if (enter > leave || enter < 0 || !std::isfinite(enter)) return hit;
  hit.t = enter, hit.normal = enterNormal;
  return hit;
}

// Moller-Trumbore on every triangle, from both sides.
LocalHit mesh(const TriangleMesh& m, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  LocalHit hit;
  for (const Eigen::Vector3i& tri : m.triangles) {
    const Eigen::Vector3d& a = m.vertices[tri[0]];
    const Eigen::Vector3d e1 = m.vertices[tri[1]] - a, e2 = m.vertices[tri[2]] - a;
    const Eigen::Vector3d p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-300) continue;
    const double inv = 1.0 / det;
    const Eigen::Vector3d s = o - a;
    const double u = s.dot(p) * inv;
    if (u < 0 || u > 1) continue;
    const Eigen::Vector3d qv = s.cross(e1);
    const double v = d.dot(qv) * inv;
    if (v < 0 || u + v > 1) continue;
    const double t = e2.dot(qv) * inv;
    if (t >= 0 && t < hit.t) hit.t = t, hit.normal = e1.cross(e2).normalized();
  }
  return hit;
}

}  // namespace

std::optional<RayShapeHit> rayCastShape(const Shape& shape, const Pose& shapePose,
                                        const Eigen::Vector3d& origin,
                                        const Eigen::Vector3d& direction, double maxDistance) {
  const Eigen::Quaterniond toLocal = shapePose.rotation.conjugate();
  const Eigen::Vector3d o = toLocal * (origin - shapePose.position);
  const Eigen::Vector3d d = toLocal * direction;
  const LocalHit hit = std::visit(
      [&](const auto& s) -> LocalHit {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, Sphere>)
          return sphere(s, o, d);
        else if constexpr (std::is_same_v<T, Box>)
          return box(s, o, d);
        else if constexpr (std::is_same_v<T, Capsule>)
          return capsule(s, o, d);
        else if constexpr (std::is_same_v<T, Cylinder>)
          return cylinder(s, o, d);
        else if constexpr (std::is_same_v<T, Plane>)
          return plane(s, o, d);
        else if constexpr (std::is_same_v<T, ConvexHull>)
          return hull(s, o, d);
        else
          return mesh(s, o, d);
      },
      shape);
  if (hit.inside) return RayShapeHit{0.0, -direction};
  if (!(hit.t <= maxDistance)) return std::nullopt;
  return RayShapeHit{hit.t, shapePose.rotation * hit.normal};
}

Eigen::Vector3d supportPoint(const Shape& shape, const Eigen::Vector3d& direction) {
  const double length = direction.norm();
  const Eigen::Vector3d u =
      length > 0 ? Eigen::Vector3d(direction / length) : Eigen::Vector3d::UnitZ();
  auto farthest = [&u](const std::vector<Eigen::Vector3d>& points) {
    Eigen::Vector3d best = points.front();
    for (const Eigen::Vector3d& p : points)
      if (p.dot(u) > best.dot(u)) best = p;
    return best;
  };
  return std::visit(
      [&](const auto& s) -> Eigen::Vector3d {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, Sphere>) {
          return s.radius * u;
        } else if constexpr (std::is_same_v<T, Box>) {
          return s.halfExtents.cwiseProduct(
              u.unaryExpr([](double x) { return x < 0 ? -1.0 : 1.0; }));
        } else if constexpr (std::is_same_v<T, Capsule>) {
          return Eigen::Vector3d(0, 0, u.z() < 0 ? -s.halfLength : s.halfLength) + s.radius * u;
        } else if constexpr (std::is_same_v<T, Cylinder>) {
          const double across = std::hypot(u.x(), u.y());
          Eigen::Vector3d p(0, 0, u.z() < 0 ? -s.halfLength : s.halfLength);
          if (across > 0) p.x() = s.radius * u.x() / across, p.y() = s.radius * u.y() / across;
          return p;
        } else if constexpr (std::is_same_v<T, Plane>) {
          throw std::invalid_argument("supportPoint: a plane is unbounded");
        } else {
          return farthest(s.vertices);
        }
      },
      shape);
}

}  // namespace coulomb::geometry
