#include <coulomb/geometry/SceneQuery.hpp>

#include <coulomb/geometry/RayCast.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace coulomb::geometry {
namespace {

struct Synced {
  Collider collider;
  Pose world;  // of the shape frame
  bool posed = false;
};

bool samePose(const Pose& a, const Pose& b) {
  return a.rotation.coeffs() == b.rotation.coeffs() && a.position == b.position;
}

std::string name(ColliderId id) {
  return "collider " + std::to_string(id.index) + "." + std::to_string(id.generation);
}

void requireFinite(const Eigen::Vector3d& v, const char* what) {
  if (!v.allFinite())
    throw std::invalid_argument(std::string(what) + " is not finite (NaN or inf)");
}

// Half-space {n.x <= offset} of a plane collider, in world frame, n unit.
void worldPlane(const Plane& plane, const Pose& pose, Eigen::Vector3d& n, double& offset) {
  const double norm = plane.normal.norm();
  n = pose.rotation * (plane.normal / norm);
  offset = plane.offset / norm + n.dot(pose.position);
}

// The point of `shape` at `pose` deepest along -n (its support point in -n), world frame.
Eigen::Vector3d lowestPoint(const Shape& shape, const Pose& pose, const Eigen::Vector3d& n) {
  return pose.apply(supportPoint(shape, pose.rotation.conjugate() * (-n)));
}

}  // namespace

struct SceneQuery::Impl {
  FclScene scene{0.0};
  std::vector<Synced> items;      // in the order sync() received them; posed == false: left out
  std::vector<std::size_t> byId;  // indices into items, sorted by collider id

  const Synced* find(ColliderId id) const {
    auto it = std::lower_bound(byId.begin(), byId.end(), id, [this](std::size_t k, ColliderId key) {
      return items[k].collider.id < key;
    });
    if (it == byId.end() || items[*it].collider.id != id || !items[*it].posed) return nullptr;
    return &items[*it];
  }

  // True when `colliders` are the ones synced last, in the same order, with the same shapes:
  // then only poses can have changed (a world between two steps), and no list is rebuilt.
  bool sameColliders(const std::vector<Collider>& colliders) const {
    if (colliders.size() != items.size()) return false;
    for (std::size_t k = 0; k < colliders.size(); ++k) {
      const Collider& a = colliders[k];
      const Collider& b = items[k].collider;
      if (a.id != b.id || a.shape != b.shape || a.body != b.body ||
          !samePose(a.localPose, b.localPose) || a.filter.category != b.filter.category ||
          a.filter.mask != b.filter.mask)
        return false;
    }
    return true;
  }

  static Synced posed(const Collider& c, std::span<const Pose> bodyPoses) {
    Synced s{c, Pose::identity(), false};
    if (c.shape && c.body.index < bodyPoses.size() && bodyPoses[c.body.index].allFinite()) {
      s.world = bodyPoses[c.body.index] * c.localPose;
      const double norm = s.world.rotation.norm();
      s.posed = s.world.allFinite() && norm > 1e-9;
      if (s.posed) s.world.rotation.coeffs() /= norm;  // unit, as the collision stage makes it
    }
    return s;
  }

  // The colliders of `ids` (sorted) that the filter accepts.
  template <class Visit>
  void forAccepted(const std::vector<ColliderId>& ids, const QueryFilter& filter,
                   const Visit& visit) const {
    for (ColliderId id : ids) {
      const Synced* s = find(id);
      if (s == nullptr || !filter.bits.accepts(s->collider.filter)) continue;
      if (filter.accept && !filter.accept(s->collider)) continue;
      visit(*s);
    }
  }

