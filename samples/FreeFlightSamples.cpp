#include "FreeFlightSamples.hpp"

#include "scenes/SceneRegistry.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>

namespace coulomb::samples {
namespace {

using geometry::BodyState;

double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// The body axis about which body i spins initially (largest body-frame angular velocity).
int spinAxis(const BodyState& state, std::size_t i) {
  const Eigen::Vector3d omegaBody =
      state.poses[i].rotation.conjugate() * state.angularVelocities[i];
  int axis = 0;
  omegaBody.cwiseAbs().maxCoeff(&axis);
  return axis;
}

Eigen::Vector3d worldAxis(const BodyState& state, std::size_t i, int axis) {
  return state.poses[i].rotation * Eigen::Vector3d::Unit(axis);
}

}  // namespace

ProjectileMeasurement measureProjectile(const engine::io::Scene& scene) {
  engine::World world = engine::io::buildWorld(scene);
  const double h = scene.settings.timeStep;
  const Eigen::Vector3d g = scene.settings.gravity;
  const Eigen::Vector3d x0 = world.state().poses[0].position;
  const Eigen::Vector3d v0 = world.state().linearVelocities[0];
  ProjectileMeasurement m;
  for (std::uint64_t n = 1; n <= scene.steps; ++n) {
    world.step(h);
    const double t = static_cast<double>(n) * h;
    const Eigen::Vector3d exact = x0 + v0 * t + 0.5 * g * t * t;
    const Eigen::Vector3d error = world.state().poses[0].position - exact;
    m.maxErrorVsClosedForm = std::max(m.maxErrorVsClosedForm, error.norm());
    m.maxErrorAfterOffset = std::max(m.maxErrorAfterOffset, (error - 0.5 * g * h * t).norm());
    m.duration = t;
  }
  m.expectedEulerOffset = 0.5 * g.norm() * h * m.duration;
  return m;
}

TopMeasurement measureSymmetricTop(const engine::io::Scene& scene) {
  engine::World world = engine::io::buildWorld(scene);
  const BodyState& s = world.state();
  const Eigen::Vector3d l0 = s.angularMomentum(0);
  const double e0 = s.kineticEnergy(0);
  const int symmetryAxis = 2;  // the scene's cylinder axis (local z)
  const double cone0 = angleBetween(worldAxis(s, 0, symmetryAxis), l0);
  TopMeasurement m;
  m.steps = scene.steps;
  for (std::uint64_t n = 0; n < scene.steps; ++n) {
    world.step(scene.settings.timeStep);
    m.maxMomentumDrift =
        std::max(m.maxMomentumDrift, (s.angularMomentum(0) - l0).norm() / l0.norm());
    m.maxEnergyDrift = std::max(m.maxEnergyDrift, std::abs(s.kineticEnergy(0) - e0) / e0);
    m.maxConeAngleError = std::max(
        m.maxConeAngleError, std::abs(angleBetween(worldAxis(s, 0, symmetryAxis), l0) - cone0));
  }
  m.duration = world.time();
  // Timing pass without the measurements.
  engine::World timed = engine::io::buildWorld(scene);
  const auto start = std::chrono::steady_clock::now();
  for (std::uint64_t n = 0; n < scene.steps; ++n) timed.step(scene.settings.timeStep);
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  m.secondsPerStep = elapsed.count() / static_cast<double>(std::max<std::uint64_t>(scene.steps, 1));
  return m;
}

DzhanibekovMeasurement measureDzhanibekov(const engine::io::Scene& scene) {
  engine::World world = engine::io::buildWorld(scene);
  const BodyState& s = world.state();
  // Bodies 0, 1, 2 spin about their minor, intermediate and major axes (scene order).
  int axes[3];
  Eigen::Vector3d momenta[3];
  for (std::size_t i = 0; i < 3; ++i) {
    axes[i] = spinAxis(s, i);
    momenta[i] = s.angularMomentum(i);
  }
  DzhanibekovMeasurement m;
  int side = 1;  // which way the intermediate axis points along L (hysteresis at +-0.5)
  for (std::uint64_t n = 0; n < scene.steps; ++n) {
    world.step(scene.settings.timeStep);
    const double c = worldAxis(s, 1, axes[1]).dot(momenta[1].normalized());
    if (side > 0 && c < -0.5) side = -1, ++m.intermediateFlips;
    if (side < 0 && c > 0.5) side = 1, ++m.intermediateFlips;
    m.maxMinorAxisTilt =
        std::max(m.maxMinorAxisTilt, angleBetween(worldAxis(s, 0, axes[0]), momenta[0]));
    m.maxMajorAxisTilt =
        std::max(m.maxMajorAxisTilt, angleBetween(worldAxis(s, 2, axes[2]), momenta[2]));
    for (std::size_t i = 0; i < 3; ++i)
      m.maxMomentumDrift = std::max(m.maxMomentumDrift,
                                    (s.angularMomentum(i) - momenta[i]).norm() / momenta[i].norm());
  }
  m.duration = world.time();
  return m;
}

void print(std::ostream& out, const ProjectileMeasurement& m) {
  out << std::scientific << std::setprecision(3) << "projectile (" << std::defaultfloat
      << m.duration << " s)\n"
      << std::scientific << "  max |x - closed form|             " << m.maxErrorVsClosedForm
      << " m  (semi-implicit Euler's O(h) term g h t/2 = " << m.expectedEulerOffset << " m)\n"
      << "  max error after removing g h t/2   " << m.maxErrorAfterOffset << " m  (round-off)\n";
}

void print(std::ostream& out, const TopMeasurement& m) {
  out << std::scientific << std::setprecision(3) << "symmetric_top (" << std::defaultfloat
      << m.steps << " steps, " << m.duration << " s)\n"
      << std::scientific << "  max relative |L(t) - L(0)|        " << m.maxMomentumDrift << "\n"
      << "  max relative |E(t) - E(0)|        " << m.maxEnergyDrift << "\n"
      << "  max cone angle error              " << m.maxConeAngleError << " rad\n"
      << "  world step, one body              " << m.secondsPerStep * 1e9 << " ns\n";
}

void print(std::ostream& out, const DzhanibekovMeasurement& m) {
  out << std::scientific << std::setprecision(3) << "dzhanibekov (" << std::defaultfloat
      << m.duration << " s)\n"
      << "  intermediate-axis flips           " << m.intermediateFlips << "\n"
      << std::scientific << "  max tilt, minor-axis spin         " << m.maxMinorAxisTilt << " rad\n"
      << "  max tilt, major-axis spin         " << m.maxMajorAxisTilt << " rad\n"
      << "  max relative |L(t) - L(0)|        " << m.maxMomentumDrift << "\n";
}

bool runFreeFlightDemo(std::ostream& out) {
  const ProjectileMeasurement projectile =
      measureProjectile(scenes::loadBuiltinScene("projectile"));
  const TopMeasurement top = measureSymmetricTop(scenes::loadBuiltinScene("symmetric_top"));
  const DzhanibekovMeasurement racket = measureDzhanibekov(scenes::loadBuiltinScene("dzhanibekov"));
  out << "Coulomb free-flight samples (scripts/demo then compares the contact solvers on a pyramid)\n\n";
  print(out, projectile);
  print(out, top);
  print(out, racket);
  const bool ok = projectile.maxErrorAfterOffset < 1e-9 && top.maxMomentumDrift < 1e-9 &&
                  top.maxEnergyDrift < 1e-3 && racket.intermediateFlips >= 2 &&
                  racket.maxMinorAxisTilt < 0.05 && racket.maxMajorAxisTilt < 0.05;
  out << "\n"
      << (ok ? "all measurements within their bounds" : "A MEASUREMENT IS OUT OF BOUNDS") << "\n";
  return ok;
}

}  // namespace coulomb::samples
