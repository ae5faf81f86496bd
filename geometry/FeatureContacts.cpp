#include <coulomb/geometry/FeatureContacts.hpp>

#include <coulomb/geometry/HullContacts.hpp>
#include <coulomb/geometry/PrimitiveContacts.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace coulomb::geometry {
namespace {

// Face normals and cylinder axes within ~18 degrees of FCL's normal are tried as the normal.
constexpr double kSnapCos = 0.95;
// [m] A tried axis wins against FCL's normal unless FCL's separates the shapes by more than this
// (MPR's depth is good to ~5e-7 m at shallow depths, docs/fcl-notes.md section 3).
constexpr double kSnapTolerance = 1e-6;
// A cylinder is supported by a cap when its axis is within 45 degrees of the direction.
constexpr double kCapCos = std::numbers::sqrt2 / 2.0;
// A polygon is a reference only within 60 degrees of the normal (projection along the normal
// onto its plane stays well conditioned).
constexpr double kMinAlignment = 0.5;
// Segments closer to parallel than ~0.6 degrees touch along their overlap.
constexpr double kParallelSin = 1e-2;
// Side planes pushed out by this fraction of the reference's inradius, as HullContacts does, so
// flush faces keep their corners (and ids) under tiny rotations.
constexpr double kClipSlop = 2e-3;
constexpr int kCapVertices = 8;
constexpr std::uint32_t kExactPointId = 0x7f;

enum Kind { kTriangle = -1, kSphere = 0, kBox, kCapsule, kCylinder, kPlane, kHull, kMesh };

// A part with its rotation and, for a hull, its world vertices and faces at hand.
struct Posed {
  const ConvexPart* part = nullptr;
  int kind = kTriangle;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  const std::vector<Eigen::Vector3d>* hullVertices = nullptr;  // world
  const ConvexHull* hull = nullptr;                            // with faces
};

Posed pose(const ConvexPart& part, std::vector<Eigen::Vector3d>& hullVertices,
           ConvexHull& faceless) {
  Posed p;
  p.part = &part;
  p.kind = part.shape ? static_cast<int>(part.shape->index()) : kTriangle;
  p.rotation = part.pose.rotationMatrix();
  if (p.kind == kHull) {
    const ConvexHull& hull = std::get<ConvexHull>(*part.shape);
    p.hull = &hull;
    if (hull.faces.empty()) {  // a hull made without makeConvexHull: its faces, once per query
      faceless.vertices = hull.vertices;
      faceless.triangles = hull.triangles;
      buildHullFaces(faceless);
      p.hull = &faceless;
    }
    hullVertices.resize(hull.vertices.size());
    for (std::size_t i = 0; i < hull.vertices.size(); ++i)
      hullVertices[i] = part.pose.apply(hull.vertices[i]);
    p.hullVertices = &hullVertices;
  }
  return p;
}

Eigen::Vector3d triangleNormal(const ConvexPart& part) {
  const auto& t = part.triangle;
  return (t[1] - t[0]).cross(t[2] - t[0]).normalized();
}

// Support function h(d) = max over the part of d.x.
double support(const Posed& p, const Eigen::Vector3d& d) {
  const Eigen::Vector3d& c = p.part->pose.position;
  switch (p.kind) {
    case kTriangle:
      return std::max(
          {d.dot(p.part->triangle[0]), d.dot(p.part->triangle[1]), d.dot(p.part->triangle[2])});
    case kSphere:
      return c.dot(d) + std::get<Sphere>(*p.part->shape).radius;
    case kBox: {
      const Eigen::Vector3d& e = std::get<Box>(*p.part->shape).halfExtents;
      return c.dot(d) + e[0] * std::abs(p.rotation.col(0).dot(d)) +
             e[1] * std::abs(p.rotation.col(1).dot(d)) + e[2] * std::abs(p.rotation.col(2).dot(d));
    }
    case kCapsule: {
      const Capsule& s = std::get<Capsule>(*p.part->shape);
      return c.dot(d) + s.halfLength * std::abs(p.rotation.col(2).dot(d)) + s.radius;
    }
    case kCylinder: {
      const Cylinder& s = std::get<Cylinder>(*p.part->shape);
      const double along = p.rotation.col(2).dot(d);
      return c.dot(d) + s.halfLength * std::abs(along) +
             s.radius * std::sqrt(std::max(0.0, 1.0 - along * along));
    }
    case kHull: {
      double best = -std::numeric_limits<double>::infinity();
      for (const Eigen::Vector3d& v : *p.hullVertices) best = std::max(best, d.dot(v));
      return best;
    }
    default:
      return std::numeric_limits<double>::quiet_NaN();  // planes and meshes are not parts
  }
}

double separation(const Posed& a, const Posed& b, const Eigen::Vector3d& d) {
  return -support(b, -d) - support(a, d);
}

// Calls `visit(axis)` for the axes of `p` that may be the contact normal: face normals of boxes,
// hulls and triangles and a cylinder's axis, signed by `sign` (+1: p is a, the normal leaves it;
// -1: p is b) and within kSnapCos of `guess`.
// Without a guess (zero: FCL found the shapes touching but gave no direction) every such axis.
template <typename Visit>
void candidateAxes(const Posed& p, double sign, const Eigen::Vector3d& guess, Visit&& visit) {
  const double cone = guess.isZero() ? -2.0 : kSnapCos;
  auto offer = [&](const Eigen::Vector3d& outward) {
    for (const double s : {1.0, -1.0}) {
      const Eigen::Vector3d axis = sign * s * outward;
      if (axis.dot(guess) > cone) visit(axis);
    }
  };
  switch (p.kind) {
    case kTriangle:
      offer(triangleNormal(*p.part));
      break;
    case kBox:
      for (int k = 0; k < 3; ++k) offer(p.rotation.col(k));
      break;
    case kCylinder:
      offer(p.rotation.col(2));
      break;
    case kHull:
      for (const HullFace& face : p.hull->faces) {
        const Eigen::Vector3d axis = sign * (p.rotation * face.normal);
        if (axis.dot(guess) > cone) visit(axis);
      }
      break;
    default:
      break;
  }
}

// The feature of `p` that supports it along the unit direction d.
void supportFeature(const Posed& p, const Eigen::Vector3d& d, SupportFeature& f) {
  f.points.clear();
  f.radius = 0.0;
  f.index = 0;
  f.exactExtra = false;
  f.discRadius = 0.0;
  const Eigen::Vector3d& c = p.part->pose.position;
  switch (p.kind) {
    case kTriangle: {
      const auto& t = p.part->triangle;
      const Eigen::Vector3d m = triangleNormal(*p.part);
      if (m.dot(d) >= 0.0) {
        f.points = {t[0], t[1], t[2]};
        f.normal = m;
      } else {  // the back side: the same loop reversed stays counter-clockwise about -m
        f.points = {t[0], t[2], t[1]};
        f.normal = -m;
        f.index = 1;
      }
      return;
    }
    case kSphere:
      f.points.push_back(c);
      f.radius = std::get<Sphere>(*p.part->shape).radius;
      return;
    case kBox: {
      const Eigen::Vector3d& e = std::get<Box>(*p.part->shape).halfExtents;
      int k = 0;
      double best = -1.0;
      for (int axis = 0; axis < 3; ++axis) {
        const double along = std::abs(p.rotation.col(axis).dot(d));
        if (along > best + 1e-12) best = along, k = axis;
      }
      const double s = p.rotation.col(k).dot(d) >= 0.0 ? 1.0 : -1.0;
      const int i = (k + 1) % 3, j = (k + 2) % 3;  // col(i) x col(j) = col(k)
      const Eigen::Vector3d centre = c + s * e[k] * p.rotation.col(k);
      const Eigen::Vector3d u = e[i] * p.rotation.col(i), w = e[j] * p.rotation.col(j);
      f.points = {centre + u + w, centre - u + w, centre - u - w, centre + u - w};
      if (s < 0.0) std::reverse(f.points.begin(), f.points.end());
      f.normal = s * p.rotation.col(k);
      f.index = static_cast<std::uint32_t>(2 * k + (s < 0.0 ? 1 : 0));
      return;
    }
    case kCapsule: {
      const Capsule& s = std::get<Capsule>(*p.part->shape);
      const Eigen::Vector3d axis = s.halfLength * p.rotation.col(2);
      if (s.halfLength > 0.0)
        f.points = {c - axis, c + axis};
      else
        f.points = {c};
      f.radius = s.radius;
      return;
    }
    case kCylinder: {
      const Cylinder& s = std::get<Cylinder>(*p.part->shape);
      const Eigen::Vector3d axis = p.rotation.col(2);
      const double along = axis.dot(d);
      const Eigen::Vector3d radial = d - along * axis;
      const double radialNorm = radial.norm();
      if (std::abs(along) >= kCapCos) {
        const double sign = along >= 0.0 ? 1.0 : -1.0;
        const Eigen::Vector3d centre = c + sign * s.halfLength * axis;
        for (int k = 0; k < kCapVertices; ++k) {
          const double angle = 2.0 * std::numbers::pi * k / kCapVertices;
          f.points.push_back(centre + s.radius * (std::cos(angle) * p.rotation.col(0) +
                                                  std::sin(angle) * p.rotation.col(1)));
        }
        if (sign < 0.0) std::reverse(f.points.begin(), f.points.end());
        f.normal = sign * axis;
        f.index = sign > 0.0 ? 1 : 2;
        f.discRadius = s.radius;
        f.discCentre = centre;
        if (radialNorm > 1e-9) {  // the rim's exact support point, between two 8-gon vertices
          f.points.push_back(centre + s.radius / radialNorm * radial);
          f.exactExtra = true;
        }
        return;
      }
      const Eigen::Vector3d out = radial / radialNorm;  // |along| < 0.71: radialNorm > 0.7
      f.points = {c - s.halfLength * axis + s.radius * out,
                  c + s.halfLength * axis + s.radius * out};
      return;
    }
    case kHull: {
      std::size_t face = 0;
      double best = -std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < p.hull->faces.size(); ++k) {
        const double along = (p.rotation * p.hull->faces[k].normal).dot(d);
        if (along > best + 1e-12) best = along, face = k;
      }
      const HullFace& chosen = p.hull->faces[face];
      for (const int v : chosen.loop) f.points.push_back((*p.hullVertices)[v]);
      f.normal = p.rotation * chosen.normal;
      f.index = static_cast<std::uint32_t>(face);
      return;
    }
    default:
      return;
  }
}

