#pragma once
// Hull-hull and box-hull manifolds built by hand, as BoxContacts does for boxes: a separating-axis
// test over the face normals of both polytopes and the cross products of their edges, then either
// the incident face clipped against the reference face's side planes (Ericson, Real-Time
// Collision Detection 5.2.1; Gregorius, "The Separating Axis Test between Convex Polyhedra",
// GDC 2013, and "Robust Contact Creation for Physics Simulations", GDC 2015) or, when an edge
// pair separates most, the closest points of the two edges. FCL's GJK/EPA gives a single point
// and misses exactly touching faces (docs/conformance.md, masonry arch); this gives the whole
// face contact from the first step, with stable feature ids.
#include <coulomb/geometry/ManifoldBuilder.hpp>
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/geometry/Shape.hpp>

namespace coulomb::geometry {

/// Largest number of hull vertices handled here; larger hulls go through FCL (the face and edge
/// enumeration is quadratic in the hull's size).
inline constexpr std::size_t kMaxClippedHullVertices = 64;

/// Feature ids: (reference is b) << 31 | reference face << 20 | incident face << 12 | clip id
/// (input vertex index < 0x80, or 0x800 | clip plane << 4 | segment for clipped vertices).
/// Edge-edge contacts: 1 << 30 | edge of a << 12 | edge of b. Returns 1 touching (points in
/// `out`, normal from a to b), 0 separated beyond the margin, -1 not handled (hull too large).
int hullHull(const ConvexHull& a, const Pose& pa, const ConvexHull& b, const Pose& pb,
             double margin, PairContact& out);
int boxHull(const Box& a, const Pose& pa, const ConvexHull& b, const Pose& pb, double margin,
            PairContact& out);

}  // namespace coulomb::geometry