  // Time of impact (fraction of `translation`) of the query shape moved from `start` against
  // one collider, with the hit point and normal; nullopt when it does not touch it by 1.
  std::optional<ShapeHit> cast(FclQueryShape& query, const Pose& start,
                               const Eigen::Vector3d& translation, const Synced& target) const {
    ShapeHit hit;
    hit.collider = target.collider.id;
    hit.body = target.collider.body;
    if (const auto* plane = std::get_if<Plane>(target.collider.shape.get())) {
      Eigen::Vector3d n;
      double offset = 0;
      worldPlane(*plane, target.world, n, offset);
      const Eigen::Vector3d low = lowestPoint(query.shape(), start, n);
      const double gap = n.dot(low) - offset, rate = n.dot(translation);
      if (gap > 0 && rate >= 0) return std::nullopt;
      hit.fraction = gap <= 0 ? 0.0 : gap / -rate;
      if (hit.fraction > 1.0) return std::nullopt;
      hit.point = low + hit.fraction * translation - std::min(gap, 0.0) * n;
      hit.normal = n;
      return hit;
    }
    // Overlapping at the start: fraction 0, FCL's contact (its normal points query -> target).
    query.setPose(start);
    const FclCollideResult touching = scene.collide(query, target.collider.id, 1);
    if (!touching.error.empty()) return std::nullopt;
    if (!touching.contacts.empty()) {
      hit.point = touching.contacts.front().position;
      hit.normal = -touching.contacts.front().normal;
      return hit;
    }
    // Conservative advancement (Mirtich 1996) on the gap d(t) = dist(shape + t translation,
    // target). For a convex target d is convex in t (the distance from a point moving on a line
    // to the convex set target - shape), so the step to the zero of its tangent, d / -d'(t) with
    // d' = n . translation, never passes the contact and converges like Newton from the left;
    // d' >= 0 means they move apart for good. A mesh is not convex: it gets the step
    // d / |translation|, which bounds the closing speed of any point.
    const bool convex = !std::holds_alternative<TriangleMesh>(*target.collider.shape);
    const double length = translation.norm();
    double t = 0.0;
    for (int iteration = 0; iteration < 100 && length > 0; ++iteration) {
      Pose at = start;
      at.position += t * translation;
      query.setPose(at);
      const FclDistanceResult gap = scene.distance(query, target.collider.id);
      if (!gap.error.empty()) return std::nullopt;
      const Eigen::Vector3d between = gap.pointA - gap.pointB;  // target -> shape
      // At (numerical) touching FCL may answer without points: keep the last normal then.
      const bool pointsValid =
          gap.distance > 0 && std::abs(between.norm() - gap.distance) <= kCastTolerance;
      if (pointsValid) hit.normal = between.normalized();
      if (gap.distance <= kCastTolerance) {
        hit.fraction = t;
        hit.point =
            pointsValid ? gap.pointB : Eigen::Vector3d(lowestPoint(query.shape(), at, hit.normal));
        return hit;
      }
      const double closing = convex ? -hit.normal.dot(translation) : length;
      if (!(closing > 0)) return std::nullopt;
      t += gap.distance / closing;
      if (t > 1.0) return std::nullopt;
    }
    return std::nullopt;
  }
};

SceneQuery::SceneQuery() : impl_(std::make_unique<Impl>()) {}
SceneQuery::~SceneQuery() = default;
SceneQuery::SceneQuery(SceneQuery&&) noexcept = default;
SceneQuery& SceneQuery::operator=(SceneQuery&&) noexcept = default;

void SceneQuery::sync(const std::vector<Collider>& colliders, std::span<const Pose> bodyPoses) {
  FclScene& scene = impl_->scene;
  std::vector<Synced>& items = impl_->items;
  if (impl_->sameColliders(colliders)) {  // between steps: poses only
    bool placed = true;
    for (Synced& s : items) {
      const Synced now = Impl::posed(s.collider, bodyPoses);
      if (now.posed != s.posed) {
        placed = false;
        break;
      }
      if (now.posed && !samePose(now.world, s.world)) {
        scene.setPose(s.collider.id, now.world);
        s.world = now.world;
      }
    }
    if (placed) {
      scene.updateTree();
      return;
    }
  }
  std::vector<Synced> next;
  next.reserve(colliders.size());
  for (const Collider& c : colliders) next.push_back(Impl::posed(c, bodyPoses));
  std::vector<ColliderId> keep;
  for (Synced& s : next) {
    if (!s.posed) continue;
    try {
      scene.upsert(s.collider.id, s.collider.shape);  // no work when the shape is unchanged
      scene.setPose(s.collider.id, s.world);
      keep.push_back(s.collider.id);
    } catch (const std::invalid_argument&) {  // a shape FCL rejects: not queryable
      s.posed = false;
    }
  }
  std::sort(keep.begin(), keep.end());
  for (ColliderId id : scene.ids())
    if (!std::binary_search(keep.begin(), keep.end(), id)) scene.erase(id);
  items = std::move(next);
  impl_->byId.resize(items.size());
  for (std::size_t k = 0; k < items.size(); ++k) impl_->byId[k] = k;
  std::sort(impl_->byId.begin(), impl_->byId.end(), [&items](std::size_t a, std::size_t b) {
    return items[a].collider.id < items[b].collider.id;
  });
  scene.updateTree();
}

std::optional<RayHit> SceneQuery::castRay(const Eigen::Vector3d& origin,
                                          const Eigen::Vector3d& translation,
                                          const QueryFilter& filter) const {
  std::vector<RayHit> all = castRayAll(origin, translation, filter);
  if (all.empty()) return std::nullopt;
  return all.front();
}

std::vector<RayHit> SceneQuery::castRayAll(const Eigen::Vector3d& origin,
                                           const Eigen::Vector3d& translation,
                                           const QueryFilter& filter) const {
  requireFinite(origin, "ray cast: origin");
  requireFinite(translation, "ray cast: translation");
  std::vector<RayHit> hits;
  const double length = translation.norm();
  if (length == 0.0) return hits;
  const Eigen::Vector3d direction = translation / length;
  std::vector<ColliderId> candidates;
  impl_->scene.queryRay(origin, direction, length, candidates);
  impl_->forAccepted(candidates, filter, [&](const Synced& s) {
    const auto hit = rayCastShape(*s.collider.shape, s.world, origin, direction, length);
    if (!hit) return;
    hits.push_back({s.collider.id, s.collider.body, origin + hit->distance * direction, hit->normal,
                    hit->distance / length});
  });
  std::stable_sort(hits.begin(), hits.end(),
                   [](const RayHit& a, const RayHit& b) { return a.fraction < b.fraction; });
  return hits;
}

