#pragma once
// Mass properties of every shape at a uniform density [kg/m^3], in the shape's local frame.
// Primitives use closed forms; convex hulls and closed meshes use the divergence theorem
// (Eberly, "Polyhedral Mass Properties (Revisited)", Geometric Tools 2002, itself a simplification
// of Mirtich, "Fast and Accurate Computation of Polyhedral Mass Properties", JGT 1(2), 1996).
#include <coulomb/geometry/Shape.hpp>
#include <coulomb/geometry/SpatialInertia.hpp>

#include <vector>

namespace coulomb::geometry {

/// Mass, COM and inertia about the COM of `shape` at `density`. Throws std::invalid_argument
/// naming the problem for a plane (infinite), a non-positive density, or a hull whose triangles
/// were not built (call makeConvexHull first). The shape must already pass validateShape().
SpatialInertia computeMassProperties(const Shape& shape, double density);

/// Volume [m^3] of a finite shape (0 for a plane).
double shapeVolume(const Shape& shape);

/// Divergence-theorem integrals of a closed, outward-oriented triangle surface at `density`.
/// A negative mass means the triangles face inward.
SpatialInertia polyhedronMassProperties(const std::vector<Eigen::Vector3d>& vertices,
                                        const std::vector<Eigen::Vector3i>& triangles,
                                        double density);

}  // namespace coulomb::geometry
