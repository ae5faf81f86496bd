#pragma once
// The free-flight samples (projectile, torque-free symmetric top, Dzhanibekov flip): each runs its
// built-in scene and measures it against the closed form or the invariants of the motion.
// Shared by `coulomb demo`, the sample programs and the tests.
#include <coulomb/io/SceneLoader.hpp>

#include <ostream>

namespace coulomb::samples {

struct ProjectileMeasurement {
  double duration = 0.0;              // [s] simulated
  double maxErrorVsClosedForm = 0.0;  // [m] max |x - (x0 + v0 t + g t^2/2)|
  double expectedEulerOffset = 0.0;   // [m] |g| h t_end / 2: semi-implicit Euler's known O(h) term
  double maxErrorAfterOffset = 0.0;   // [m] max |x - closed form - g h t / 2| (round-off only)
};

struct TopMeasurement {
  double duration = 0.0;  // [s]
  std::uint64_t steps = 0;
  double maxMomentumDrift = 0.0;   // max |L(t) - L(0)| / |L(0)|, world frame
  double maxEnergyDrift = 0.0;     // max |E(t) - E(0)| / E(0)
  double maxConeAngleError = 0.0;  // [rad] max change of the angle between symmetry axis and L
  double secondsPerStep = 0.0;     // wall time of World::step for this one-body scene
};

struct DzhanibekovMeasurement {
  double duration = 0.0;          // [s]
  int intermediateFlips = 0;      // half-turns of the intermediate axis relative to L
  double maxMinorAxisTilt = 0.0;  // [rad] max angle between the spin axis and L (minor axis)
  double maxMajorAxisTilt = 0.0;  // [rad] same for the major axis
  double maxMomentumDrift = 0.0;  // over the three bodies
};

ProjectileMeasurement measureProjectile(const engine::io::Scene& scene);
TopMeasurement measureSymmetricTop(const engine::io::Scene& scene);
DzhanibekovMeasurement measureDzhanibekov(const engine::io::Scene& scene);

void print(std::ostream& out, const ProjectileMeasurement& m);
void print(std::ostream& out, const TopMeasurement& m);
void print(std::ostream& out, const DzhanibekovMeasurement& m);

/// Runs the three built-in free-flight scenes and prints their measurements; returns false if a
/// measurement is outside its expected bound.
bool runFreeFlightDemo(std::ostream& out);

}  // namespace coulomb::samples
