#include <coulomb/geometry/NarrowPhase.hpp>

#include <coulomb/geometry/BoxContacts.hpp>
#include <coulomb/geometry/FeatureContacts.hpp>
#include <coulomb/geometry/HullContacts.hpp>
#include <coulomb/geometry/MeshEdges.hpp>
#include <coulomb/geometry/PrimitiveContacts.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

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

// [m] MPR's tolerance: overlaps below it come back with arbitrary normals, or not at all.
constexpr double kMprTolerance = 1e-6;

double maxAbsDepth(const PairContact& contact) {
  double deepest = 0.0;
  for (const ContactCandidate& c : contact.points) deepest = std::max(deepest, std::abs(c.depth));
  return deepest;
}

FeatureScratch& featureScratch(NarrowPhaseScratch& scratch) {
  if (!scratch.features) scratch.features = std::make_shared<FeatureScratch>();
  return *scratch.features;
}

// A mesh contact whose normal leans away from its triangle's face only across internal edges
// (MeshEdges.hpp) is an artefact of the triangulation: the face normal is the contact normal.
// `fromMesh` is the contact normal leaving the mesh; `face` the triangle's outward normal.
bool leansOnlyOverInternalEdges(const std::array<Eigen::Vector3d, 3>& v,
                                const Eigen::Vector3d& face, const Eigen::Vector3d& fromMesh,
                                std::uint8_t activeEdges) {
  if (fromMesh.dot(face) <= 0.0) return false;  // from behind the face: not a surface contact
  const Eigen::Vector3d lean = fromMesh - fromMesh.dot(face) * face;
  const double size = lean.norm();
  if (size < 1e-9) return false;  // already the face normal
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d outward = (v[(k + 1) % 3] - v[k]).cross(face);
    if (outward.dot(lean) > 1e-6 * size * outward.norm() && ((activeEdges >> k) & 1u)) return false;
  }
  return true;
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

// Triangle t of `mesh` in the world, into `part` (a triangle part: no shape).
void placeTriangle(const TriangleMesh& mesh, const Pose& pose, int t, ConvexPart& part) {
  const Eigen::Vector3i& v = mesh.triangles[static_cast<std::size_t>(t)];
  for (int k = 0; k < 3; ++k)
    part.triangle[k] = pose.apply(mesh.vertices[static_cast<std::size_t>(v[k])]);
}

Eigen::Vector3d faceNormal(const ConvexPart& triangle) {
  const auto& t = triangle.triangle;
  return (t[1] - t[0]).cross(t[2] - t[0]).normalized();
}

// One normal for a mesh pair's triangle results: the deepest's, averaged (by depth) with those
// within ~10 degrees of it; the points of those go to `out`.
void mergeTriangleResults(FeatureScratch& features, PairContact& out) {
  std::size_t deepest = 0;
  for (std::size_t r = 1; r < features.results.size(); ++r)
    if (features.results[r].weight > features.results[deepest].weight) deepest = r;
  const Eigen::Vector3d n0 = features.results[deepest].normal;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  out.points.clear();
  for (const FeatureScratch::TriangleResult& r : features.results) {
    if (r.normal.dot(n0) < 0.985) continue;
    sum += (std::max(0.0, r.weight) + 1e-9) * r.normal;
    out.points.insert(out.points.end(),
                      features.merged.begin() + static_cast<std::ptrdiff_t>(r.begin),
                      features.merged.begin() + static_cast<std::ptrdiff_t>(r.end));
  }
  out.normal = sum.normalized();
}

// Whether a point of featureContact(triangle, other) (or (other, triangle) when the triangle is
// B) is a vertex of the other shape on the triangle's face: the triangle is the clip reference
// (bit 31 of the id says the reference is B; bit 30 marks a segment pair, with no reference) and
// the vertex was not clipped (0x800: a cut against a side of the reference).
bool slidesOnTheFace(std::uint32_t id, bool triangleIsA) {
  if (id & (1u << 30) || id & 0x800u) return false;
  return ((id >> 31) != 0) != triangleIsA;
}

// Appends one triangle pair's (or one triangle's) points to the merged list, ids mixed with
// `key` so that they stay unique across triangles. With a `patch` (MeshSurface), a vertex of the
// other shape on the triangle's face is keyed by the triangle's smooth patch instead: it is one
// feature sliding over the surface, and keeps its id, and so its warm start and last solved row
// (ContactCache), from triangle to triangle (a ball round a faceted drum, a box over a
// triangulated floor; docs/tuning.md "Triangle meshes").
void keepTriangleResult(const PairContact& one, std::uint32_t key, FeatureScratch& features,
                        const std::uint32_t* patch = nullptr, bool triangleIsA = true) {
  double deepest = -std::numeric_limits<double>::infinity();
  const std::size_t begin = features.merged.size();
  for (ContactCandidate c : one.points) {
    const bool onPatch = patch && slidesOnTheFace(c.featureId, triangleIsA);
    c.featureId = (onPatch ? 0x80000000u | *patch : key) * 2654435761u ^ c.featureId;
    deepest = std::max(deepest, c.depth);
    features.merged.push_back(c);
  }
  features.results.push_back({one.normal, begin, features.merged.size(), deepest});
}

