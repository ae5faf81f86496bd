#include <coulomb/geometry/PrimitiveContacts.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace coulomb::geometry {
namespace {

constexpr double kTiny = 1e-12;

// Two balls (centres ca, cb, radii ra, rb) give one point; `fallback` is the normal used when
// the centres coincide (no direction is defined there).
bool ballBall(const Eigen::Vector3d& ca, double ra, const Eigen::Vector3d& cb, double rb,
              const Eigen::Vector3d& fallback, double margin, PairContact& out) {
  const Eigen::Vector3d d = cb - ca;
  const double dist = d.norm();
  const double gap = dist - ra - rb;
  if (gap > margin) return false;
  out.normal = dist > kTiny ? Eigen::Vector3d(d / dist) : fallback;
  const Eigen::Vector3d onA = ca + ra * out.normal, onB = cb - rb * out.normal;
  out.points.push_back({0.5 * (onA + onB), -gap, 0});
  return true;
}

Eigen::Vector3d capsuleEnd(const Capsule& c, const Pose& p, double sign) {
  return p.apply(Eigen::Vector3d(0.0, 0.0, sign * c.halfLength));
}

}  // namespace

WorldPlane toWorld(const Plane& plane, const Pose& pose) {
  const double norm = plane.normal.norm();
  const Eigen::Vector3d n = plane.normal / norm;
  WorldPlane w;
  w.normal = (pose.rotation * n).normalized();
  w.offset = w.normal.dot(pose.apply(n * (plane.offset / norm)));
  return w;
}

void closestSegmentPoints(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1,
                          const Eigen::Vector3d& p2, const Eigen::Vector3d& q2, Eigen::Vector3d& c1,
                          Eigen::Vector3d& c2) {
  const Eigen::Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  if (a <= kTiny && e <= kTiny) {
    s = t = 0.0;
  } else if (a <= kTiny) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= kTiny) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > kTiny * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  c1 = p1 + s * d1;
  c2 = p2 + t * d2;
}

bool planePoints(const WorldPlane& plane, std::span<const Eigen::Vector3d> points, double radius,
                 double margin, PairContact& out) {
  out.normal = plane.normal;
  bool any = false;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double gap = plane.normal.dot(points[i]) - plane.offset - radius;
    if (gap > margin) continue;
    const Eigen::Vector3d position = points[i] - plane.normal * (radius + 0.5 * gap);
    out.points.push_back({position, -gap, static_cast<std::uint32_t>(i)});
    any = true;
  }
  return any;
}

