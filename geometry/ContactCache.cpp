#include <coulomb/geometry/ContactCache.hpp>

#include <algorithm>
#include <array>
#include <tuple>

namespace coulomb::geometry {
namespace {

bool byColliders(const ContactManifold& l, const ContactManifold& r) {
  return std::tie(l.colliderA, l.colliderB) < std::tie(r.colliderA, r.colliderB);
}

void carryOver(const ContactManifold& old, ContactManifold& fresh, std::span<const Pose> bodyPoses,
               const ContactCacheSettings& settings) {
  if (old.normal.dot(fresh.normal) < settings.normalAgreement) return;
  std::array<bool, ContactManifold::kMaxPoints> used{};
  auto take = [&](ContactPoint& point, int k) {
    const ContactPoint& from = old.points[static_cast<std::size_t>(k)];
    used[static_cast<std::size_t>(k)] = true;
    point.normalImpulse = from.normalImpulse;
    point.tangentImpulse = from.tangentImpulse;
    point.warmStarted = true;
  };
  const bool havePoses =
      fresh.bodyA.index < bodyPoses.size() && fresh.bodyB.index < bodyPoses.size();
  for (ContactPoint& point : fresh.activePoints()) {
    int match = -1;
    for (int k = 0; k < old.pointCount && match < 0; ++k)
      if (!used[static_cast<std::size_t>(k)] &&
          old.points[static_cast<std::size_t>(k)].featureId == point.featureId)
        match = k;
    if (match < 0 && havePoses) {  // feature changed: nearest old anchor, seen from both bodies
      double best = settings.matchDistance;
      for (int k = 0; k < old.pointCount; ++k) {
        if (used[static_cast<std::size_t>(k)]) continue;
        const ContactPoint& o = old.points[static_cast<std::size_t>(k)];
        const double da = (bodyPoses[fresh.bodyA.index].apply(o.localA) - point.position).norm();
        const double db = (bodyPoses[fresh.bodyB.index].apply(o.localB) - point.position).norm();
        if (std::max(da, db) <= best) best = std::max(da, db), match = k;
      }
    }
    if (match >= 0) take(point, match);
  }
}

}  // namespace

const std::vector<ContactManifold>& ContactCache::refresh(std::vector<ContactManifold>& fresh,
                                                          std::span<const Pose> bodyPoses) {
  if (!std::is_sorted(fresh.begin(), fresh.end(), byColliders))  // NarrowPhase output already is
    std::sort(fresh.begin(), fresh.end(), byColliders);
  auto old = manifolds_.begin();
  for (ContactManifold& m : fresh) {
    old = std::lower_bound(old, manifolds_.end(), m, byColliders);
    if (old != manifolds_.end() && old->colliderA == m.colliderA && old->colliderB == m.colliderB)
      carryOver(*old, m, bodyPoses, settings_);
  }
  manifolds_.swap(fresh);
  return manifolds_;
}

void ContactCache::restore(std::vector<ContactManifold> saved) {
  std::sort(saved.begin(), saved.end(), byColliders);
  manifolds_ = std::move(saved);
}

}  // namespace coulomb::geometry
