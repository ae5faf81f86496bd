#pragma once
// Energy projection of an island of ideal joints (docs/tuning.md, "Chains keep their energy").
//
// The step is symplectic Euler with SHAKE for the joints: while it resolves the motion it keeps a
// modified energy, to first order (Hairer, Lubich, Wanner, "Geometric Numerical Integration",
// sec. IX.8, for the kick-then-drift order of FreeMotion.hpp and PositionUpdate.hpp)
//   E~ = T + V + (h/2) sum m g.v,        V = -sum m g.x,
// and where it does not (a whipping chain turns its links by h |omega| ~ 0.1-1 rad per step) it
// loses or gains energy from step to step. An island whose only forces are gravity and ideal
// joints conserves energy exactly, so after its step the velocities are scaled back to the E~ the
// step started with: the smallest change of the velocities in the kinetic metric that restores it
// (GNI sec. IV.4, projection onto an invariant). Scaling keeps J v = 0 for every joint. An island
// that hangs from the world has all its velocities scaled; a free island keeps its momentum and
// its angular momentum about its centre of mass (only the motion relative to its rigid motion is
// scaled). Projecting E~ rather than E keeps the first-order oscillation of the energy that the
// step has where it is accurate, so a swinging pendulum keeps its phase (projecting E moves it by
// O(h) per period).
#include <coulomb/geometry/BodyState.hpp>

#include <cstdint>
#include <span>

namespace coulomb::integrators {

/// One body's energy at a step boundary, in the two parts E~ is made of (zero for a body that is
/// not dynamic): E~ = energy + w gravityPower, w = h/2 (or 0 to keep E itself).
struct BodyEnergy {
  double energy = 0.0;        // [J] T + V, V = -m g.x
  double gravityPower = 0.0;  // [W] m g.v
};
BodyEnergy bodyEnergy(const geometry::BodyState& state, std::size_t body,
                      const Eigen::Vector3d& gravity);

struct EnergyProjection {
  bool applied = false;
  double scale = 1.0;        // the factor on the (relative) velocities
  double energyError = 0.0;  // [J] E~ the step started with minus E~ after it, before projecting
};

/// The largest change of the speeds a projection may make: |scale - 1| <= 1/2. A larger one means
/// that the step's energy error is not small against the kinetic energy (an island nearly at
/// rest, or a turning point), where scaling the speeds is no model of the error; the step is then
/// left as it is.
inline constexpr double kMaxProjectionChange = 0.5;

/// Scales the velocities of `bodies` (dynamic bodies joined by ideal joints, nothing else acting
/// but gravity) so that their energy + powerWeight gravityPower equals `target` (powerWeight h/2:
/// E~; 0: E). `anchored`: some joint holds the island to the world or to a static body (no
/// momentum to keep).
EnergyProjection projectEnergy(geometry::BodyState& state, std::span<const std::int32_t> bodies,
                               bool anchored, double target, const Eigen::Vector3d& gravity,
                               double powerWeight);

}  // namespace coulomb::integrators