// A mesh against a mesh, triangle against triangle (FCL's own mesh-mesh contacts are unusable,
// docs/fcl-notes.md 4.5): each triangle of the mesh with fewer triangles near the other mesh,
// against the other's triangles near it; only faces that face each other (within 60 degrees),
// normal from the pair's face normals (FeatureContacts picks the one that separates most).
// A mesh has no inside: a triangle pair overlapping deeper than 5% of the smaller mesh's size is
// a pass-through, not a contact, and is skipped (documented limit: no volume, docs/collision.md).
bool meshMeshContact(const Collider& a, const Pose& poseA, const Collider& b, const Pose& poseB,
                     const FclScene& scene, double margin, PairContact& out,
                     FeatureScratch& features) {
  const TriangleMesh& meshA = std::get<TriangleMesh>(*a.shape);
  const TriangleMesh& meshB = std::get<TriangleMesh>(*b.shape);
  const bool outerIsA = meshA.triangles.size() <= meshB.triangles.size();
  const Collider& outer = outerIsA ? a : b;
  const Collider& inner = outerIsA ? b : a;
  const TriangleMesh& outerMesh = outerIsA ? meshA : meshB;
  const TriangleMesh& innerMesh = outerIsA ? meshB : meshA;
  const Pose& outerPose = outerIsA ? poseA : poseB;
  const Pose& innerPose = outerIsA ? poseB : poseA;
  auto grown = [margin](Aabb box) {
    box.min.array() -= margin;
    box.max.array() += margin;
    return box;
  };
  const Aabb boxA = scene.worldAabb(a.id), boxB = scene.worldAabb(b.id);
  const double size = std::min((boxA.max - boxA.min).norm(), (boxB.max - boxB.min).norm());
  const double deepest = 0.05 * size;
  scene.meshTrianglesNear(outer.id, grown(scene.worldAabb(inner.id)), features.triangles);
  features.results.clear();
  features.merged.clear();
  ConvexPart outerTriangle, innerTriangle;
  for (const int to : features.triangles) {
    placeTriangle(outerMesh, outerPose, to, outerTriangle);
    const Eigen::Vector3d outerFace = faceNormal(outerTriangle);
    Aabb box{outerTriangle.triangle[0], outerTriangle.triangle[0]};
    for (const Eigen::Vector3d& v : outerTriangle.triangle) {
      box.min = box.min.cwiseMin(v);
      box.max = box.max.cwiseMax(v);
    }
    scene.meshTrianglesNear(inner.id, grown(box), features.otherTriangles);
    for (const int ti : features.otherTriangles) {
      placeTriangle(innerMesh, innerPose, ti, innerTriangle);
      const Eigen::Vector3d innerFace = faceNormal(innerTriangle);
      if (outerFace.dot(innerFace) > -0.5) continue;  // not facing each other
      const ConvexPart& partA = outerIsA ? outerTriangle : innerTriangle;
      const ConvexPart& partB = outerIsA ? innerTriangle : outerTriangle;
      const Eigen::Vector3d guess = -(outerIsA ? innerFace : outerFace);  // b's face, a to b
      PairContact& one = features.one;
      one.points.clear();
      if (!featureContact(partA, partB, guess, margin, one, features)) continue;
      bool passThrough = false;
      for (const ContactCandidate& c : one.points) passThrough = passThrough || c.depth > deepest;
      if (passThrough) continue;
      const auto ia = static_cast<std::uint32_t>(outerIsA ? to : ti);
      const auto ib = static_cast<std::uint32_t>(outerIsA ? ti : to);
      keepTriangleResult(one, (ia + 1) * 40503u ^ (ib + 1), features);
    }
  }
  if (features.results.empty()) return false;
  mergeTriangleResults(features, out);
  return true;
}

}  // namespace

