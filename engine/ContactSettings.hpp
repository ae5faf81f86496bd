#pragma once
// Settings of the contact stage of a step (restitution, speculative gaps, penetration correction),
// each with unit, default and reason. docs/tuning.md compares the penetration methods.

namespace coulomb::engine {

enum class PenetrationMethod {
  SplitImpulse,  // default: pseudo-velocities, no energy added
  Baumgarte,     // bias beta (depth - slop) / h on u_N in the velocity problem (adds energy)
  None,
};

struct PenetrationSettings {
  PenetrationMethod method = PenetrationMethod::SplitImpulse;
  /// [-] Fraction of the penetration beyond `slop` removed per step. Default 0.2: removes a
  /// penetration within ~10 steps without visible popping (Box2D and Bullet use 0.2).
  double beta = 0.2;
  /// [m] Penetration left alone, so resting contacts keep touching (and keep their manifold
  /// points) instead of being pushed out and falling back every step. Default 0.5 mm.
  double slop = 0.0005;
  /// Sweeps of the projected Gauss-Seidel on the pseudo-impulse problem (it only has to remove
  /// most of a small overlap; exactness is not needed). Default 20.
  int iterations = 20;
};

struct ContactSettings {
  /// [m/s] Approach speeds below this are treated as inelastic (e = 0): resting contacts must not
  /// bounce on the velocity gravity adds in one step. Default 0.2 m/s (a 2 mm drop at g = 9.81
  /// gives 0.2 m/s; below it a bounce would be invisible but would keep stacks jittering).
  double restitutionThreshold = 0.2;
  /// Speculative points (negative depth = gap) let the bodies close the gap within the step
  /// (u_N >= -gap/h) instead of being pushed apart early. Default on: this is what keeps a
  /// resting contact from flickering on and off.
  bool speculativeContacts = true;
  PenetrationSettings penetration;
};

/// Velocity bias of one contact for the Baumgarte method (0 for the other methods) [m/s].
double baumgarteBias(const PenetrationSettings& settings, double depth, double h);

}  // namespace coulomb::engine