std::size_t vertexCount(const SupportFeature& f) {
  return f.points.size() - (f.exactExtra ? 1 : 0);
}

struct Clipper {
  const SupportFeature& ref;
  const SupportFeature& inc;
  bool refIsB;
  const Eigen::Vector3d& n;
  double margin;
  FeatureScratch& scratch;
  std::vector<ContactCandidate>& points;

  // The side planes of the reference polygon, containing the normal (a projection along it).
  bool buildSides(double& slop) {
    std::vector<Eigen::Vector3d>& sides = scratch.sideNormals;
    std::vector<double>& limits = scratch.sideLimits;
    sides.clear();
    limits.clear();
    const std::size_t count = vertexCount(ref);
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < count; ++k) centre += ref.points[k];
    centre /= static_cast<double>(count);
    double inradius = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < count; ++k) {
      const Eigen::Vector3d& p0 = ref.points[k];
      Eigen::Vector3d side = (ref.points[(k + 1) % count] - p0).cross(n);
      const double length = side.norm();
      if (length < 1e-12) continue;  // repeated vertex
      side /= length;
      if (side.dot(centre - p0) > 0.0) side = -side;
      sides.push_back(side);
      limits.push_back(side.dot(p0));
      inradius = std::min(inradius, limits.back() - side.dot(centre));
    }
    if (sides.size() < 3 || !(inradius > 0.0)) return false;
    slop = kClipSlop * inradius;
    return true;
  }

  // Sutherland-Hodgman of the incident polygon, or the parameter interval of a segment, or the
  // inside test of a point; ids as HullContacts (0x800 | side << 4 | segment when clipped).
  void clipIncident(double slop) {
    std::vector<ClipVertex>& polygon = scratch.polygon;
    std::vector<ClipVertex>& clipped = scratch.clipped;
    polygon.clear();
    const std::size_t count = vertexCount(inc);
    for (std::size_t k = 0; k < count; ++k)
      polygon.push_back({inc.points[k], static_cast<std::uint32_t>(k & 0x7f)});
    const std::vector<Eigen::Vector3d>& sides = scratch.sideNormals;
    const std::vector<double>& limits = scratch.sideLimits;
    for (std::size_t k = 0; k < sides.size() && !polygon.empty(); ++k) {
      clipped.clear();
      const std::size_t edges = polygon.size() == 2 ? 1 : polygon.size();  // a segment: one edge
      if (polygon.size() == 1) {
        if (sides[k].dot(polygon[0].position) - limits[k] - slop <= 0.0)
          clipped.push_back(polygon[0]);
      }
      for (std::size_t v = 0; v < edges && polygon.size() > 1; ++v) {
        const ClipVertex& a = polygon[v];
        const ClipVertex& b = polygon[(v + 1) % polygon.size()];
        const double da = sides[k].dot(a.position) - limits[k] - slop;
        const double db = sides[k].dot(b.position) - limits[k] - slop;
        if (da <= 0.0) clipped.push_back(a);
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
          // Kept or dropped by the pushed plane, but placed on the real side plane, so that a
          // clipped point needs no clamping back (which would move it off the incident edge).
          const double t = std::clamp((da + slop) / (da - db), 0.0, 1.0);
          const std::uint32_t segment =
              a.id & 0x800u ? 0x40u | ((a.id >> 4) & 0x3fu) : a.id & 0x3fu;
          clipped.push_back(
              {a.position + t * (b.position - a.position),
               0x800u | (static_cast<std::uint32_t>(k & 0x7f) << 4) | (segment & 0xfu)});
        }
        if (polygon.size() == 2 && db <= 0.0) clipped.push_back(b);  // a segment's far end
      }
      std::swap(polygon, clipped);
    }
    if (inc.exactExtra) {  // the cap's exact support point, kept when inside the reference
      const Eigen::Vector3d& extra = inc.points.back();
      bool inside = true;
      for (std::size_t k = 0; k < sides.size(); ++k)
        inside = inside && sides[k].dot(extra) - limits[k] - slop <= 0.0;
      if (inside) polygon.push_back({extra, kExactPointId});
    }
  }

  // A segment or point against a cylinder cap's disc (distances from the axis, exact): the chord
  // ends are smooth in the pose, where the 8-gon's sides would kink at its vertices. Ids: an end
  // inside keeps its index, a cut end is 0x800 | end << 4.
  void clipAgainstDisc() {
    std::vector<ClipVertex>& polygon = scratch.polygon;
    polygon.clear();
    scratch.sideNormals.clear();  // nothing to clamp back to in emit
    scratch.sideLimits.clear();
    const Eigen::Vector3d& m = ref.normal;
    auto radial = [&](const Eigen::Vector3d& x) {
      const Eigen::Vector3d r = x - ref.discCentre;
      return Eigen::Vector3d(r - r.dot(m) * m);
    };
    const double limit = ref.discRadius;
    if (inc.points.size() == 1) {
      if (radial(inc.points[0]).norm() <= limit) polygon.push_back({inc.points[0], 0});
      return;
    }
    const Eigen::Vector3d w0 = radial(inc.points[0]);
    const Eigen::Vector3d e = radial(inc.points[1]) - w0;
    // |w0 + t e|^2 = r^2: t between the roots is inside.
    const double a = e.squaredNorm(), b = w0.dot(e), c = w0.squaredNorm() - limit * limit;
    double lo = 0.0, hi = 1.0;
    if (a <= 1e-24) {  // the segment along the axis: all in or all out
      if (c > 0.0) return;
    } else {
      const double disc = b * b - a * c;
      if (disc < 0.0) return;
      const double root = std::sqrt(disc);
      lo = std::max(0.0, (-b - root) / a);
      hi = std::min(1.0, (-b + root) / a);
      if (lo > hi) return;
    }
    const Eigen::Vector3d& p0 = inc.points[0];
    const Eigen::Vector3d d = inc.points[1] - p0;
    polygon.push_back({p0 + lo * d, lo > 0.0 ? 0x800u : 0u});
    if (hi > lo) polygon.push_back({p0 + hi * d, hi < 1.0 ? 0x810u : 1u});
  }

  void emit(std::uint32_t base) {
    const Eigen::Vector3d& m = ref.normal;
    const double denominator = m.dot(n);
    const double plane = m.dot(ref.points[0]);
    const std::vector<Eigen::Vector3d>& sides = scratch.sideNormals;
    const std::vector<double>& limits = scratch.sideLimits;
    for (const ClipVertex& v : scratch.polygon) {
      const Eigen::Vector3d onRef = v.position + (plane - m.dot(v.position)) / denominator * n;
      const Eigen::Vector3d onInc = v.position + (refIsB ? inc.radius : -inc.radius) * n;
      const Eigen::Vector3d onA = refIsB ? onInc : onRef;
      const Eigen::Vector3d onB = refIsB ? onRef : onInc;
      const double gap = n.dot(onB - onA);
      if (gap > margin) continue;
      // Back inside the reference polygon (undoes the slop), midway between the surfaces.
      Eigen::Vector3d q = 0.5 * (onA + onB);
      for (std::size_t k = 0; k < sides.size(); ++k) {
        const double outside = sides[k].dot(q) - limits[k];
        if (outside > 0.0) q -= outside * sides[k];
      }
      points.push_back({q, -gap, base | (v.id & 0xffffu)});
    }
  }
};

