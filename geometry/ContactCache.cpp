#include <coulomb/geometry/ContactCache.hpp>

#include <algorithm>
#include <array>
#include <tuple>

namespace coulomb::geometry {
namespace {

bool byColliders(const ContactManifold& l, const ContactManifold& r) {
  return std::tie(l.colliderA, l.colliderB) < std::tie(r.colliderA, r.colliderB);
}

// The old tangent impulse as a world vector, in the fresh manifold's tangent frame: the frame is a
// function of the normal (makeTangentFrame) that turns with it and flips where n_z changes sign,
// and a warm start in a stale frame pushes the wrong way (docs/solver-derivations.md section 11
// pitfall 8).
Eigen::Vector2d rotatedTangentImpulse(const ContactManifold& old, const ContactPoint& from,
                                      const ContactManifold& fresh) {
  const Eigen::Vector3d world =
      from.tangentImpulse[0] * old.tangent1 + from.tangentImpulse[1] * old.tangent2;
  return {fresh.tangent1.dot(world), fresh.tangent2.dot(world)};
}

// The last solve's normal row goes with the impulses. A pair handed over with its colliders in
// the other order has A and B swapped: the normal and its moments change sign and the moments swap
// bodies (the normal velocity n . (v_B - v_A) is the same).
void copySolvedRow(const ContactPoint& from, ContactPoint& to, double sign) {
  to.solvedNormal = sign * from.solvedNormal;
  to.solvedMomentA = sign > 0 ? from.solvedMomentA : Eigen::Vector3d(-from.solvedMomentB);
  to.solvedMomentB = sign > 0 ? from.solvedMomentB : Eigen::Vector3d(-from.solvedMomentA);
  to.solvedNormalVelocity = from.solvedNormalVelocity;
}

void carryOver(const ContactManifold& old, ContactManifold& fresh, std::span<const Pose> bodyPoses,
               const ContactCacheSettings& settings) {
  if (old.normal.dot(fresh.normal) < settings.normalAgreement) return;
  std::array<bool, ContactManifold::kMaxPoints> used{};
  auto take = [&](ContactPoint& point, int k) {
    const ContactPoint& from = old.points[static_cast<std::size_t>(k)];
    used[static_cast<std::size_t>(k)] = true;
    point.normalImpulse = from.normalImpulse;
    point.tangentImpulse = rotatedTangentImpulse(old, from, fresh);
    point.warmStarted = true;
    copySolvedRow(from, point, 1.0);
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

void ContactCache::handOver(std::vector<ContactManifold>& fresh,
                            std::span<const std::size_t> orphans,
                            const std::vector<char>& continued) const {
  // Old one-point manifolds that ended, keyed by (their collider, the other body): a ball rolling
  // from one capsule of a rail (or one piece of a compound body) onto the next has one collider in
  // common with its last contact, the same other body and nearly the same normal.
  std::vector<std::pair<ColliderId, BodyId>> wanted;  // what the orphans can match
  for (const std::size_t f : orphans) {
    wanted.emplace_back(fresh[f].colliderA, fresh[f].bodyB);
    wanted.emplace_back(fresh[f].colliderB, fresh[f].bodyA);
  }
  std::sort(wanted.begin(), wanted.end());
  std::vector<std::tuple<ColliderId, BodyId, std::size_t>> ended;
  for (std::size_t k = 0; k < manifolds_.size(); ++k) {
    const ContactManifold& o = manifolds_[k];
    if (continued[k] || o.pointCount != 1) continue;
    for (const auto& key : {std::pair{o.colliderA, o.bodyB}, {o.colliderB, o.bodyA}})
      if (std::binary_search(wanted.begin(), wanted.end(), key))
        ended.emplace_back(key.first, key.second, k);
  }
  if (ended.empty()) return;
  std::sort(ended.begin(), ended.end());
  std::vector<char> taken(manifolds_.size(), 0);
  for (const std::size_t f : orphans) {
    ContactManifold& m = fresh[f];
    int best = -1;
    double agreement = settings_.normalAgreement;
    for (const auto& [collider, other] : {std::pair{m.colliderA, m.bodyB}, {m.colliderB, m.bodyA}})
      for (auto it = std::lower_bound(ended.begin(), ended.end(),
                                      std::make_tuple(collider, other, std::size_t{0}));
           it != ended.end() && std::get<0>(*it) == collider && std::get<1>(*it) == other; ++it) {
        const std::size_t k = std::get<2>(*it);
        const ContactManifold& o = manifolds_[k];
        if (taken[k]) continue;
        // Collider order decides which body is A: a swapped pair has the opposite normal.
        const double a = (o.bodyA == m.bodyA ? 1.0 : -1.0) * o.normal.dot(m.normal);
        if (a >= agreement) agreement = a, best = static_cast<int>(k);
      }
    if (best < 0) continue;
    taken[static_cast<std::size_t>(best)] = 1;
    const ContactManifold& o = manifolds_[static_cast<std::size_t>(best)];
    m.points[0].normalImpulse = o.points[0].normalImpulse;
    m.points[0].tangentImpulse =
        (o.bodyA == m.bodyA ? 1.0 : -1.0) * rotatedTangentImpulse(o, o.points[0], m);
    m.points[0].warmStarted = true;
    copySolvedRow(o.points[0], m.points[0], o.bodyA == m.bodyA ? 1.0 : -1.0);
  }
}

const std::vector<ContactManifold>& ContactCache::refresh(std::vector<ContactManifold>& fresh,
                                                          std::span<const Pose> bodyPoses) {
  if (!std::is_sorted(fresh.begin(), fresh.end(), byColliders))  // NarrowPhase output already is
    std::sort(fresh.begin(), fresh.end(), byColliders);
  auto old = manifolds_.begin();
  std::vector<char>& continued = continued_;
  continued.assign(manifolds_.size(), 0);
  std::vector<std::size_t>& orphans = orphans_;  // fresh one-point manifolds of a pair new now
  orphans.clear();
  for (std::size_t f = 0; f < fresh.size(); ++f) {
    ContactManifold& m = fresh[f];
    old = std::lower_bound(old, manifolds_.end(), m, byColliders);
    if (old != manifolds_.end() && old->colliderA == m.colliderA && old->colliderB == m.colliderB) {
      carryOver(*old, m, bodyPoses, settings_);
      continued[static_cast<std::size_t>(old - manifolds_.begin())] = 1;
    } else if (m.pointCount == 1) {
      orphans.push_back(f);
    }
  }
  if (!orphans.empty()) handOver(fresh, orphans, continued);
  manifolds_.swap(fresh);
  return manifolds_;
}

void ContactCache::restore(std::vector<ContactManifold> saved) {
  std::sort(saved.begin(), saved.end(), byColliders);
  manifolds_ = std::move(saved);
}

}  // namespace coulomb::geometry
