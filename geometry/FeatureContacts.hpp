#pragma once
// Manifolds for the convex pairs without a closed form (box-cylinder, cylinder-cylinder,
// cylinder-capsule, capsule-hull, cylinder-hull, hulls above kMaxClippedHullVertices) and for one
// mesh triangle against a convex shape. FCL's MPR gives one point and a normal for these
// (docs/fcl-notes.md section 2); this turns them into a manifold the way Jolt does ("supporting
// faces"; Gregorius, "Robust Contact Creation for Physics Simulations", GDC 2015):
// 1. The normal: FCL's guess, or a face normal / cylinder axis near it when its separation
//    (from the support functions of both shapes) is at least as large. A flat face touching
//    anything has exactly the face's normal, which MPR only approximates (fcl-notes section 3),
//    and by the separating-axis theorem the true normal maximises the separation.
// 2. Each shape's supporting feature along it: a polygon (box or hull face, a cylinder cap as the
//    regular 8-gon of its rim, a mesh triangle), a segment (capsule core, cylinder side line) or
//    a point.
// 3. The incident feature clipped against the side planes of the reference polygon (projected
//    along the normal), or two nearly parallel segments clipped to their overlap. Points whose
//    gap along the normal is within the margin are kept, midway between the surfaces.
// A cylinder standing on a box then gets its rim points in the first step, as on a plane.
#include <coulomb/geometry/ManifoldBuilder.hpp>
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/geometry/Shape.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace coulomb::geometry {

/// A convex shape at its world pose, or (shape == nullptr) one mesh triangle in world
/// coordinates, counter-clockwise about its outward normal.
struct ConvexPart {
  const Shape* shape = nullptr;
  Pose pose = Pose::identity();
  std::array<Eigen::Vector3d, 3> triangle{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                          Eigen::Vector3d::Zero()};
};

/// A shape's feature that supports it along a direction (world coordinates).
struct SupportFeature {
  std::vector<Eigen::Vector3d> points;  // polygon (>= 3, counter-clockwise about `normal`),
                                        // segment (2) or point (1)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // a polygon's outward normal
  double radius = 0.0;                                // a capsule's
  std::uint32_t index = 0;                            // face / cap / side, for feature ids
  bool exactExtra = false;  // points.back() is a cylinder cap's exact support point, not a vertex
  // A cylinder cap: the disc itself (radius > 0, centre), against which segments and points are
  // clipped exactly; its 8-gon would put kinks where a rod lies across a vertex.
  double discRadius = 0.0;
  Eigen::Vector3d discCentre = Eigen::Vector3d::Zero();
};

/// Storage of the queries, kept by the caller between them (one query at a time).
struct FeatureScratch {
  SupportFeature a, b;
  std::vector<ClipVertex> polygon, clipped;
  std::vector<Eigen::Vector3d> sideNormals, hullVerticesA, hullVerticesB;
  std::vector<double> sideLimits;
  ConvexHull facelessA, facelessB;  // faces of hulls made without makeConvexHull
  // A mesh pair's (NarrowPhase): the triangles near the shape, one triangle's contact, and the
  // per-triangle results (normal, first point, depth weight) merged into one manifold.
  std::vector<int> triangles, otherTriangles;
  PairContact one;
  struct TriangleResult {
    Eigen::Vector3d normal;
    std::size_t begin = 0, end = 0;
    double weight = 0.0;
  };
  std::vector<TriangleResult> results;
  std::vector<ContactCandidate> merged;
};

/// The separation of b from a along the unit axis d: min over b of d.x - max over a of d.x
/// (> 0: a gap). Shapes: sphere, box, capsule, cylinder, hull; or a triangle.
double separationAlong(const ConvexPart& a, const ConvexPart& b, const Eigen::Vector3d& d);
/// The same with the caller's storage (no allocation once it has grown).
double separationAlong(const ConvexPart& a, const ConvexPart& b, const Eigen::Vector3d& d,
                       FeatureScratch& scratch);

/// Appends the manifold of a touching pair to `out` (normal from a to b) from FCL's normal
/// `guess` (unit, a to b). Returns false, leaving `out` untouched, when no point of the
/// features lies within the margin or the features are degenerate (the caller keeps FCL's
/// point). `faceNormalOnly`: a triangle part keeps its face normal whatever the guess (an
/// inactive mesh edge, MeshEdges.hpp).
bool featureContact(const ConvexPart& a, const ConvexPart& b, const Eigen::Vector3d& guess,
                    double margin, PairContact& out, FeatureScratch& scratch,
                    bool faceNormalOnly = false);

}  // namespace coulomb::geometry
