#pragma once
// The track of docs/scene-specifications.md B11 double_loop (scripts/generate_double_loop.py builds
// the same rails): midline C(phi) = (A phi + B sin phi, D phi / 2pi, B (1 - cos phi)), phi in
// [-pi/2, 4pi], then a straight 2 m exit along the tangent at 4pi (here: phi > 4pi continues C
// linearly with the speed |C'(4pi)|), and the frame t = C'/|C'|, b = normalize(y - (y.t) t), n = t
// x b. Plus the progress measure of docs/scene-specifications.md B11 "What to report": s(t), the
// arc length from phi = 0 of the point of the ball's path C + h n nearest to the ball, followed by
// continuation.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace coulomb::conformance {

class DoubleLoopTrack {
 public:
  static constexpr double kA = 0.4, kB = 1.0, kDrift = 0.4;  // [m]
  static constexpr double kBallHeight = 0.0979795897113271;  // h = sqrt(0.11^2 - 0.05^2) [m]
  static constexpr double kExitLength = 2.0;                 // [m]
  /// [m] the ball centre's path radius at a loop top: the midline's (B - A)^2 / B less h (the
  /// drift along y neglected).
  static constexpr double kTopPathRadius = (kB - kA) * (kB - kA) / kB - kBallHeight;
  /// [m/s] the least speed over a loop top at which the rails still push (m v^2 / R >= m g):
  /// slower, the ball leaves them there.
  [[nodiscard]] static double keepContactSpeed(double gravity);

  DoubleLoopTrack();  // tabulates the arc length

  [[nodiscard]] static double phiStart();                  // -pi/2
  [[nodiscard]] static double phiLoopsEnd();               // 4 pi
  [[nodiscard]] double phiEnd() const { return phiEnd_; }  // end of the exit
  [[nodiscard]] static Eigen::Vector3d midline(double phi);
  [[nodiscard]] static Eigen::Vector3d tangent(double phi);  // unit
  [[nodiscard]] static Eigen::Vector3d normal(double phi);   // n = t x b, unit
  /// [m] arc length of C from phi = 0 (negative behind the start).
  [[nodiscard]] double arcLength(double phi) const;

 private:
  std::vector<double> table_;  // arc length at phiStart + i * step_
  double step_ = 0.0;
  double phiEnd_ = 0.0;
};

/// s(t) of docs/scene-specifications.md B11: phi* = argmin |p - (C + h n)(phi)| over |phi -
/// phi*_prev| <= 0.5; s is frozen while that distance exceeds 0.05 m (the ball is off the rails).
class TrackProgress {
 public:
  explicit TrackProgress(const DoubleLoopTrack& track) : track_(track) {}
  /// Updates with the ball centre; returns the current s [m].
  double update(const Eigen::Vector3d& ballCentre);
  /// The same, and keeps `speed` [m/s] when this update carries the ball over a loop top.
  double update(const Eigen::Vector3d& ballCentre, double speed);
  /// The speeds given with the updates that passed a loop top, in order.
  [[nodiscard]] const std::vector<double>& topSpeeds() const { return topSpeeds_; }
  [[nodiscard]] double s() const { return s_; }
  [[nodiscard]] double sMax() const { return sMax_; }
  [[nodiscard]] double phi() const { return phi_; }
  [[nodiscard]] double phiMax() const { return phiMax_; }  // furthest tracked phi
  [[nodiscard]] bool onRails() const { return onRails_; }
  [[nodiscard]] bool everLeft() const { return everLeft_; }
  /// Loop tops passed while on the rails (phi = pi, 3 pi): 0, 1 or 2.
  [[nodiscard]] int loopsDone() const;

 private:
  [[nodiscard]] double distance(const Eigen::Vector3d& p, double phi) const;
  const DoubleLoopTrack& track_;
  double phi_ = 0.0, phiMax_ = 0.0, s_ = 0.0, sMax_ = 0.0;
  bool onRails_ = true, everLeft_ = false;
  std::vector<double> topSpeeds_;
};

}  // namespace coulomb::conformance