bool NarrowPhase::contactPair(const Collider& a, const Pose& poseA, const Collider& b,
                              const Pose& poseB, const FclScene& scene, PairContact& out,
                              std::string& error, double margin,
                              NarrowPhaseScratch& scratch) const {
  out.points.clear();
  error.clear();
  const bool swap = a.shape->index() > b.shape->index();
  const int handled = swap ? closedForm(*b.shape, poseB, *a.shape, poseA, margin, out, scratch)
                           : closedForm(*a.shape, poseA, *b.shape, poseB, margin, out, scratch);
  if (handled >= 0) {
    if (swap) out.normal = -out.normal;
    return handled == 1 && !out.points.empty();
  }
  out.points.clear();
  if (a.shape->index() == kMesh && b.shape->index() == kMesh)
    return meshMeshContact(a, poseA, b, poseB, scene, margin, out, featureScratch(scratch));
  if (a.shape->index() == kMesh || b.shape->index() == kMesh)
    return meshContact(a, poseA, b, poseB, scene, margin, out, error, scratch);
  // FCL's one point and normal made into the manifold of the supporting features; shapes FCL
  // finds exactly touching (distance 0, no direction) get the face axis that separates most.
  const bool touching = viaFcl(a, poseA, b, poseB, scene, margin, out, error);
  if (!touching && (!error.empty() || !out.normal.isZero())) return false;
  // MPR's normal of an overlap below its tolerance is arbitrary (docs/fcl-notes.md section 3: a
  // cylinder exactly on a box came back with a normal 90 degrees off): no guess then.
  const bool reliable = touching && !out.points.empty() && maxAbsDepth(out) >= kMprTolerance;
  FeatureScratch& features = featureScratch(scratch);
  PairContact& refined = features.one;
  refined.points.clear();
  const ConvexPart partA{.shape = a.shape.get(), .pose = poseA};
  const ConvexPart partB{.shape = b.shape.get(), .pose = poseB};
  const Eigen::Vector3d guess = reliable ? out.normal : Eigen::Vector3d::Zero();
  if (featureContact(partA, partB, guess, margin, refined, features)) {
    out.normal = refined.normal;
    out.points.swap(refined.points);
    return true;
  }
  return touching && reliable;  // an unreliable FCL point is dropped: the next step's is good
}

bool NarrowPhase::meshContact(const Collider& a, const Pose& poseA, const Collider& b,
                              const Pose& poseB, const FclScene& scene, double margin,
                              PairContact& out, std::string& error,
                              NarrowPhaseScratch& scratch) const {
  if (!viaFcl(a, poseA, b, poseB, scene, margin, out, error) && !error.empty()) return false;
  const bool meshIsA = a.shape->index() == kMesh;
  const Collider& mesh = meshIsA ? a : b;
  const Collider& other = meshIsA ? b : a;
  const Pose& meshPose = meshIsA ? poseA : poseB;
  const TriangleMesh& shape = std::get<TriangleMesh>(*mesh.shape);
  FeatureScratch& features = featureScratch(scratch);
  Aabb box = scene.worldAabb(other.id);
  box.min.array() -= margin;
  box.max.array() += margin;
  scene.meshTrianglesNear(mesh.id, box, features.triangles);
  const MeshSurface* surface = scene.meshSurface(mesh.id);
  const ConvexPart otherPart{.shape = other.shape.get(), .pose = meshIsA ? poseB : poseA};
  ConvexPart triangle;
  const bool fclReliable = !out.points.empty() && maxAbsDepth(out) >= kMprTolerance;
  features.results.clear();
  features.merged.clear();
  for (const int t : features.triangles) {
    placeTriangle(shape, meshPose, t, triangle);
    const Eigen::Vector3d face = faceNormal(triangle);
    const std::uint8_t flags =
        surface ? surface->activeEdges[static_cast<std::size_t>(t)] : std::uint8_t{0x7};
    // Whether FCL reported this triangle (`out` holds FCL's points, their ids made from t).
    const auto tag = static_cast<std::uint32_t>((t + 1) << 4);
    const bool reported =
        fclReliable && std::any_of(out.points.begin(), out.points.end(),
                                   [tag](const ContactCandidate& c) { return c.featureId == tag; });
    Eigen::Vector3d guess;
    bool faceOnly = false;
    if (reported) {
      guess = out.normal;  // FCL's (merged) normal, from a to b
      faceOnly =
          leansOnlyOverInternalEdges(triangle.triangle, face, meshIsA ? guess : -guess, flags);
    } else {
      // Not overlapping by FCL: the face normal, for a shape in front of the face only.
      if (face.dot(otherPart.pose.position - triangle.triangle[0]) <= 0.0) continue;
      guess = meshIsA ? face : Eigen::Vector3d(-face);
      faceOnly = true;
    }
    PairContact& one = features.one;
    one.points.clear();
    const bool touching =
        meshIsA ? featureContact(triangle, otherPart, guess, margin, one, features, faceOnly)
                : featureContact(otherPart, triangle, guess, margin, one, features, faceOnly);
    if (!touching) continue;
    // FCL found no overlap with this triangle: a point deep along its face normal means the face
    // is not the separating direction (a side face next to a shape resting on the top), not a
    // contact.
    if (!reported &&
        std::any_of(one.points.begin(), one.points.end(),
                    [](const ContactCandidate& c) { return c.depth > 10.0 * kMprTolerance; }))
      continue;
    keepTriangleResult(one, static_cast<std::uint32_t>(t + 1), features,
                       surface ? &surface->patch[static_cast<std::size_t>(t)] : nullptr, meshIsA);
  }
  if (features.results.empty()) return !out.points.empty() && fclReliable;  // FCL's points
  mergeTriangleResults(features, out);
  return true;
}

