#include <coulomb/geometry/NarrowPhase.hpp>

#include <coulomb/geometry/BoxContacts.hpp>
#include <coulomb/geometry/HullContacts.hpp>
#include <coulomb/geometry/PrimitiveContacts.hpp>

#include <algorithm>
#include <cmath>

namespace coulomb::geometry {
namespace {

// Shape::index() order: Sphere, Box, Capsule, Cylinder, Plane, ConvexHull, TriangleMesh.
enum Kind { kSphere = 0, kBox, kCapsule, kCylinder, kPlane, kHull, kMesh };

// `local` moved to the world, into `out` (the narrow phase's kept storage).
std::span<const Eigen::Vector3d> worldVertices(const std::vector<Eigen::Vector3d>& local,
                                               const Pose& pose,
                                               std::vector<Eigen::Vector3d>& out) {
  out.resize(local.size());
  for (std::size_t i = 0; i < local.size(); ++i) out[i] = pose.apply(local[i]);
  return out;
}

// Closed-form routines, with `first` of a kind <= `second` (normal first -> second).
// Returns 1 touching, 0 apart, -1 not handled here (use FCL).
int closedForm(const Shape& first, const Pose& p1, const Shape& second, const Pose& p2,
               double margin, PairContact& out, NarrowPhaseScratch& scratch) {
  const int k1 = static_cast<int>(first.index()), k2 = static_cast<int>(second.index());
  // Plane against anything: plane first gives the plane -> object normal; flip when the plane
  // is the second shape.
  auto planeVs = [&](const WorldPlane& plane, const Shape& other, const Pose& pose) -> bool {
    switch (other.index()) {
      case kSphere: {
        const Eigen::Vector3d centre = pose.position;
        return planePoints(plane, std::span(&centre, 1), std::get<Sphere>(other).radius, margin,
                           out);
      }
      case kBox: {
        const auto corners = boxCorners(std::get<Box>(other), pose);
        return planePoints(plane, corners, 0.0, margin, out);
      }
      case kCapsule: {
        const Capsule& c = std::get<Capsule>(other);
        const std::array<Eigen::Vector3d, 2> ends{pose.apply({0, 0, -c.halfLength}),
                                                  pose.apply({0, 0, c.halfLength})};
        // A zero-length capsule is a sphere: one end, not two coincident points.
        return planePoints(plane, std::span(ends.data(), c.halfLength > 0.0 ? 2 : 1), c.radius,
                           margin, out);
      }
      case kCylinder:
        return planeCylinder(plane, std::get<Cylinder>(other), pose, margin, out);
      case kHull:
        return planePoints(
            plane, worldVertices(std::get<ConvexHull>(other).vertices, pose, scratch.worldVertices),
            0.0, margin, out);
      case kMesh:
        return planePoints(
            plane,
            worldVertices(std::get<TriangleMesh>(other).vertices, pose, scratch.worldVertices), 0.0,
            margin, out);
      default:
        return false;  // plane-plane: both static, nothing to do
    }
  };
  if (k2 == kPlane || k1 == kPlane) {
    const bool planeFirst = k1 == kPlane;
    const WorldPlane plane =
        toWorld(std::get<Plane>(planeFirst ? first : second), planeFirst ? p1 : p2);
    const bool touching = planeVs(plane, planeFirst ? second : first, planeFirst ? p2 : p1);
    if (!planeFirst) out.normal = -out.normal;
    return touching ? 1 : 0;
  }
  switch (k1 * 8 + k2) {
    case kSphere * 8 + kSphere:
      return sphereSphere(std::get<Sphere>(first), p1, std::get<Sphere>(second), p2, margin, out);
    case kSphere * 8 + kBox:
      return sphereBox(std::get<Sphere>(first), p1, std::get<Box>(second), p2, margin, out);
    case kSphere * 8 + kCapsule:
      return sphereCapsule(std::get<Sphere>(first), p1, std::get<Capsule>(second), p2, margin, out);
    case kSphere * 8 + kCylinder:
      return sphereCylinder(std::get<Sphere>(first), p1, std::get<Cylinder>(second), p2, margin,
                            out);
    case kBox * 8 + kBox:
      return boxBox(std::get<Box>(first), p1, std::get<Box>(second), p2, margin, out);
    case kBox * 8 + kCapsule: {
      const auto result =
          boxCapsule(std::get<Box>(first), p1, std::get<Capsule>(second), p2, margin, out);
      if (result == BoxCapsuleResult::AxisInsideBox) return -1;
      return result == BoxCapsuleResult::Touching ? 1 : 0;
    }
    case kBox * 8 + kHull:  // -1 (FCL) for hulls above kMaxClippedHullVertices
      return boxHull(std::get<Box>(first), p1, std::get<ConvexHull>(second), p2, margin, out,
                     scratch.hulls);
    case kHull * 8 + kHull:
      return hullHull(std::get<ConvexHull>(first), p1, std::get<ConvexHull>(second), p2, margin,
                      out, scratch.hulls);
    case kCapsule * 8 + kCapsule:
      return capsuleCapsule(std::get<Capsule>(first), p1, std::get<Capsule>(second), p2, margin,
                            out);
    default:
      return -1;
  }
}

}  // namespace

bool NarrowPhase::contactPair(const Collider& a, const Pose& poseA, const Collider& b,
                              const Pose& poseB, const FclScene& scene, PairContact& out,
                              std::string& error, double margin) const {
  out.points.clear();
  error.clear();
  const bool swap = a.shape->index() > b.shape->index();
  const int handled = swap ? closedForm(*b.shape, poseB, *a.shape, poseA, margin, out, scratch_)
                           : closedForm(*a.shape, poseA, *b.shape, poseB, margin, out, scratch_);
  if (handled >= 0) {
    if (swap) out.normal = -out.normal;
    return handled == 1 && !out.points.empty();
  }
  out.points.clear();
  if (a.shape->index() == kMesh && b.shape->index() == kMesh) {
    error = "mesh-mesh contact is not supported (docs/fcl-notes.md 4.5): use convex pieces";
    return false;
  }
  return viaFcl(a, b, scene, margin, out, error);
}

bool NarrowPhase::viaFcl(const Collider& a, const Collider& b, const FclScene& scene, double margin,
                         PairContact& out, std::string& error) const {
  const bool mesh = a.shape->index() == kMesh || b.shape->index() == kMesh;
  FclCollideResult hit = scene.collide(a.id, b.id, mesh ? settings_.maxMeshContacts : 4, injector_);
  if (!hit.error.empty()) {
    error = hit.error;
    return false;
  }
  if (!hit.contacts.empty()) {
    // One normal per manifold: the deepest contact's, averaged (depth-weighted) with the
    // contacts that agree with it within ~10 degrees; the others belong to other faces.
    std::size_t deepest = 0;
    for (std::size_t i = 1; i < hit.contacts.size(); ++i)
      if (hit.contacts[i].depth > hit.contacts[deepest].depth) deepest = i;
    const Eigen::Vector3d n0 = hit.contacts[deepest].normal;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < hit.contacts.size(); ++i) {
      const FclContact& c = hit.contacts[i];
      if (c.normal.dot(n0) < 0.985) continue;
      sum += (c.depth + 1e-9) * c.normal;
      const int triangle = std::max(c.triangleA, c.triangleB);
      const auto id = static_cast<std::uint32_t>(triangle >= 0 ? (triangle + 1) << 4 : int(i));
      out.points.push_back({c.position, c.depth, id});
    }
    out.normal = sum.normalized();
    return true;
  }
  // No overlap: a speculative point if the gap is within the margin.
  FclDistanceResult gap = scene.distance(a.id, b.id, injector_);
  if (!gap.error.empty()) {
    error = gap.error;
    return false;
  }
  const Eigen::Vector3d d = gap.pointB - gap.pointA;
  if (gap.distance > margin || gap.distance <= 0.0 || d.norm() < 1e-12) return false;
  out.normal = d.normalized();
  out.points.push_back({0.5 * (gap.pointA + gap.pointB), -gap.distance, 0});
  return true;
}

