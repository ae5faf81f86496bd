#pragma once
// From the raw points of one touching pair to a ContactManifold: at most 4 points chosen to span
// the contact area (area-maximising reduction, docs/fcl-notes.md section 9), a deterministic
// tangent frame, body-frame anchors and the combined material. The shape-pair routines that produce
// the raw points live in PrimitiveContacts / BoxContacts (closed forms) and NarrowPhase (FCL).
#include <coulomb/geometry/Collider.hpp>
#include <coulomb/geometry/ContactManifold.hpp>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace coulomb::geometry {

/// One candidate point: world position midway between the surfaces, depth (> 0 overlapping,
/// < 0 gap within the speculative margin) and a feature id that stays fixed while the same
/// features touch.
struct ContactCandidate {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double depth = 0.0;
  std::uint32_t featureId = 0;
};

/// Raw output of a shape-pair routine: one normal (from the routine's first shape to its second)
/// and any number of candidate points.
struct PairContact {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  std::vector<ContactCandidate> points;
};

/// Keeps at most 4 points: the deepest, the farthest from it, the one making the largest triangle,
/// the one adding the most area outside that triangle. Ties go to the lower feature id, so the
/// result never depends on the input order.
void reduceToFour(const Eigen::Vector3d& normal, std::vector<ContactCandidate>& points);

/// Sutherland-Hodgman clip of a convex polygon against the half-plane {x : axis.x <= limit}.
/// Input vertices carry ids 0..3; a vertex created on clip line `plane` (0..3) gets
/// 0x100 | (plane << 4) | segment, where segment is the input edge (0..3) or 4 + the earlier clip
/// line it lies on, so ids are unique and stable under small motions.
struct ClipVertex {
  Eigen::Vector3d position;
  std::uint32_t id = 0;
};
/// A quadrilateral clipped by four lines has at most 8 vertices (each line adds at most one to a
/// convex polygon), so the clip works in place without touching the heap in the narrow phase.
struct ClipPolygon {
  static constexpr std::size_t kCapacity = 8;
  std::array<ClipVertex, kCapacity> vertices;
  std::size_t count = 0;
  std::size_t size() const { return count; }
  const ClipVertex& operator[](std::size_t i) const { return vertices[i]; }
  const ClipVertex* begin() const { return vertices.data(); }
  const ClipVertex* end() const { return vertices.data() + count; }
};
/// Needs polygon.size() < ClipPolygon::kCapacity (a quad after at most three earlier clips).
void clipPolygon(ClipPolygon& polygon, const Eigen::Vector3d& axis, double limit,
                 std::uint32_t plane);

/// Builds the final manifold (<= 4 points, tangent frame, anchors, material). `raw.normal` must
/// already point from collider a to collider b; a.id < b.id.
ContactManifold finishManifold(PairContact& raw, const Collider& a, const Collider& b,
                               const Pose& bodyPoseA, const Pose& bodyPoseB);

}  // namespace coulomb::geometry