bool NarrowPhase::viaFcl(const Collider& a, const Pose& poseA, const Collider& b, const Pose& poseB,
                         const FclScene& scene, double margin, PairContact& out,
                         std::string& error) const {
  (void)poseA;
  (void)poseB;
  out.normal = Eigen::Vector3d::UnitZ();
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
  if (gap.distance > margin) return false;
  if (gap.distance <= 0.0 || d.norm() < 1e-12) {
    out.normal = Eigen::Vector3d::Zero();  // touching, with no direction: contactPair decides
    return false;
  }
  out.normal = d.normalized();
  out.points.push_back({0.5 * (gap.pointA + gap.pointB), -gap.distance, 0});
  return true;
}

void NarrowPhase::collidePair(const CandidatePair& pair, const std::vector<Collider>& colliders,
                              std::span<const Pose> shapePoses, std::span<const Pose> bodyPoses,
                              const FclScene& scene, std::span<const double> sweeps,
                              NarrowPhaseChunk& chunk) const {
  const Collider& a = colliders[pair.a];
  const Collider& b = colliders[pair.b];
  if (a.body.index >= bodyPoses.size() || b.body.index >= bodyPoses.size()) {
    chunk.failures.push_back({a.id, b.id, "body index out of range of the body poses"});
    return;
  }
  double margin = settings_.margin;
  if (pair.a < sweeps.size() && pair.b < sweeps.size()) margin += sweeps[pair.a] + sweeps[pair.b];
  PairContact& contact = chunk.pair;
  const bool touching = contactPair(a, shapePoses[pair.a], b, shapePoses[pair.b], scene, contact,
                                    chunk.error, margin, chunk.scratch);
  if (!chunk.error.empty()) {
    chunk.failures.push_back({a.id, b.id, chunk.error});
    return;
  }
  if (!touching) return;
  bool finite = contact.normal.allFinite();
  for (const ContactCandidate& c : contact.points)
    finite = finite && c.position.allFinite() && std::isfinite(c.depth);
  if (!finite) {
    chunk.failures.push_back({a.id, b.id, "contact produced a non-finite value; pair skipped"});
    return;
  }
  chunk.manifolds.push_back(
      finishManifold(contact, a, b, bodyPoses[a.body.index], bodyPoses[b.body.index]));
}

void NarrowPhase::collide(std::span<const CandidatePair> pairs,
                          const std::vector<Collider>& colliders, std::span<const Pose> shapePoses,
                          std::span<const Pose> bodyPoses, const FclScene& scene,
                          std::vector<ContactManifold>& out,
                          std::vector<CollisionFailure>& failures, std::span<const double> sweeps,
                          const ParallelFor& parallel) {
  // Fixed chunks of consecutive pairs whatever the threads: every pair is computed the same way
  // and the results are merged in pair order, so they do not depend on the thread count.
  constexpr std::size_t kPairsPerChunk = 32;
  const std::size_t chunkCount = (pairs.size() + kPairsPerChunk - 1) / kPairsPerChunk;
  if (chunks_.size() < chunkCount) chunks_.resize(chunkCount);
  const auto run = [&](std::size_t c) {
    NarrowPhaseChunk& chunk = chunks_[c];
    chunk.manifolds.clear();
    chunk.failures.clear();
    const std::size_t end = std::min(pairs.size(), (c + 1) * kPairsPerChunk);
    for (std::size_t k = c * kPairsPerChunk; k < end; ++k)
      collidePair(pairs[k], colliders, shapePoses, bodyPoses, scene, sweeps, chunk);
  };
  if (parallel && chunkCount > 1) {
    parallel(chunkCount, run);
  } else {
    for (std::size_t c = 0; c < chunkCount; ++c) run(c);
  }
  for (std::size_t c = 0; c < chunkCount; ++c) {
    out.insert(out.end(), chunks_[c].manifolds.begin(), chunks_[c].manifolds.end());
    failures.insert(failures.end(), chunks_[c].failures.begin(), chunks_[c].failures.end());
  }
}

}  // namespace coulomb::geometry
