#include <coulomb/geometry/ContinuousCollision.hpp>

#include <coulomb/geometry/RayCast.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

namespace coulomb::geometry {
namespace {

Eigen::Vector3d at(std::span<const Eigen::Vector3d> values, std::uint32_t index) {
  return index < values.size() && values[index].allFinite() ? values[index]
                                                            : Eigen::Vector3d::Zero();
}

// A body's motion over the step: from `start`, the constant velocities (v, w) for h seconds.
struct BodyPath {
  Pose start;
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  Eigen::Vector3d w = Eigen::Vector3d::Zero();
  double h = 0.0;

  [[nodiscard]] Pose at(double s) const {
    Pose pose = start;
    pose.position += s * h * v;
    const double angle = w.norm() * s * h;
    if (angle > 0)
      pose.rotation =
          (Eigen::Quaterniond(Eigen::AngleAxisd(angle, w.normalized())) * start.rotation)
              .normalized();
    return pose;
  }
  // How far any point of the collider can move over the whole path [m].
  [[nodiscard]] double reach(const Collider& c) const {
    return h * (v.norm() + w.norm() * (c.localPose.position.norm() + rotationReach(*c.shape)));
  }
};

struct Touch {
  double s = 0.0;                                      // fraction of the step; 0: at the start
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   // moving -> other
  Eigen::Vector3d onMoving = Eigen::Vector3d::Zero();  // at s, in the other's start frame
  Eigen::Vector3d onOther = Eigen::Vector3d::Zero();   // the other's point at its start pose
  Pose movingShape;                                    // the moving shape's pose that gave them
};

bool sweepable(const Collider& c) {
  return c.continuous && !std::holds_alternative<Plane>(*c.shape) &&
         !std::holds_alternative<TriangleMesh>(*c.shape);
}

// First touch (gap <= tolerance) of two colliders moving along their paths, by conservative
// advancement (Mirtich 1996): the gap closes at most at the sum of the reaches per unit of s, so
// advancing by gap / (reach_m + reach_o) never passes a contact. The distance is that of the
// moving shape placed relative to the other, with the other at its start pose (where the scene
// holds it): the same number, and only one FCL object moves.
std::optional<Touch> firstTouch(const Collider& moving, const BodyPath& pathM,
                                const Collider& other, const BodyPath& pathO,
                                const Pose& otherShapeStart, const FclScene& scene,
                                double tolerance, FclQueryShape& query) {
  const double bound = pathM.reach(moving) + pathO.reach(other);
  const auto* plane = std::get_if<Plane>(other.shape.get());
  Touch touch;
  double gap = 0.0;
  auto evaluate = [&](double s) {
    const Pose poseM = pathM.at(s) * moving.localPose;
    const Pose poseO = pathO.at(s) * other.localPose;
    touch.movingShape = otherShapeStart * (poseO.inverse() * poseM);
    if (plane != nullptr) {
      const double norm = plane->normal.norm();
      const Eigen::Vector3d n = otherShapeStart.rotation * (plane->normal / norm);
      const double offset = plane->offset / norm + n.dot(otherShapeStart.position);
      touch.onMoving = touch.movingShape.apply(
          supportPoint(*moving.shape, touch.movingShape.rotation.conjugate() * -n));
      gap = n.dot(touch.onMoving) - offset;
      touch.onOther = touch.onMoving - gap * n;
      touch.normal = -n;
      return true;
    }
    query.setPose(touch.movingShape);
    const FclDistanceResult r = scene.distance(query, other.id);
    if (!r.error.empty()) return false;
    gap = r.distance;
    touch.onMoving = r.pointA;
    touch.onOther = r.pointB;
    const Eigen::Vector3d between = r.pointB - r.pointA;
    if (gap > 0 && between.norm() > 1e-12) touch.normal = between.normalized();
    return true;
  };
  if (!evaluate(0.0)) return std::nullopt;
  if (gap <= tolerance) return touch;  // s = 0
  if (!(bound > 0) || !std::isfinite(bound)) return std::nullopt;
  for (int iteration = 0; iteration < 64; ++iteration) {
    touch.s += gap / bound;
    if (touch.s > 1.0 || !evaluate(touch.s)) return std::nullopt;
    if (gap <= tolerance) return touch;
  }
  return std::nullopt;  // still apart after 64 advances: slower than the bound says
}

template <class Visit>
void forContinuousPairs(const std::vector<Collider>& colliders,
                        const std::vector<std::size_t>& byId,
                        std::vector<ContactManifold>& manifolds, const Visit& visit) {
  auto indexOf = [&](ColliderId id) -> std::optional<std::size_t> {
    auto it = std::lower_bound(byId.begin(), byId.end(), id, [&](std::size_t k, ColliderId key) {
      return colliders[k].id < key;
    });
    if (it == byId.end() || colliders[*it].id != id) return std::nullopt;
    return *it;
  };
  for (ContactManifold& m : manifolds) {
    if (m.sensor || !m.enabled) continue;  // nothing to stop at
    const auto ia = indexOf(m.colliderA), ib = indexOf(m.colliderB);
    if (!ia || !ib || !(sweepable(colliders[*ia]) || sweepable(colliders[*ib]))) continue;
    visit(m, *ia, *ib);
  }
}

BodyPath pathOf(std::span<const Pose> poses, std::span<const Eigen::Vector3d> v,
                std::span<const Eigen::Vector3d> w, std::uint32_t body, double h) {
  return {poses[body], at(v, body), at(w, body), h};
}

}  // namespace

int applyContinuousCollision(const std::vector<Collider>& colliders,
                             const std::vector<std::size_t>& byId, std::span<const Pose> shapePoses,
                             std::span<const Pose> bodyPoses, const SweepMotion& motion,
                             const FclScene& scene, double tolerance,
                             std::vector<ContactManifold>& manifolds) {
  if (!(motion.h > 0)) return 0;
  int replaced = 0;
  forContinuousPairs(
      colliders, byId, manifolds, [&](ContactManifold& m, std::size_t ia, std::size_t ib) {
        const Collider& a = colliders[ia];
        const Collider& b = colliders[ib];
        if (a.body.index >= bodyPoses.size() || b.body.index >= bodyPoses.size()) return;
        const BodyPath pathA = pathOf(bodyPoses, motion.linearVelocities, motion.angularVelocities,
                                      a.body.index, motion.h);
        const BodyPath pathB = pathOf(bodyPoses, motion.linearVelocities, motion.angularVelocities,
                                      b.body.index, motion.h);
        // The swept one: the continuous collider (the one that moves farther when both are).
        const bool aMoves = sweepable(a) && (!sweepable(b) || pathA.reach(a) >= pathB.reach(b));
        const std::size_t im = aMoves ? ia : ib, io = aMoves ? ib : ia;
        FclQueryShape query(colliders[im].shape);
        const auto touch =
            firstTouch(colliders[im], aMoves ? pathA : pathB, colliders[io], aMoves ? pathB : pathA,
                       shapePoses[io], scene, tolerance, query);
        if (!touch || touch->s == 0.0) return;  // apart all step, or touching now: as it is
        // The features that meet, where they are at the start of the step: the moving collider's
        // point (fixed in it) and the other's (evaluated at its start pose).
        const Eigen::Vector3d onMoving =
            shapePoses[im].apply(touch->movingShape.applyInverse(touch->onMoving));
        const double startGap = std::max(0.0, touch->normal.dot(touch->onOther - onMoving));
        m.normal = aMoves ? touch->normal : Eigen::Vector3d(-touch->normal);  // A -> B
        makeTangentFrame(m.normal, m.tangent1, m.tangent2);
        ContactPoint point;
        point.position = onMoving;  // the row's lever arms: the fast body's point
        point.depth = -startGap;
        point.featureId = kTimeOfImpactFeature;
        point.localA = bodyPoses[m.bodyA.index].applyInverse(onMoving);
        point.localB = bodyPoses[m.bodyB.index].applyInverse(onMoving);
        m.points[0] = point;
        m.pointCount = 1;
        ++replaced;
      });
  return replaced;
}

std::size_t clampToTimeOfImpact(const std::vector<Collider>& colliders,
                                const std::vector<std::size_t>& byId,
                                std::span<const Pose> shapePoses,
                                std::span<const Pose> startBodyPoses, BodyState& state, double h,
                                const FclScene& scene, double tolerance,
                                std::vector<ContactManifold>& manifolds) {
  // The earliest first touch per body, over every pair it had a manifold with this step.
  std::vector<std::pair<std::uint32_t, double>> earliest;
  forContinuousPairs(
      colliders, byId, manifolds, [&](ContactManifold&, std::size_t ia, std::size_t ib) {
        for (const bool aMoves : {true, false}) {
          const Collider& moving = colliders[aMoves ? ia : ib];
          const Collider& other = colliders[aMoves ? ib : ia];
          const std::uint32_t body = moving.body.index;
          if (!sweepable(moving) || body >= startBodyPoses.size() || body >= state.size() ||
              other.body.index >= startBodyPoses.size() || !state.isDynamic(body))
            continue;
          const BodyPath pathM =
              pathOf(startBodyPoses, state.linearVelocities, state.angularVelocities, body, h);
          const BodyPath pathO = pathOf(startBodyPoses, state.linearVelocities,
                                        state.angularVelocities, other.body.index, h);
          FclQueryShape query(moving.shape);
          const auto touch = firstTouch(moving, pathM, other, pathO, shapePoses[aMoves ? ib : ia],
                                        scene, tolerance, query);
          if (!touch || touch->s == 0.0) continue;
          earliest.emplace_back(body, touch->s);
        }
      });
  std::sort(earliest.begin(), earliest.end());
  std::size_t clamped = 0;
  for (std::size_t k = 0; k < earliest.size(); ++k) {
    if (k > 0 && earliest[k].first == earliest[k - 1].first) continue;  // sorted: smallest s
    const std::uint32_t body = earliest[k].first;
    const BodyPath path{startBodyPoses[body], state.linearVelocities[body],
                        state.angularVelocities[body], h};
    state.poses[body] = path.at(earliest[k].second);
    state.refreshWorldInertia(body);
    ++clamped;
  }
  return clamped;
}

}  // namespace coulomb::geometry
