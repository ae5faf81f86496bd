#pragma once
// Every tunable of a World, with its unit, default and the reason for the default.
#include <coulomb/engine/ContactSettings.hpp>
#include <coulomb/engine/ProblemAssembler.hpp>
#include <coulomb/engine/QuarantineSettings.hpp>
#include <coulomb/engine/Sleep.hpp>
#include <coulomb/geometry/CollisionPipeline.hpp>
#include <coulomb/joints/Stabilization.hpp>
#include <coulomb/solvers/SolvePolicy.hpp>

#include <Eigen/Core>

#include <optional>
#include <string>

namespace coulomb::engine {

/// Every field is saved by snapshots: a new field needs a line in io/Snapshot.cpp
/// (transferSettings), or a restored World keeps its own value of it.
/// How articulations move between contact events (docs/tuning.md, "Tree integrators").
enum class TreeIntegrator {
  /// Default: a tree that no row touches in a step (no contact, active limit, motor, friction,
  /// coupling or closure) is integrated over the step by an embedded Runge-Kutta method
  /// (Dormand-Prince 5(4)) on its joint manifolds, with sub-steps where its local error asks for
  /// them (a whipping chain); a tree that rows touch takes the semi-implicit Euler step of the
  /// velocity-level solve. 6 ABA passes per sub-step.
  RungeKutta,
  /// Semi-implicit Euler on every step (one ABA pass): qd+ = qd + h qdd, q+ = q (+) h qd+.
  /// Diverges on a whipping chain (docs/tuning.md).
  SemiImplicitEuler,
};

struct WorldSettings {
  /// [m/s^2] Uniform gravitational acceleration. Default: standard gravity along -z (z up, as in
  /// URDF/ROS and the scenes of docs/scene-specifications.md).
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};
  /// [s] Step used by World::step() without an argument. Default 0.01: the rate at which the
  /// design's peer engines are compared (docs/architecture.md section 7).
  double timeStep = 0.01;
  /// [kg/m^3] Density for bodies that give neither a density nor an explicit mass. Default: water.
  double defaultDensity = 1000.0;
  /// [-] Largest accepted | |q| - 1 | of a body's orientation quaternion; the quaternion is then
  /// normalised. Larger deviations are an error (a silent renormalisation hides typos).
  double unitQuaternionTolerance = 1e-6;

  /// How every island is solved (solvers/SolvePolicy.hpp, docs/tuning.md "The solve policy"):
  /// which solvers (automatic by default, or a preferred solver, or an exact chain of attempts),
  /// the options every attempt shares, the chooser's thresholds and the promotion rule. A body's
  /// own BodyDesc::solver overrides the choice for its island.
  solvers::SolvePolicy solve;
  /// When an island's W is dense, block-sparse or kept factored (engine/ProblemAssembler.hpp).
  AssemblySettings assembly;
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
  /// How articulations move between contact events. Default RungeKutta.
  TreeIntegrator treeIntegrator = TreeIntegrator::RungeKutta;
  /// [threads] The threads a step runs its islands on (docs/embedding.md, "Threads"): 1
  /// (default) the calling thread only; 0 every hardware thread; N > 1 up to N (at most the
  /// hardware's). The results are bit-identical whatever the count. Without oneTBB (a build with
  /// COULOMB_WITH_TBB off) every count runs on the calling thread. Not saved by snapshots: the
  /// host's choice, not the simulation's state (a restored World keeps its own).
  int threads = 1;
  static constexpr int kMaxThreads = 1024;

  /// nullopt if every value is usable, else a message naming the first bad one (solver names
  /// are checked against the World's registry by the World).
  [[nodiscard]] std::optional<std::string> validate() const;
};

}  // namespace coulomb::engine
