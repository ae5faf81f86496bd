#pragma once
// How joint drift (position error C(x) != 0) is removed: the two policies of the survey
// (Bender, Erleben, Trinkle 2014, "Interactive simulation of rigid body dynamics in computer
// graphics", sec. 4.4.1). Chosen per world (WorldSettings::jointStabilization) and per joint
// (JointDef::stabilization overrides). docs/tuning.md compares them with figures.
#include <optional>
#include <string>

namespace coulomb::joints {

enum class StabilizationMethod {
  /// Bias beta C / h on the velocity rows (Baumgarte 1972; survey sec. 4.4.1): cheap, but the
  /// bias does work, so it adds or removes energy, and a stiff beta makes chains jitter.
  Baumgarte,
  /// Impulse-based predicted-state correction (Bender et al. 2005, survey sec. 4.4.1, Fig. 11):
  /// after the velocity solve, predict each joint's error at t+h, solve J M^-1 J^T p = -C/h and
  /// iterate to a tolerance. With equality rows this is SHAKE: no energy is pumped in.
  PredictedState,
  /// Velocity rows only: the joints drift (for tests and comparisons).
  None,
};

const char* stabilizationMethodName(StabilizationMethod method);
std::optional<StabilizationMethod> stabilizationMethodFromName(const std::string& name);

struct BaumgarteSettings {
  /// [-] Fraction of the position error removed per step. Default 0.2: removes a gap within
  /// ~10 steps without visible jitter (Box2D and Bullet's ERP use 0.2).
  double beta = 0.2;
  /// [m or rad] Error per row left alone. Default 0: a joint is meant to be exact (a slop only
  /// helps contacts keep their manifold points).
  double slop = 0.0;
};

/// What an island of ideal joints keeps through the energy projection after its correction
/// (integrators/EnergyProjection.hpp; docs/tuning.md, "Chains keep their energy").
enum class EnergyTarget {
  /// No projection: the step's own energy behaviour (a whipping chain loses 40-80 % of its
  /// energy in 10 s at dt 0.01, or gains at smaller steps).
  None,
  /// The step's first-order modified energy E + (h/2) sum m g.v: no drift, and the O(h)
  /// oscillation of E that the step has where it is accurate is kept (so is a pendulum's phase).
  Modified,
  /// The energy E itself, on the symmetric step (half kicks around the position update, RATTLE):
  /// E never rises above its start; pinning it moves a period by O((h omega)^2) (B8 -2.2e-4,
  /// the fast B9 mode h omega = 0.1 by -1.3e-3).
  Exact,
};

const char* energyTargetName(EnergyTarget target);
std::optional<EnergyTarget> energyTargetFromName(const std::string& name);

struct PredictedStateSettings {
  /// Largest number of correction solves per step (a budget: the loop stops at `tolerance`).
  /// Default 50: the fixed-point iteration contracts by about h |omega| per pass, so 1e-10 is
  /// reached in 5-10 passes at h |omega| < 0.1 but needs ~25 at a chain's whip (h |omega| ~ 0.4;
  /// chain_50 at dt 0.01: 7-11 passes on 9 999 of 10 000 steps, 23 on one), and 50 covers a
  /// contraction factor up to 0.6. A correction that stalls instead switches to projection.
  int iterations = 50;
  /// [m or rad] Stop when every predicted joint error is below this. Default 1e-10: far below
  /// any visible gap, and about the round-off of a 100-link chain's anchor positions.
  double tolerance = 1e-10;
  /// Default Modified: chains and ragdolls keep their energy at game time steps, pendulums their
  /// period (docs/tuning.md, "Chains keep their energy").
  EnergyTarget energy = EnergyTarget::Modified;
};

struct Stabilization {
  /// Default PredictedState: it keeps chains closed without adding or losing energy
  /// (docs/scene-specifications.md A6: maximal-coordinate peers lose 57-96 % of a chain's energy
  /// with Baumgarte-style bias).
  StabilizationMethod method = StabilizationMethod::PredictedState;
  BaumgarteSettings baumgarte;
  PredictedStateSettings predictedState;

  /// nullopt if usable, else a message naming the first bad value.
  [[nodiscard]] std::optional<std::string> validate() const;
};

}  // namespace coulomb::joints