std::optional<ShapeHit> SceneQuery::castShape(const std::shared_ptr<const Shape>& shape,
                                              const Pose& start, const Eigen::Vector3d& translation,
                                              const QueryFilter& filter) const {
  if (!start.allFinite()) throw std::invalid_argument("shape cast: start pose is not finite");
  requireFinite(translation, "shape cast: translation");
  FclQueryShape query(shape);
  query.setPose(start);
  Aabb swept = query.worldAabb();
  swept.min = swept.min.cwiseMin(swept.min + translation);
  swept.max = swept.max.cwiseMax(swept.max + translation);
  std::vector<ColliderId> candidates;
  impl_->scene.queryAabb(swept, candidates);
  std::optional<ShapeHit> first;
  impl_->forAccepted(candidates, filter, [&](const Synced& s) {
    const auto hit = impl_->cast(query, start, translation, s);
    if (hit && (!first || hit->fraction < first->fraction)) first = hit;  // ids ascend: ties keep
  });
  return first;
}

std::vector<ColliderId> SceneQuery::overlap(const std::shared_ptr<const Shape>& shape,
                                            const Pose& pose, const QueryFilter& filter) const {
  if (!pose.allFinite()) throw std::invalid_argument("overlap query: pose is not finite");
  FclQueryShape query(shape);
  query.setPose(pose);
  std::vector<ColliderId> candidates, out;
  impl_->scene.queryAabb(query.worldAabb(), candidates);
  impl_->forAccepted(candidates, filter, [&](const Synced& s) {
    const FclCollideResult touching = impl_->scene.collide(query, s.collider.id, 1);
    if (touching.error.empty() && !touching.contacts.empty()) out.push_back(s.collider.id);
  });
  return out;
}

std::vector<ColliderId> SceneQuery::queryAabb(const Aabb& box, const QueryFilter& filter) const {
  requireFinite(box.min, "AABB query: min");
  requireFinite(box.max, "AABB query: max");
  std::vector<ColliderId> candidates, out;
  impl_->scene.queryAabb(box, candidates);
  impl_->forAccepted(candidates, filter, [&](const Synced& s) { out.push_back(s.collider.id); });
  return out;
}

ClosestPoints SceneQuery::closestPoints(ColliderId a, ColliderId b) const {
  const Synced* sa = impl_->find(a);
  const Synced* sb = impl_->find(b);
  if (sa == nullptr || sb == nullptr)
    throw std::invalid_argument("closest points: " + name(sa == nullptr ? a : b) +
                                " is not in the query scene");
  const auto* planeA = std::get_if<Plane>(sa->collider.shape.get());
  const auto* planeB = std::get_if<Plane>(sb->collider.shape.get());
  ClosestPoints out;
  if (planeA != nullptr && planeB != nullptr)
    throw std::invalid_argument("closest points: " + name(a) + " and " + name(b) +
                                " are both planes");
  if (planeA != nullptr || planeB != nullptr) {  // FCL has no half-space distance (fcl#623)
    const Synced& plane = planeA != nullptr ? *sa : *sb;
    const Synced& other = planeA != nullptr ? *sb : *sa;
    Eigen::Vector3d n;
    double offset = 0;
    worldPlane(planeA != nullptr ? *planeA : *planeB, plane.world, n, offset);
    const Eigen::Vector3d low = lowestPoint(*other.collider.shape, other.world, n);
    out.distance = n.dot(low) - offset;
    const Eigen::Vector3d onPlane = low - out.distance * n;
    out.pointA = planeA != nullptr ? onPlane : low;
    out.pointB = planeA != nullptr ? low : onPlane;
    if (out.distance < 0) out.pointA = out.pointB = low;
    return out;
  }
  const FclCollideResult touching = impl_->scene.collide(a, b, 8);
  if (!touching.error.empty())
    throw std::invalid_argument("closest points of " + name(a) + " and " + name(b) + ": " +
                                touching.error);
  if (!touching.contacts.empty()) {
    const auto deepest = std::max_element(
        touching.contacts.begin(), touching.contacts.end(),
        [](const FclContact& x, const FclContact& y) { return x.depth < y.depth; });
    out.distance = -deepest->depth;
    out.pointA = out.pointB = deepest->position;
    return out;
  }
  const FclDistanceResult gap = impl_->scene.distance(a, b);
  if (!gap.error.empty())
    throw std::invalid_argument("closest points of " + name(a) + " and " + name(b) + ": " +
                                gap.error);
  out.distance = gap.distance;
  out.pointA = gap.pointA;
  out.pointB = gap.pointB;
  return out;
}

}  // namespace coulomb::geometry
