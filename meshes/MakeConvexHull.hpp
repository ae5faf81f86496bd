#pragma once
// Convex hull of a point cloud, computed by Qhull (Barber, Dobkin, Huhdanpaa, "The Quickhull
// Algorithm for Convex Hulls", ACM TOMS 22(4), 1996) through Debian's libqhull_r.
#include <coulomb/geometry/Shape.hpp>

#include <vector>

namespace coulomb::geometry {

/// A ConvexHull whose `vertices` are `points` (unchanged, so indices stay meaningful) and whose
/// `triangles` are the hull's faces, triangulated and oriented outward (counter-clockwise seen
/// from outside). Throws std::invalid_argument naming the problem: fewer than 4 points,
/// non-finite points, or points that are coplanar (no volume).
ConvexHull makeConvexHull(const std::vector<Eigen::Vector3d>& points);

}  // namespace coulomb::geometry