void NarrowPhase::collide(std::span<const CandidatePair> pairs,
                          const std::vector<Collider>& colliders, std::span<const Pose> shapePoses,
                          std::span<const Pose> bodyPoses, const FclScene& scene,
                          std::vector<ContactManifold>& out,
                          std::vector<CollisionFailure>& failures, std::span<const double> sweeps) {
  std::string error;
  for (const CandidatePair& pair : pairs) {
    const Collider& a = colliders[pair.a];
    const Collider& b = colliders[pair.b];
    if (a.body.index >= bodyPoses.size() || b.body.index >= bodyPoses.size()) {
      failures.push_back({a.id, b.id, "body index out of range of the body poses"});
      continue;
    }
    double margin = settings_.margin;
    if (pair.a < sweeps.size() && pair.b < sweeps.size()) margin += sweeps[pair.a] + sweeps[pair.b];
    const bool touching = contactPair(a, shapePoses[pair.a], b, shapePoses[pair.b], scene,
                                      pairScratch_, error, margin);
    if (!error.empty()) {
      failures.push_back({a.id, b.id, error});
      continue;
    }
    if (!touching) continue;
    bool finite = pairScratch_.normal.allFinite();
    for (const ContactCandidate& c : pairScratch_.points)
      finite = finite && c.position.allFinite() && std::isfinite(c.depth);
    if (!finite) {
      failures.push_back({a.id, b.id, "contact produced a non-finite value; pair skipped"});
      continue;
    }
    out.push_back(
        finishManifold(pairScratch_, a, b, bodyPoses[a.body.index], bodyPoses[b.body.index]));
  }
}

}  // namespace coulomb::geometry
