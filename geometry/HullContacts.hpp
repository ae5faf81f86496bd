#pragma once
// Hull-hull and box-hull manifolds built by hand, as BoxContacts does for boxes: a separating-axis
// test over the face normals of both polytopes and the cross products of their edges, then either
// the incident face clipped against the reference face's side planes (Ericson, Real-Time
// Collision Detection 5.2.1; Gregorius, "The Separating Axis Test between Convex Polyhedra",
// GDC 2013, and "Robust Contact Creation for Physics Simulations", GDC 2015) or, when an edge
// pair separates most, the closest points of the two edges. FCL's GJK/EPA gives a single point
// and misses exactly touching faces (docs/conformance.md, masonry arch); this gives the whole
// face contact from the first step, with stable feature ids.
//
// The hull's faces and edges are its shape's (ConvexHull::faces/edges, built once by
// makeConvexHull); a query moves only the vertices and face planes to the world, into a
// HullScratch the caller keeps, so a steady step allocates nothing here.
#include <coulomb/geometry/ManifoldBuilder.hpp>
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/geometry/Shape.hpp>

#include <utility>
#include <vector>

namespace coulomb::geometry {

/// Largest number of hull vertices handled here; larger hulls go through FCL (the face and edge
/// enumeration is quadratic in the hull's size).
inline constexpr std::size_t kMaxClippedHullVertices = 64;

/// Merges a hull's triangles into polygonal faces (coplanar within 1e-9 of its size, loops
/// counter-clockwise from outside) and lists its unique edges: fills hull.faces and hull.edges.
void buildHullFaces(ConvexHull& hull);

/// A polytope in world coordinates: vertices and face planes; the face loops and edges are its
/// shape's (borrowed).
struct WorldPolytope {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3d> normals;  // per face, outward, unit
  std::vector<double> offsets;           // per face: normal . x = offset on the plane
  const std::vector<HullFace>* faces = nullptr;
  const std::vector<std::pair<int, int>>* edges = nullptr;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
};

/// Storage of the queries, kept by the caller between them (one query at a time).
struct HullScratch {
  WorldPolytope a, b;
  ConvexHull box;                   // a box's faces and edges (vertex order of the box corners)
  ConvexHull facelessA, facelessB;  // faces of a hull made without makeConvexHull
  std::vector<ClipVertex> polygon, clipped;
  std::vector<Eigen::Vector3d> sideNormals;
  std::vector<double> sideLimits;
};

/// Feature ids: (reference is b) << 31 | reference face << 20 | incident face << 12 | clip id
/// (input vertex index < 0x80, or 0x800 | clip plane << 4 | segment for clipped vertices).
/// Edge-edge contacts: 1 << 30 | edge of a << 12 | edge of b. Returns 1 touching (points in
/// `out`, normal from a to b), 0 separated beyond the margin, -1 not handled (hull too large).
int hullHull(const ConvexHull& a, const Pose& pa, const ConvexHull& b, const Pose& pb,
             double margin, PairContact& out, HullScratch& scratch);
int boxHull(const Box& a, const Pose& pa, const ConvexHull& b, const Pose& pb, double margin,
            PairContact& out, HullScratch& scratch);
/// The same with storage of their own (tests, one-off queries).
int hullHull(const ConvexHull& a, const Pose& pa, const ConvexHull& b, const Pose& pb,
             double margin, PairContact& out);
int boxHull(const Box& a, const Pose& pa, const ConvexHull& b, const Pose& pb, double margin,
            PairContact& out);

}  // namespace coulomb::geometry
