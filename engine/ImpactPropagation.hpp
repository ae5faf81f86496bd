#pragma once
// The propagating impact law (ContactSettings::impactLaw = Propagating): before an island's
// velocity problem, its impacts are resolved pair by pair, each manifold as a collision of its two
// bodies alone (Newton's law on the pair's points), sweeping the island in contact order until no
// contact impacts. This is the propagation model of Bender, Erleben, Trinkle 2014 (sec. 4.2.2,
// [BETC12]): a collision travels through touching bodies one contact at a time, so equal balls
// exchange velocities and Newton's cradle sends the last ball off alone
// (docs/scene-specifications.md A7).
//
// What takes part: a manifold impacts when one of its points approaches faster than the
// restitution threshold while touching (gap <= touchingTolerance) or while its speculative gap
// closes within the step h (-u_N h > gap; wider gaps stay speculative points of the velocity
// problem). The pair problem is frictionless
// (friction acts in the velocity problem that follows) and skips kinematic bodies (link proxies
// of trees and user-driven bodies: their contacts keep the simultaneous law). Joints are not seen
// here; they act in the velocity problem.
#include <coulomb/engine/ContactSettings.hpp>
#include <coulomb/engine/IslandBuilder.hpp>
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/geometry/ContactManifold.hpp>

#include <span>
#include <vector>

namespace coulomb::engine {

struct ImpactPropagationReport {
  int pairImpacts = 0;    // pair problems solved
  int sweeps = 0;         // sweeps over the island's contacts
  bool converged = true;  // false if contacts still impacted after maxImpactSweeps
};

/// Resolves the impacts of `island` (contact constraints: indices into `manifolds`) in place on
/// the velocities of `state` (v* before the velocity problem).
ImpactPropagationReport propagateImpacts(std::span<const std::int32_t> contacts,
                                         const std::vector<geometry::ContactManifold>& manifolds,
                                         const ContactSettings& settings, double h,
                                         geometry::BodyState& state);

}  // namespace coulomb::engine
