#pragma once
// Energy projection of an island of ideal joints (docs/tuning.md, "Chains keep their energy").
//
// The step is symplectic Euler with SHAKE for the joints: while it resolves the motion it keeps a
// modified energy, to first order (Hairer, Lubich, Wanner, "Geometric Numerical Integration",
// sec. IX.8: the kick-then-drift map of p' = -grad V, q' = p keeps H - (h/2) p.grad V)
//   E~ = T + V + (h/2) sum m g.u,        V = -sum m g.x,
// with u the tangent velocity of the step boundary at the step's rates (the bodies' angular
// velocities carried through the joints, engine/JointStage::boundaryVelocities; the chord velocity
// of SHAKE dips below it by (h/2) omega x (omega x r), an O(h^2) term that made E~ swing by
// (h omega)^2 / 2 of T on a normal mode). Where the step does not resolve the motion (a whipping
// chain turns its links by h |omega| ~ 0.1-1 rad per step) it loses or gains energy from step to
// step. An island whose only forces are gravity and ideal joints conserves energy exactly, so
// after its step the velocities are scaled back to the E~ the step started with: the smallest
// change of the velocities in the kinetic metric that restores it (GNI sec. IV.4, projection onto
// an invariant). Scaling keeps J v = 0 for every joint. An island that hangs from the world has
// all its velocities scaled; a free island keeps its momentum and its angular momentum about its
// centre of mass (only the motion relative to its rigid motion is scaled). Projecting E~ rather
// than E keeps the first-order oscillation of the energy that the step has where it is accurate,
// so a swinging pendulum keeps its phase (projecting E moves it by O(h) per period).
#include <coulomb/geometry/BodyState.hpp>

#include <cstdint>
#include <span>

namespace coulomb::integrators {

/// One body's energy T + V [J] (V = -m g.x; zero for a body that is not dynamic).
double bodyEnergy(const geometry::BodyState& state, std::size_t body,
                  const Eigen::Vector3d& gravity);

struct EnergyProjection {
  bool applied = false;
  double scale = 1.0;        // the factor on the (relative) velocities
  bool partial = false;      // the factor was held at a bound: only part of the error restored
  double energyError = 0.0;  // [J] E~ the step started with minus E~ after it, before projecting
};

/// The bounds of the factor a projection may put on the speeds: [1/2, 2]. A step whose energy
/// error needs more is corrected as far as the bound allows (partly): its error is then not small
/// against its kinetic energy (a violent whip, a turning point), and a factor of more than 2 on
/// the speeds would be no model of it.
inline constexpr double kMinProjectionScale = 0.5;
inline constexpr double kMaxProjectionScale = 2.0;

/// Scales the velocities of `bodies` (dynamic bodies joined by ideal joints, nothing else acting
/// but gravity) so that their energy + powerWeight sum m g.u equals `target` (powerWeight h/2:
/// E~; 0: E). u is `powerVelocities[i]` per body slot, the tangent velocities of the step boundary
/// (engine/JointStage::boundaryVelocities), linear in the body velocities; empty: the bodies'
/// linear velocities. `anchored`: some joint holds the island to the world or to a static body (no
/// momentum to keep). `resolution` [J]: an error |target - E~| at most this is left alone (the
/// energy is not known better than the joints' tolerance lets the bodies' heights be).
EnergyProjection projectEnergy(geometry::BodyState& state, std::span<const std::int32_t> bodies,
                               bool anchored, double target, const Eigen::Vector3d& gravity,
                               double powerWeight,
                               std::span<const Eigen::Vector3d> powerVelocities = {},
                               double resolution = 0.0);

}  // namespace coulomb::integrators
