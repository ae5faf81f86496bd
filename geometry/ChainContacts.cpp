#include <coulomb/geometry/ChainContacts.hpp>

#include <coulomb/geometry/PrimitiveContacts.hpp>

#include <algorithm>
#include <tuple>
#include <variant>

namespace coulomb::geometry {
namespace {

// One single-point manifold between a sphere and a capsule, seen from the sphere.
struct SphereCapsuleContact {
  std::size_t manifold = 0;
  ColliderId sphere, capsule;
  BodyId capsuleBody;
  Eigen::Vector3d centre, end0, end1;  // sphere centre, capsule segment ends (world)
  double radius = 0.0;                 // capsule radius
  double gap = 0.0;                    // -depth of the manifold's point
};

// Groups (sphere, other body), nearest first inside a group: only an earlier (nearer, or as near
// with a lower id) capsule may cover a cap, so the nearest contact of a group is always kept.
bool byGroup(const SphereCapsuleContact& l, const SphereCapsuleContact& r) {
  return std::tie(l.sphere, l.capsuleBody, l.gap, l.capsule) <
         std::tie(r.sphere, r.capsuleBody, r.gap, r.capsule);
}

}  // namespace

void dropCoveredCapsuleEnds(const std::vector<Collider>& colliders,
                            std::span<const Pose> shapePoses,
                            std::vector<ContactManifold>& manifolds,
                            std::vector<std::tuple<ColliderId, BodyId, std::size_t>>* keyList) {
  // Cheap exit first: a ghost needs two single-point manifolds of one collider with one body.
  std::vector<std::tuple<ColliderId, BodyId, std::size_t>> local;
  std::vector<std::tuple<ColliderId, BodyId, std::size_t>>& keys =
      keyList != nullptr ? *keyList : local;
  keys.clear();
  for (std::size_t m = 0; m < manifolds.size(); ++m) {
    if (manifolds[m].pointCount != 1) continue;
    keys.emplace_back(manifolds[m].colliderA, manifolds[m].bodyB, m);
    keys.emplace_back(manifolds[m].colliderB, manifolds[m].bodyA, m);
  }
  std::sort(keys.begin(), keys.end());
  bool shared = false;
  for (std::size_t k = 1; k < keys.size() && !shared; ++k)
    shared = std::get<0>(keys[k]) == std::get<0>(keys[k - 1]) &&
             std::get<1>(keys[k]) == std::get<1>(keys[k - 1]);
  if (!shared) return;

  std::vector<std::pair<ColliderId, std::size_t>> index(colliders.size());
  for (std::size_t i = 0; i < colliders.size(); ++i) index[i] = {colliders[i].id, i};
  std::sort(index.begin(), index.end());
  auto find = [&](ColliderId id) -> const Collider* {
    const auto it =
        std::lower_bound(index.begin(), index.end(), std::make_pair(id, std::size_t{0}));
    if (it == index.end() || it->first != id || it->second >= shapePoses.size()) return nullptr;
    return &colliders[it->second];
  };
  std::vector<SphereCapsuleContact> contacts;
  for (std::size_t m = 0; m < manifolds.size(); ++m) {
    const ContactManifold& man = manifolds[m];
    if (man.pointCount != 1) continue;
    const Collider* a = find(man.colliderA);
    const Collider* b = find(man.colliderB);
    if (!a || !b || !a->shape || !b->shape) continue;
    if (std::holds_alternative<Capsule>(*a->shape)) std::swap(a, b);
    if (!std::holds_alternative<Sphere>(*a->shape) || !std::holds_alternative<Capsule>(*b->shape))
      continue;
    const Capsule& capsule = std::get<Capsule>(*b->shape);
    const Pose& pose = shapePoses[static_cast<std::size_t>(b - colliders.data())];
    SphereCapsuleContact c;
    c.manifold = m;
    c.sphere = a->id;
    c.capsule = b->id;
    c.capsuleBody = b->body;
    c.centre = shapePoses[static_cast<std::size_t>(a - colliders.data())].position;
    c.end0 = pose.apply(Eigen::Vector3d(0.0, 0.0, -capsule.halfLength));
    c.end1 = pose.apply(Eigen::Vector3d(0.0, 0.0, capsule.halfLength));
    c.radius = capsule.radius;
    c.gap = -man.points[0].depth;
    contacts.push_back(c);
  }
  std::sort(contacts.begin(), contacts.end(), byGroup);

  std::vector<char> drop(manifolds.size(), 0);
  for (std::size_t begin = 0; begin < contacts.size();) {
    std::size_t end = begin + 1;
    while (end < contacts.size() && contacts[end].sphere == contacts[begin].sphere &&
           contacts[end].capsuleBody == contacts[begin].capsuleBody)
      ++end;
    for (std::size_t i = begin + 1; i < end; ++i) {
      const SphereCapsuleContact& c = contacts[i];
      const Eigen::Vector3d axis = c.end1 - c.end0;
      const double s =
          axis.squaredNorm() > 0.0 ? (c.centre - c.end0).dot(axis) / axis.squaredNorm() : 0.0;
      // A side point is never a ghost; within 1e-9 of an end (a ball right over a joint, where
      // rounding decides which capsule's side it is on) it counts as the cap.
      if (s > 1e-9 && s < 1.0 - 1e-9) continue;
      const Eigen::Vector3d cap = s <= 0.5 ? c.end0 : c.end1;
      for (std::size_t j = begin; j < i; ++j) {
        const SphereCapsuleContact& o = contacts[j];
        // The cap (ball of radius c.radius about `cap`) lies inside capsule o: 1e-6 r of slack
        // for chains whose shared ends were written with rounded coordinates.
        Eigen::Vector3d onAxis, unused;
        closestSegmentPoints(cap, cap, o.end0, o.end1, unused, onAxis);
        if ((cap - onAxis).norm() + c.radius <= o.radius * (1.0 + 1e-6)) {
          drop[c.manifold] = 1;
          break;
        }
      }
    }
    begin = end;
  }
  std::size_t kept = 0;
  for (std::size_t m = 0; m < manifolds.size(); ++m)
    if (!drop[m]) {
      if (kept != m) manifolds[kept] = manifolds[m];
      ++kept;
    }
  manifolds.resize(kept);
}

}  // namespace coulomb::geometry
