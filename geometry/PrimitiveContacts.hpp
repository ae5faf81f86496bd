#pragma once
// Closed-form contacts for spheres, capsules, cylinders and planes (FCL is inexact or returns one
// point for these: docs/fcl-notes.md sections 2, 3 and 9). Each routine writes a normal pointing
// from its first shape to its second, appends candidates whose gap is below `margin`, and returns
// whether it appended any. Shapes are given with their world pose.
#include <coulomb/geometry/ManifoldBuilder.hpp>
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/geometry/Shape.hpp>

#include <span>

namespace coulomb::geometry {

/// A plane in world coordinates: half-space {x : normal.x <= offset}, unit normal.
struct WorldPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0.0;
};
WorldPlane toWorld(const Plane& plane, const Pose& pose);

/// Closest points of segments p1q1 and p2q2 (Ericson, Real-Time Collision Detection, 5.1.9).
void closestSegmentPoints(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1,
                          const Eigen::Vector3d& p2, const Eigen::Vector3d& q2, Eigen::Vector3d& c1,
                          Eigen::Vector3d& c2);

/// Plane (first) against points swept by `radius` (second): box/hull/mesh vertices with radius
/// 0, capsule ends with the capsule radius. Feature id = index of the point.
bool planePoints(const WorldPlane& plane, std::span<const Eigen::Vector3d> points, double radius,
                 double margin, PairContact& out);
/// The 8 box corners in world coordinates, corner i = (+-x, +-y, +-z) with bit 0,1,2 = sign.
std::array<Eigen::Vector3d, 8> boxCorners(const Box& box, const Pose& pose);
/// Cylinder rim points against a plane: 8 points per rim plus each rim's exact deepest point.
bool planeCylinder(const WorldPlane& plane, const Cylinder& cylinder, const Pose& pose,
                   double margin, PairContact& out);

bool sphereSphere(const Sphere& a, const Pose& pa, const Sphere& b, const Pose& pb, double margin,
                  PairContact& out);
bool sphereBox(const Sphere& a, const Pose& pa, const Box& b, const Pose& pb, double margin,
               PairContact& out);
bool sphereCapsule(const Sphere& a, const Pose& pa, const Capsule& b, const Pose& pb, double margin,
                   PairContact& out);
bool sphereCylinder(const Sphere& a, const Pose& pa, const Cylinder& b, const Pose& pb,
                    double margin, PairContact& out);
/// Segment-segment closest points; nearly parallel overlapping capsules get the 2 ends of the
/// overlap (ids 0, 1), otherwise one point (id 2).
bool capsuleCapsule(const Capsule& a, const Pose& pa, const Capsule& b, const Pose& pb,
                    double margin, PairContact& out);

}  // namespace coulomb::geometry
