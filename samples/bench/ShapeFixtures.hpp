#pragma once
// Shapes and trees built by hand for the tests and benchmarks of the contact manifolds, the mesh
// pairs and the tree integrators (tests/engine/ShapePairRestingTest, MeshSlidingTest,
// MeshMeshTest, TreeIntegratorTest; bench/PairContactBench, TreeIntegratorBench).
#include <coulomb/engine/ArticulationDesc.hpp>
#include <coulomb/geometry/Shape.hpp>

#include <Eigen/Core>

namespace coulomb::samples {

/// A closed slab whose top face (z = 0) is a `cells` x `cells` grid of 2 cells^2 triangles over
/// [-halfWidth, halfWidth]^2, `thickness` deep (its bottom a grid too, its sides strips).
geometry::TriangleMesh gridSlab(int cells, double halfWidth, double thickness = 0.2);

/// A closed ring (a drum's wall) about z: `facets` flat facets between `innerRadius` and
/// `outerRadius`, z in [-height/2, height/2]. Its inner wall faces the axis, so a body inside the
/// ring touches a concave polygon of facets (the vertices lie on the circle).
geometry::TriangleMesh ringWall(int facets, double innerRadius, double outerRadius, double height);

/// A box as a convex hull (makeConvexHull of its 8 corners), centred at the origin.
geometry::ConvexHull boxHull(const Eigen::Vector3d& halfExtents);

/// The chain of docs/scene-specifications.md A6 as one articulation: `links` links of 0.1 kg and
/// 0.1 m along x on spherical joints (the first at the world origin), released horizontal.
engine::ArticulationDesc releasedChain(int links);

}  // namespace coulomb::samples
