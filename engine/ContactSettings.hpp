#pragma once
// Settings of the contact stage of a step (restitution, speculative gaps, penetration correction),
// each with unit, default and reason. docs/tuning.md compares the penetration methods.
#include <string>

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
  /// Registry solver of the pseudo-impulse problem (one unilateral row per contact, no
  /// friction). Default "pgs": it only has to remove most of a small overlap, and a few sweeps of
  /// O(contacts) do that; a Newton solver would factorize for an exactness nobody sees.
  std::string solver = "pgs";
  /// Iterations of that solver. Default 20.
  int iterations = 20;
  /// [-] Its target common residual. Default 1e-6, the velocity problem's.
  double tolerance = 1e-6;
};

/// How an island's simultaneous impacts are resolved (docs/tuning.md, "Impact laws").
enum class ImpactLaw {
  /// Default: Newton's law u_N+ >= -e u_N- on every impacting point in the one velocity problem
  /// of the step (survey sec. 2.1.6). A striker hitting a row of touching balls pushes them all:
  /// Newton's cradle gives (-0.6, 0.4, 0.4, 0.4, 0.4) (docs/scene-specifications.md A7).
  Simultaneous,
  /// Impacts resolved pair by pair, each contact an impact of its two bodies alone, sweeping
  /// the island until no contact impacts (the propagation model of Bender et al. 2014, sec.
  /// 4.2.2 [BETC12]); the velocity problem then runs on the result. Newton's cradle: (0, 0, 0,
  /// 0, 1). engine/ImpactPropagation.hpp.
  Propagating,
};

struct ContactSettings {
  /// [m/s] Approach speeds below this are treated as inelastic (e = 0): resting contacts must not
  /// bounce on the velocity gravity adds in one step. Default 0.2 m/s (a 2 mm drop at g = 9.81
  /// gives 0.2 m/s; below it a bounce would be invisible but would keep stacks jittering).
  double restitutionThreshold = 0.2;
  /// Simultaneous (default: one velocity problem per island, no extra pass) or Propagating.
  ImpactLaw impactLaw = ImpactLaw::Simultaneous;
  /// [m] Gaps up to this count as touching: bodies placed exactly touching are often ~1e-17 m
  /// apart after rounding (0.1 * 3 = 0.30000000000000004, docs/scene-specifications.md A7), and
  /// such a point must take restitution like a touching one, not be treated as a speculative gap to
  /// close. Default 1e-9 m: a million times the rounding of coordinates of order 1 m, far below any
  /// visible gap.
  double touchingTolerance = 1e-9;
  /// Propagating law: most sweeps over the island's contacts; contacts still impacting after
  /// them are left to the velocity problem (Newton's law there). Default 100: a chain of n
  /// touching bodies needs at most n sweeps for equal masses; mass ratios can need many more
  /// impacts, and the cap bounds the cost per step.
  int maxImpactSweeps = 100;
  /// Speculative points (negative depth = gap) let the bodies close the gap within the step
  /// (u_N >= -gap/h) instead of being pushed apart early. Default on: this is what keeps a
  /// resting contact from flickering on and off.
  bool speculativeContacts = true;
  /// Elastic turning (docs/tuning.md, "Elastic turning"): at a persistent contact that is in
  /// contact (it touches, or it pushed in the last solve) and whose normal turned by less than
  /// kElasticTurningMaxAngle since the last step, the approach that the turning causes is
  /// reflected (u_N+ >= -u_turn) instead of stopped, so a body circling on a concave curved
  /// surface follows the chords of a polygon inscribed in it instead of losing (1/2) m v^2
  /// sin^2(v h / R) per step (pi m v^3 h / R per turn). Gravity's h g along the normal, every new
  /// contact and every speculative point that did not push (an impact) stay inelastic. Default
  /// on; off gives the plain velocity-level step (inelastic turning, loss proportional to h).
  bool elasticTurning = true;
  PenetrationSettings penetration;
};

/// [rad] Elastic turning applies only where the normal turned by less than this in one step:
/// larger turns are corners or new features, not a curved surface sampled by the step. 10 degrees:
/// the double loop's ball turns by at most ~5 degrees per step at dt 0.01 (2 m/s on the 0.26 m
/// path radius of the loop tops); 10 m/s on a 0.36 m radius would turn by 16.
inline constexpr double kElasticTurningMaxAngle = 0.17453292519943295;

/// Velocity bias of one contact for the Baumgarte method (0 for the other methods) [m/s].
double baumgarteBias(const PenetrationSettings& settings, double depth, double h);

}  // namespace coulomb::engine
