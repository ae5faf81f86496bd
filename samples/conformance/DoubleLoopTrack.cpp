#include "DoubleLoopTrack.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace coulomb::conformance {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kTableSteps = 40000;  // arc-length table over [-pi/2, 4pi]: 3.5e-4 rad per entry

Eigen::Vector3d derivative(double phi) {  // C'(phi) on the loops
  using T = DoubleLoopTrack;
  return {T::kA + T::kB * std::cos(phi), T::kDrift / (2 * kPi), T::kB * std::sin(phi)};
}

}  // namespace

double DoubleLoopTrack::phiStart() {
  return -kPi / 2;
}
double DoubleLoopTrack::phiLoopsEnd() {
  return 4 * kPi;
}

DoubleLoopTrack::DoubleLoopTrack() {
  step_ = (phiLoopsEnd() - phiStart()) / kTableSteps;
  table_.resize(kTableSteps + 1, 0.0);
  // Simpson on each table interval; s(0) is subtracted afterwards so s counts from phi = 0.
  for (int i = 0; i < kTableSteps; ++i) {
    const double a = phiStart() + i * step_;
    table_[i + 1] = table_[i] + step_ / 6 *
                                    (derivative(a).norm() + 4 * derivative(a + step_ / 2).norm() +
                                     derivative(a + step_).norm());
  }
  const double atZero = arcLength(0.0);
  for (double& s : table_) s -= atZero;
  phiEnd_ = phiLoopsEnd() + kExitLength / derivative(phiLoopsEnd()).norm();
}

Eigen::Vector3d DoubleLoopTrack::midline(double phi) {
  if (phi > phiLoopsEnd())
    return midline(phiLoopsEnd()) + (phi - phiLoopsEnd()) * derivative(phiLoopsEnd());
  return {kA * phi + kB * std::sin(phi), kDrift * phi / (2 * kPi), kB * (1 - std::cos(phi))};
}

Eigen::Vector3d DoubleLoopTrack::tangent(double phi) {
  return derivative(std::min(phi, phiLoopsEnd())).normalized();
}

Eigen::Vector3d DoubleLoopTrack::normal(double phi) {
  const Eigen::Vector3d t = tangent(phi);
  const Eigen::Vector3d y = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d b = (y - y.dot(t) * t).normalized();
  return t.cross(b);
}

double DoubleLoopTrack::keepContactSpeed(double gravity) {
  return std::sqrt(gravity * kTopPathRadius);
}

double DoubleLoopTrack::arcLength(double phi) const {
  if (phi >= phiLoopsEnd())
    return table_.back() + (phi - phiLoopsEnd()) * derivative(phiLoopsEnd()).norm();
  const double x = std::max(0.0, (phi - phiStart()) / step_);
  const auto i = std::min(static_cast<std::size_t>(x), table_.size() - 2);
  const double f = x - static_cast<double>(i);
  return table_[i] + f * (table_[i + 1] - table_[i]);
}

double TrackProgress::distance(const Eigen::Vector3d& p, double phi) const {
  return (p - (DoubleLoopTrack::midline(phi) +
               DoubleLoopTrack::kBallHeight * DoubleLoopTrack::normal(phi)))
      .norm();
}

double TrackProgress::update(const Eigen::Vector3d& ballCentre, double speed) {
  const int topsBefore = loopsDone();
  const double s = update(ballCentre);
  if (loopsDone() > topsBefore) topSpeeds_.push_back(speed);
  return s;
}

double TrackProgress::update(const Eigen::Vector3d& p) {
  constexpr double kWindow = 0.5,
                   kOffRails = 0.05;  // [rad], [m] (docs/scene-specifications.md B11)
  constexpr int kSamples = 200;
  const double lo = std::max(DoubleLoopTrack::phiStart(), phi_ - kWindow);
  const double hi = std::min(track_.phiEnd(), phi_ + kWindow);
  double best = phi_, bestDistance = distance(p, phi_);
  for (int i = 0; i <= kSamples; ++i) {
    const double phi = lo + (hi - lo) * i / kSamples;
    const double d = distance(p, phi);
    if (d < bestDistance) best = phi, bestDistance = d;
  }
  // Golden-section refinement within one sample spacing of the best sample.
  double a = std::max(lo, best - (hi - lo) / kSamples),
         b = std::min(hi, best + (hi - lo) / kSamples);
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int k = 0; k < 60; ++k) {
    const double c = b - g * (b - a), d = a + g * (b - a);
    if (distance(p, c) < distance(p, d))
      b = d;
    else
      a = c;
  }
  const double refined = (a + b) / 2;
  if (distance(p, refined) < bestDistance) best = refined, bestDistance = distance(p, refined);
  onRails_ = bestDistance <= kOffRails;
  if (!onRails_) {
    everLeft_ = true;
    return s_;  // frozen
  }
  phi_ = best;
  phiMax_ = std::max(phiMax_, phi_);
  s_ = track_.arcLength(phi_);
  sMax_ = std::max(sMax_, s_);
  return s_;
}

int TrackProgress::loopsDone() const {
  return (phiMax_ >= kPi ? 1 : 0) + (phiMax_ >= 3 * kPi ? 1 : 0);
}

}  // namespace coulomb::conformance
