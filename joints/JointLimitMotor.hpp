#pragma once
// Rows on a joint's coordinate (hinge angle or slider displacement), with rate row
// c_dot = J_c (t_A, t_B) from JointCoordinate:
//   limit     one Unilateral row per stop that the coordinate can reach within the step:
//             lower: u = c_dot + b >= 0, upper: u = -c_dot + b >= 0, with the distance to the
//             stop g >= 0 as a speculative bias b = g/h (the stop is reached, never crossed), a
//             Baumgarte push-out b = beta g/h once crossed (g < 0), and Newton restitution
//             b = e c_dot- when a fast approach (> bounceThreshold) reaches the stop (survey
//             sec. 5.4, as contacts);
//   motor     one Bounded row u = c_dot - v_target, |lambda| <= F_max h (velocity motor with a
//             force/torque bound: the impulse over the step is at most F_max h);
//   friction  one Bounded row u = c_dot, |lambda| <= f_max h (dry joint friction: sticks while
//             the load is below f_max, slides against it above).
#include <coulomb/joints/JointDef.hpp>
#include <coulomb/joints/JointPrimitives.hpp>
#include <coulomb/joints/RowBlock.hpp>

#include <vector>

namespace coulomb::joints {

/// [rad/s or m/s] Approach speeds below this reach a stop inelastically (like contacts, so a
/// joint resting on its stop does not chatter on the speed gravity adds in one step).
inline constexpr double kLimitBounceThreshold = 0.1;

/// Appends the limit block (Unilateral, 0-2 rows; none when no stop is within reach) and the
/// motor or friction block (Bounded, 1 row) of `def` to `out`. `coordinateRate` is c_dot at the
/// velocities of the step's start of solve (v*). Returns the number of blocks appended.
int appendLimitMotorRows(const JointDef& def, const JointCoordinate& coordinate,
                         double coordinateRate, double beta, double h, std::vector<RowBlock>& out);

}  // namespace coulomb::joints
