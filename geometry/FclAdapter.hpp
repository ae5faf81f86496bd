#pragma once
// The one door to FCL (the only file pair that sees FCL headers is FclAdapter.cpp). It owns one
// FCL geometry + CollisionObject per collider and FCL's dynamic AABB tree, and answers guarded
// queries: any exception or non-finite output from FCL/libccd comes back as an error string for
// that pair, never as a throw (docs/fcl-notes.md section 9, "Ordering and guards").
#include <coulomb/geometry/Ids.hpp>
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/geometry/Shape.hpp>

#include <Eigen/Core>

#include <cstdint>

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace coulomb::geometry {

struct MeshSurface;  // MeshEdges.hpp

struct Aabb {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
};

/// One contact as FCL reports it, already re-oriented so the normal points from a to b.
struct FclContact {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double depth = 0.0;
  int triangleA = -1;  // mesh triangle index on a's side, -1 for primitives
  int triangleB = -1;
};

struct FclCollideResult {
  std::vector<FclContact> contacts;  // only finite contacts with a usable (|n| >= 0.5) normal
  std::string error;                 // non-empty when FCL threw or returned NaN
};

struct FclDistanceResult {
  double distance = 0.0;
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero();  // world frame
  Eigen::Vector3d pointB = Eigen::Vector3d::Zero();
  int triangleA = -1;  // the mesh triangle of the nearest points on a's side, -1 for primitives
  int triangleB = -1;
  std::string error;
};

/// Called inside the guarded region of every query (tests use it to throw as FCL would).
using FclFaultInjector = std::function<void(ColliderId a, ColliderId b)>;

class FclScene;

/// A shape that is not in a scene, posed for the scene queries of FclScene (overlap, closest
/// points, shape casts): a sphere, box, capsule, cylinder or convex hull.
class FclQueryShape {
 public:
  /// Throws std::invalid_argument for a missing, invalid, plane or mesh shape.
  explicit FclQueryShape(const std::shared_ptr<const Shape>& shape);
  ~FclQueryShape();
  FclQueryShape(FclQueryShape&&) noexcept;
  FclQueryShape& operator=(FclQueryShape&&) noexcept;
  FclQueryShape(const FclQueryShape&) = delete;
  FclQueryShape& operator=(const FclQueryShape&) = delete;

  void setPose(const Pose& worldPose);   // throws std::invalid_argument if not finite
  [[nodiscard]] Aabb worldAabb() const;  // tight, at the pose last set
  [[nodiscard]] const Shape& shape() const;

 private:
  friend class FclScene;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class FclScene {
 public:
  /// `aabbMargin` [m] fattens every AABB so pairs closer than it reach the narrow phase.
  explicit FclScene(double aabbMargin);
  ~FclScene();
  FclScene(FclScene&&) noexcept;
  FclScene& operator=(FclScene&&) noexcept;
  FclScene(const FclScene&) = delete;
  FclScene& operator=(const FclScene&) = delete;

  /// Creates (or rebuilds, when the shape pointer changed) the FCL geometry of a collider.
  /// Throws std::invalid_argument naming the collider when the shape is degenerate.
  /// Planes get an fcl::Halfspace but are kept out of the tree (docs/fcl-notes.md section 4.8).
  void upsert(ColliderId id, const std::shared_ptr<const Shape>& shape);
  void erase(ColliderId id);
  [[nodiscard]] bool contains(ColliderId id) const;
  [[nodiscard]] std::vector<ColliderId> ids() const;  // sorted
  [[nodiscard]] std::size_t size() const;

  /// World pose of the collider's shape frame; throws std::invalid_argument if not finite.
  /// `sweep` [m] grows its AABB beyond the margin (velocity-swept margin, SweptMargin.hpp).
  void setPose(ColliderId id, const Pose& worldPose, double sweep = 0.0);
  /// Refits the tree after setPose calls (one rebalance for all moved objects).
  void updateTree();
  /// Every pair of tree objects whose (fattened) AABBs overlap, as (lower id, higher id), sorted,
  /// into `pairs` (cleared first; its capacity is reused, so a steady step does not allocate).
  void overlappingPairs(std::vector<std::pair<ColliderId, ColliderId>>& pairs) const;
  [[nodiscard]] Aabb worldAabb(ColliderId id) const;
  /// A mesh collider's active edges and smooth patches (MeshEdges.hpp), computed once in
  /// upsert; nullptr for other shapes.
  [[nodiscard]] const MeshSurface* meshSurface(ColliderId id) const;
  /// The triangles of a mesh collider whose bounding boxes overlap the world box `box` (from its
  /// BVH; a superset of the touching ones), ascending, into `out` (cleared first).
  void meshTrianglesNear(ColliderId mesh, const Aabb& box, std::vector<int>& out) const;

  /// fcl::collide with GST_LIBCCD. Meshes go first as FCL requires; the result is re-oriented.
  [[nodiscard]] FclCollideResult collide(ColliderId a, ColliderId b, int maxContacts,
                                         const FclFaultInjector& inject = {}) const;
  /// fcl::distance for separated pairs (never with a plane: FCL crashes, fcl#623).
  [[nodiscard]] FclDistanceResult distance(ColliderId a, ColliderId b,
                                           const FclFaultInjector& inject = {}) const;

  /// Scene queries, valid after updateTree: colliders whose tight world AABB overlaps `box`
  /// (planes whose half-space reaches it), sorted by id.
  void queryAabb(const Aabb& box, std::vector<ColliderId>& out) const;
  /// Candidates of a ray (unit `direction`, t in [0, maxDistance]): colliders whose tree box it
  /// crosses, and every plane; sorted by id. The exact test is rayCastShape (RayCast.hpp).
  void queryRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double maxDistance,
                std::vector<ColliderId>& out) const;
  /// fcl::collide / fcl::distance of a query shape (first, "a") against a collider ("b").
  [[nodiscard]] FclCollideResult collide(const FclQueryShape& query, ColliderId b,
                                         int maxContacts) const;
  [[nodiscard]] FclDistanceResult distance(const FclQueryShape& query, ColliderId b) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace coulomb::geometry