// Two segments (or a segment and a point) without a reference polygon: nearly parallel
// segments at right angles to the normal touch along their overlap (ids 0, 1).
bool segmentContact(const SupportFeature& fa, const SupportFeature& fb, const Eigen::Vector3d& n,
                    double margin, std::uint32_t base, std::vector<ContactCandidate>& points) {
  if (fa.points.size() != 2 || fb.points.size() != 2) return false;
  const Eigen::Vector3d da = fa.points[1] - fa.points[0];
  const double lengthA = da.norm();
  const Eigen::Vector3d db = fb.points[1] - fb.points[0];
  if (lengthA < 1e-12 || db.norm() < 1e-12) return false;
  const Eigen::Vector3d ua = da / lengthA, ub = db.normalized();
  if (ua.cross(ub).norm() > kParallelSin || std::abs(ua.dot(n)) > kParallelSin ||
      std::abs(ub.dot(n)) > kParallelSin)
    return false;
  const double t0 = ua.dot(fb.points[0] - fa.points[0]);
  const double t1 = ua.dot(fb.points[1] - fa.points[0]);
  const double lo = std::max(0.0, std::min(t0, t1)), hi = std::min(lengthA, std::max(t0, t1));
  if (lo > hi) return false;
  const std::size_t before = points.size();
  const int ends = hi - lo > 1e-9 * lengthA ? 2 : 1;
  for (int e = 0; e < ends; ++e) {
    const Eigen::Vector3d pa = fa.points[0] + (e == 0 ? lo : hi) * ua;
    const Eigen::Vector3d pb = fb.points[0] + (pa - fb.points[0]).dot(ub) * ub;
    const Eigen::Vector3d onA = pa + fa.radius * n, onB = pb - fb.radius * n;
    const double gap = n.dot(onB - onA);
    if (gap > margin) continue;
    points.push_back({0.5 * (onA + onB), -gap, base | static_cast<std::uint32_t>(e)});
  }
  return points.size() > before;
}

}  // namespace

