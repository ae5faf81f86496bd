#pragma once
// Box-box and box-capsule manifolds built by hand (conventions as in PrimitiveContacts.hpp).
// Box-box: separating-axis test over the 15 axes, then the incident face clipped against the
// reference face (Ericson, Real-Time Collision Detection 4.4 and 5.2.1; Gregorius, "Robust
// Contact Creation for Physics Simulations", GDC 2015), which gives the 4 corners of a resting
// box in its first step, with feature ids, and speculative points inside the margin.
#include <coulomb/geometry/ManifoldBuilder.hpp>
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/geometry/Shape.hpp>

namespace coulomb::geometry {

/// Feature ids of a box-box face contact: (reference is b) << 31 | reference face << 20 |
/// incident face << 12 | clip vertex id (ManifoldBuilder clipPolygon); faces are 2*axis + (sign<0).
/// Edge-edge contacts: 1 << 30 | edge axis of a << 4 | edge axis of b.
bool boxBox(const Box& a, const Pose& pa, const Box& b, const Pose& pb, double margin,
            PairContact& out);

enum class BoxCapsuleResult { Separated, Touching, AxisInsideBox };
/// Segment-to-box closest points; a capsule lying on a face gets the two ends of its segment
/// clipped to that face (ids 0, 1), other contacts one point (id 2). AxisInsideBox means the
/// capsule's axis itself enters the box (a deep overlap): the caller falls back to FCL.
BoxCapsuleResult boxCapsule(const Box& a, const Pose& pa, const Capsule& b, const Pose& pb,
                            double margin, PairContact& out);

}  // namespace coulomb::geometry