std::array<Eigen::Vector3d, 8> boxCorners(const Box& box, const Pose& pose) {
  std::array<Eigen::Vector3d, 8> corners;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d sign((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
    corners[static_cast<std::size_t>(i)] = pose.apply(sign.cwiseProduct(box.halfExtents));
  }
  return corners;
}

bool planeCylinder(const WorldPlane& plane, const Cylinder& cylinder, const Pose& pose,
                   double margin, PairContact& out) {
  const Eigen::Matrix3d r = pose.rotationMatrix();
  const Eigen::Vector3d axis = r.col(2);
  // Direction of the deepest rim point: minus the normal's component across the axis.
  Eigen::Vector3d down = -(plane.normal - plane.normal.dot(axis) * axis);
  const bool tilted = down.norm() > 1e-3;  // below ~0.06 deg the 8 rim points are exact enough
  if (tilted) down.normalize();
  std::array<Eigen::Vector3d, 18> rim;
  std::array<std::uint32_t, 18> ids;
  std::size_t count = 0;
  for (int cap = 0; cap < 2; ++cap) {
    const Eigen::Vector3d centre = pose.position + (cap ? 1.0 : -1.0) * cylinder.halfLength * axis;
    const Eigen::Vector3d deepest = centre + cylinder.radius * down;
    for (int k = 0; k < 8; ++k) {
      const double angle = k * std::numbers::pi / 4.0;
      const Eigen::Vector3d p =
          centre + cylinder.radius * (std::cos(angle) * r.col(0) + std::sin(angle) * r.col(1));
      if (tilted && (p - deepest).norm() < 1e-9 * cylinder.radius) continue;  // no duplicates
      rim[count] = p;
      ids[count++] = static_cast<std::uint32_t>(cap * 16 + k);
    }
    if (tilted) {
      rim[count] = deepest;
      ids[count++] = static_cast<std::uint32_t>(cap * 16 + 8);
    }
  }
  PairContact scratch;
  planePoints(plane, std::span(rim.data(), count), 0.0, margin, scratch);
  out.normal = plane.normal;
  for (ContactCandidate& c : scratch.points) {
    c.featureId = ids[c.featureId];
    out.points.push_back(c);
  }
  return !scratch.points.empty();
}

bool sphereSphere(const Sphere& a, const Pose& pa, const Sphere& b, const Pose& pb, double margin,
                  PairContact& out) {
  return ballBall(pa.position, a.radius, pb.position, b.radius, Eigen::Vector3d::UnitZ(), margin,
                  out);
}

bool sphereBox(const Sphere& a, const Pose& pa, const Box& b, const Pose& pb, double margin,
               PairContact& out) {
  const Eigen::Vector3d q = pb.applyInverse(pa.position);  // sphere centre in the box frame
  const Eigen::Vector3d& h = b.halfExtents;
  const Eigen::Vector3d closest = q.cwiseMax(-h).cwiseMin(h);
  const Eigen::Vector3d d = q - closest;
  const double dist = d.norm();
  if (dist > kTiny) {  // centre outside the box
    const double gap = dist - a.radius;
    if (gap > margin) return false;
    const Eigen::Vector3d nBoxToSphere = pb.rotation * (d / dist);
    out.normal = -nBoxToSphere;
    const Eigen::Vector3d onBox = pb.apply(closest);
    const Eigen::Vector3d onSphere = pa.position - a.radius * nBoxToSphere;
    out.points.push_back({0.5 * (onBox + onSphere), -gap, 0});
    return true;
  }
  // Centre inside: leave through the nearest face.
  int axis = 0;
  double least = h[0] - std::abs(q[0]);
  for (int i = 1; i < 3; ++i)
    if (h[i] - std::abs(q[i]) < least) least = h[i] - std::abs(q[i]), axis = i;
  Eigen::Vector3d local = Eigen::Vector3d::Zero();
  local[axis] = q[axis] >= 0.0 ? 1.0 : -1.0;
  const Eigen::Vector3d nBoxToSphere = pb.rotation * local;
  out.normal = -nBoxToSphere;
  const Eigen::Vector3d onBox = pa.position + least * nBoxToSphere;
  const Eigen::Vector3d onSphere = pa.position - a.radius * nBoxToSphere;
  out.points.push_back({0.5 * (onBox + onSphere), least + a.radius, 0});
  return true;
}

bool sphereCapsule(const Sphere& a, const Pose& pa, const Capsule& b, const Pose& pb, double margin,
                   PairContact& out) {
  Eigen::Vector3d onAxis, centre;
  closestSegmentPoints(pa.position, pa.position, capsuleEnd(b, pb, -1.0), capsuleEnd(b, pb, 1.0),
                       centre, onAxis);
  // On the axis the direction is undefined: use the capsule's local x axis, a fixed choice.
  return ballBall(pa.position, a.radius, onAxis, b.radius, pb.rotation * Eigen::Vector3d::UnitX(),
                  margin, out);
}

bool sphereCylinder(const Sphere& a, const Pose& pa, const Cylinder& b, const Pose& pb,
                    double margin, PairContact& out) {
  const Eigen::Vector3d q = pb.applyInverse(pa.position);
  const double rho = std::hypot(q.x(), q.y());
  const Eigen::Vector3d radial =
      rho > kTiny ? Eigen::Vector3d(q.x() / rho, q.y() / rho, 0.0) : Eigen::Vector3d::UnitX();
  if (std::abs(q.z()) <= b.halfLength && rho <= b.radius) {  // centre inside the cylinder
    const double axial = b.halfLength - std::abs(q.z()), across = b.radius - rho;
    const Eigen::Vector3d local =
        axial <= across ? Eigen::Vector3d(0.0, 0.0, q.z() >= 0.0 ? 1.0 : -1.0) : radial;
    const double least = std::min(axial, across);
    const Eigen::Vector3d nCylToSphere = pb.rotation * local;
    out.normal = -nCylToSphere;
    const Eigen::Vector3d onCyl = pa.position + least * nCylToSphere;
    const Eigen::Vector3d onSphere = pa.position - a.radius * nCylToSphere;
    out.points.push_back({0.5 * (onCyl + onSphere), least + a.radius, 0});
    return true;
  }
  const Eigen::Vector3d closest(radial.x() * std::min(rho, b.radius),
                                radial.y() * std::min(rho, b.radius),
                                std::clamp(q.z(), -b.halfLength, b.halfLength));
  const Eigen::Vector3d d = q - closest;
  const double dist = d.norm();
  const double gap = dist - a.radius;
  if (gap > margin) return false;
  const Eigen::Vector3d nCylToSphere = pb.rotation * (d / dist);
  out.normal = -nCylToSphere;
  const Eigen::Vector3d onCyl = pb.apply(closest);
  const Eigen::Vector3d onSphere = pa.position - a.radius * nCylToSphere;
  out.points.push_back({0.5 * (onCyl + onSphere), -gap, 0});
  return true;
}

bool capsuleCapsule(const Capsule& a, const Pose& pa, const Capsule& b, const Pose& pb,
                    double margin, PairContact& out) {
  const Eigen::Vector3d a0 = capsuleEnd(a, pa, -1.0), a1 = capsuleEnd(a, pa, 1.0);
  const Eigen::Vector3d b0 = capsuleEnd(b, pb, -1.0), b1 = capsuleEnd(b, pb, 1.0);
  Eigen::Vector3d ca, cb;
  closestSegmentPoints(a0, a1, b0, b1, ca, cb);
  const Eigen::Vector3d d = cb - ca;
  const double dist = d.norm();
  if (dist - a.radius - b.radius > margin) return false;
  const Eigen::Vector3d da = a1 - a0, db = b1 - b0;
  Eigen::Vector3d n;
  if (dist > kTiny) {
    n = d / dist;
  } else {  // axes intersect: the common perpendicular, else a fixed direction across a
    const Eigen::Vector3d cross = da.cross(db);
    n = cross.norm() > kTiny ? Eigen::Vector3d(cross.normalized())
                             : Eigen::Vector3d(pa.rotation * Eigen::Vector3d::UnitX());
    if (n.dot(pb.position - pa.position) < 0.0) n = -n;
  }
  out.normal = n;
  auto addPoint = [&](const Eigen::Vector3d& onAxisA, const Eigen::Vector3d& onAxisB,
                      std::uint32_t id) {
    const double gap = n.dot(onAxisB - onAxisA) - a.radius - b.radius;
    if (gap > margin) return;
    const Eigen::Vector3d position = 0.5 * (onAxisA + a.radius * n + onAxisB - b.radius * n);
    out.points.push_back({position, -gap, id});
  };
  const double la = da.norm(), lb = db.norm();
  const bool parallel = la > kTiny && lb > kTiny && da.cross(db).norm() <= 1e-3 * la * lb;
  if (parallel) {  // clip b's projection to a's segment: the overlap interval's two ends
    const double t0 = (b0 - a0).dot(da) / (la * la), t1 = (b1 - a0).dot(da) / (la * la);
    const double lo = std::max(0.0, std::min(t0, t1)), hi = std::min(1.0, std::max(t0, t1));
    if ((hi - lo) * la > 1e-9) {
      for (int k = 0; k < 2; ++k) {
        const Eigen::Vector3d onA = a0 + (k ? hi : lo) * da;
        Eigen::Vector3d unused, onB;
        closestSegmentPoints(onA, onA, b0, b1, unused, onB);
        addPoint(onA, onB, static_cast<std::uint32_t>(k));
      }
      return !out.points.empty();
    }
  }
  addPoint(ca, cb, 2);
  return !out.points.empty();
}

}  // namespace coulomb::geometry