double separationAlong(const ConvexPart& a, const ConvexPart& b, const Eigen::Vector3d& d) {
  std::vector<Eigen::Vector3d> va, vb;
  ConvexHull fa, fb;
  return separation(pose(a, va, fa), pose(b, vb, fb), d);
}

double separationAlong(const ConvexPart& a, const ConvexPart& b, const Eigen::Vector3d& d,
                       FeatureScratch& scratch) {
  return separation(pose(a, scratch.hullVerticesA, scratch.facelessA),
                    pose(b, scratch.hullVerticesB, scratch.facelessB), d);
}

bool featureContact(const ConvexPart& a, const ConvexPart& b, const Eigen::Vector3d& guess,
                    double margin, PairContact& out, FeatureScratch& scratch, bool faceNormalOnly) {
  const Posed pa = pose(a, scratch.hullVerticesA, scratch.facelessA);
  const Posed pb = pose(b, scratch.hullVerticesB, scratch.facelessB);
  if ((pa.kind == kHull && pa.hull->faces.empty()) || (pb.kind == kHull && pb.hull->faces.empty()))
    return false;

  // 1. The normal: the guess, or a face normal / cylinder axis near it that separates at least
  //    as much. A triangle on an inactive edge keeps its face normal.
  const bool noGuess = !guess.allFinite() || guess.norm() < 0.5;
  Eigen::Vector3d n = noGuess ? Eigen::Vector3d::Zero() : Eigen::Vector3d(guess.normalized());
  if (faceNormalOnly && (pa.kind == kTriangle || pb.kind == kTriangle)) {
    const Eigen::Vector3d m = pa.kind == kTriangle ? triangleNormal(a) : -triangleNormal(b);
    n = m;
  } else {
    const double guessSeparation =
        noGuess ? -std::numeric_limits<double>::infinity() : separation(pa, pb, n);
    double best = -std::numeric_limits<double>::infinity();
    Eigen::Vector3d bestAxis = n;
    auto consider = [&](const Eigen::Vector3d& axis) {
      const double s = separation(pa, pb, axis);
      if (s > best) best = s, bestAxis = axis;
    };
    candidateAxes(pa, 1.0, n, consider);
    candidateAxes(pb, -1.0, n, consider);
    if (best >= guessSeparation - kSnapTolerance) n = bestAxis;
    if (noGuess && !(best > -kSnapTolerance)) return false;  // no axis shows them touching
  }
  if (!n.allFinite() || separation(pa, pb, n) > margin) return false;

  // 2. The supporting features along it.
  supportFeature(pa, n, scratch.a);
  supportFeature(pb, -n, scratch.b);
  const SupportFeature& fa = scratch.a;
  const SupportFeature& fb = scratch.b;
  const double alignA = vertexCount(fa) >= 3 ? fa.normal.dot(n) : -1.0;
  const double alignB = vertexCount(fb) >= 3 ? -fb.normal.dot(n) : -1.0;

  // 3. Clip, keep the points within the margin.
  const std::size_t before = out.points.size();
  if (std::max(alignA, alignB) >= kMinAlignment) {
    const bool refIsB = alignB > alignA + 1e-6;
    const SupportFeature& ref = refIsB ? fb : fa;
    const SupportFeature& inc = refIsB ? fa : fb;
    Clipper clipper{ref, inc, refIsB, n, margin, scratch, out.points};
    if (ref.discRadius > 0.0 && vertexCount(inc) <= 2) {
      clipper.clipAgainstDisc();
    } else {
      double slop = 0.0;
      if (!clipper.buildSides(slop)) return false;
      clipper.clipIncident(slop);
    }
    const std::uint32_t base =
        (refIsB ? 1u << 31 : 0u) | ((ref.index & 0x7fu) << 24) | ((inc.index & 0xffu) << 16);
    clipper.emit(base);
  } else if (!segmentContact(fa, fb, n, margin, 1u << 30, out.points)) {
    return false;
  }
  if (out.points.size() == before) return false;
  out.normal = n;
  return true;
}

}  // namespace coulomb::geometry
