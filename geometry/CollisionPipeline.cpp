#include <coulomb/geometry/CollisionPipeline.hpp>

#include <coulomb/geometry/ContinuousCollision.hpp>

#include <coulomb/geometry/ChainContacts.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

namespace coulomb::geometry {
namespace {

std::string describe(const Collider& c) {
  std::ostringstream out;
  out << "collider " << c.id.index << "." << c.id.generation << " (body " << c.body.index << ")";
  return out.str();
}

}  // namespace

CollisionPipeline::CollisionPipeline(CollisionSettings settings)
    : settings_(settings),
      scene_(settings.speculativeMargin),
      narrowPhase_(NarrowPhaseSettings{settings.speculativeMargin, settings.maxMeshContacts}),
      cache_(ContactCacheSettings{settings.matchDistance, 0.95}) {}

std::optional<std::string> CollisionPipeline::validateCollider(const Collider& collider) {
  const std::string who = describe(collider);
  if (!collider.id.valid()) return who + ": invalid collider id";
  if (!collider.body.valid()) return who + ": invalid body id";
  if (!collider.shape) return who + ": has no shape";
  if (auto problem = validateShape(*collider.shape)) return who + ": " + *problem;
  if (!collider.localPose.allFinite()) return who + ": local pose is not finite (NaN or inf)";
  if (collider.localPose.rotation.norm() < 1e-9) return who + ": local rotation is zero";
  const Material& m = collider.material;
  if (!std::isfinite(m.friction) || m.friction < 0.0)
    return who + ": friction must be finite and >= 0";
  if (!std::isfinite(m.restitution) || m.restitution < 0.0 || m.restitution > 1.0)
    return who + ": restitution must be in [0, 1]";
  return std::nullopt;
}

const std::vector<ContactManifold>& CollisionPipeline::step(const std::vector<Collider>& colliders,
                                                            std::span<const Pose> bodyPoses,
                                                            const SweepMotion& motion,
                                                            const PairPredicate& keepPair,
                                                            const ParallelFor& parallel) {
  diagnostics_.failures.clear();
  diagnostics_.stats = {};
  const std::size_t n = colliders.size();
  shapePoses_.assign(n, Pose{});
  usable_.assign(n, 1);

  // Duplicate ids would make pairs ambiguous: keep the first, report the others.
  std::vector<std::size_t>& order = order_;
  order.resize(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t l, std::size_t r) {
    return std::tie(colliders[l].id, l) < std::tie(colliders[r].id, r);
  });
  for (std::size_t k = 1; k < n; ++k)
    if (colliders[order[k]].id == colliders[order[k - 1]].id) {
      usable_[order[k]] = 0;
      diagnostics_.failures.push_back(
          {colliders[order[k]].id, ColliderId{}, describe(colliders[order[k]]) + ": duplicate id"});
    }

  for (std::size_t i = 0; i < n; ++i) {
    if (!usable_[i]) continue;
    const Collider& c = colliders[i];
    std::string problem;
    if (!c.shape) {
      problem = describe(c) + ": has no shape";
    } else if (c.body.index >= bodyPoses.size()) {
      problem = describe(c) + ": body index out of range of the body poses";
    } else {
      Pose world = bodyPoses[c.body.index] * c.localPose;
      const double norm = world.rotation.norm();
      if (!world.allFinite() || !(norm > 1e-9)) {
        problem = describe(c) + ": world pose is not finite (NaN or inf); collider skipped";
      } else {
        world.rotation.coeffs() /= norm;  // FCL needs unit rotations (fcl#567)
        shapePoses_[i] = world;
      }
    }
    if (!problem.empty()) {
      usable_[i] = 0;
      diagnostics_.failures.push_back({c.id, ColliderId{}, problem});
    }
  }

  colliderSweeps(colliders, usable_, motion, settings_.speculativeSweep, sweeps_);
  const std::vector<CandidatePair>& pairs =
      broadPhase_.update(colliders, shapePoses_, usable_, scene_, settings_.speculativeMargin,
                         keepPair, diagnostics_.failures, sweeps_);
  fresh_.clear();
  narrowPhase_.collide(pairs, colliders, shapePoses_, bodyPoses, scene_, fresh_,
                       diagnostics_.failures, sweeps_, parallel);
  dropCoveredCapsuleEnds(colliders, shapePoses_, fresh_,
                         &capsuleEndKeys_);  // ghost points of capsule chains
  // Nothing to do, and nothing spent, unless some collider asked for it.
  anyContinuous_ = std::any_of(colliders.begin(), colliders.end(),
                               [](const Collider& c) { return c.continuous; });
  if (anyContinuous_) {
    startBodyPoses_.assign(bodyPoses.begin(), bodyPoses.end());
    applyContinuousCollision(colliders, order_, shapePoses_, bodyPoses, motion, scene_,
                             continuousTolerance(), fresh_);
  }

  diagnostics_.stats.candidatePairs = pairs.size();
  diagnostics_.stats.touchingPairs = fresh_.size();
  for (const ContactManifold& m : fresh_)
    diagnostics_.stats.contactPoints += static_cast<std::size_t>(m.pointCount);
  return cache_.refresh(fresh_, bodyPoses);  // fresh_ gets the old buffer back for next step
}

std::size_t CollisionPipeline::clampContinuous(const std::vector<Collider>& colliders,
                                               BodyState& state, double h) {
  if (!anyContinuous_ || colliders.size() != shapePoses_.size()) return 0;
  return clampToTimeOfImpact(colliders, order_, shapePoses_, startBodyPoses_, state, h, scene_,
                             continuousTolerance(), cache_.manifolds());
}

}  // namespace coulomb::geometry
