#pragma once
// Every tunable of a World, with its unit, default and the reason for the default.
#include <coulomb/engine/ContactSettings.hpp>
#include <coulomb/engine/QuarantineSettings.hpp>
#include <coulomb/engine/Sleep.hpp>
#include <coulomb/geometry/CollisionPipeline.hpp>
#include <coulomb/joints/Stabilization.hpp>
#include <coulomb/solvers/SolverOptions.hpp>

#include <Eigen/Core>

#include <optional>
#include <string>

namespace coulomb::engine {

/// Every field is saved by snapshots: a new field needs a line in engine/io/Snapshot.cpp
/// (transferSettings), or a restored World keeps its own value of it.
struct WorldSettings {
  /// [m/s^2] Uniform gravitational acceleration. Default: standard gravity along -z (z up, as in
  /// URDF/ROS and the scenes of SCENES.md).
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};
  /// [s] Step used by World::step() without an argument. Default 0.01: the rate at which the
  /// design's peer engines are compared (ARCHITECTURE.md section 7).
  double timeStep = 0.01;
  /// [kg/m^3] Density for bodies that give neither a density nor an explicit mass. Default: water.
  double defaultDensity = 1000.0;
  /// [-] Largest accepted | |q| - 1 | of a body's orientation quaternion; the quaternion is then
  /// normalised. Larger deviations are an error (a silent renormalisation hides typos).
  double unitQuaternionTolerance = 1e-6;

  /// Contact solver for every island: "auto" (SolverChooser picks per island and says why) or a
  /// registry name (`coulomb solvers`). A body's own `solver` overrides it for its island.
  std::string solver = "auto";
  /// Common solver options per island. Default tolerance 1e-6 on the common relative residual
  /// (far below what changes a trajectory visibly, and reached in a few warm-started sweeps on
  /// stacks); at most 200 iterations per attempt; no time limit. 200 is ac_newton's and
  /// fb_newton's own cap, so it only shortens Gauss-Seidel (pgs, bgs: 10000 sweeps otherwise)
  /// and staggered (1000 outer steps): a cold-started stack (first step of a resting pyramid)
  /// needs thousands of sweeps to reach 1e-6, which cost seconds per step on 200+ boxes. Capped
  /// attempts say "max_iterations" and the plan's fallbacks continue from their best iterate;
  /// the warm start carries the rest into the next step (docs/benchmarks.md, "Contact step
  /// performance"). 0 = each solver's own default.
  solvers::SolverOptions solverOptions = defaultSimulationSolverOptions();
  /// With "auto": when a fallback had to finish an island's step (pgs stalled, ac_newton
  /// converged), it runs first in that island's next step, solved to 1/100 of the tolerance
  /// (engine/SolverPromotion.hpp: the warm start after a fallback carries a one-off correction
  /// that makes pgs and Newton alternate otherwise). Default on: a 55-box pyramid over 10 000
  /// steps needs 17 Newton solves instead of ~2 300 (docs/benchmarks.md, "Long runs").
  bool promoteFallbacks = true;
  /// Restitution, speculative gaps and penetration correction (docs/tuning.md).
  ContactSettings contact;
  /// Speculative margin and contact-matching distances of the collision layer.
  geometry::CollisionSettings collision;
  /// Islands at rest stop being simulated until touched (engine/Sleep.hpp). Default off.
  SleepSettings sleep;
  /// Sanity limits of the World-level guard (engine/Quarantine.hpp, docs/reliability.md).
  QuarantineSettings quarantine;
  /// How joint drift is removed (joints/Stabilization.hpp; docs/tuning.md compares the policies
  /// with figures). A joint's own JointDef::stabilization overrides it.
  joints::Stabilization jointStabilization;

  static solvers::SolverOptions defaultSimulationSolverOptions() {
    solvers::SolverOptions options;
    options.tolerance = 1e-6;
    options.maxIterations = 200;
    return options;
  }

  /// nullopt if every value is usable, else a message naming the first bad one.
  [[nodiscard]] std::optional<std::string> validate() const;
};

}  // namespace coulomb::engine
