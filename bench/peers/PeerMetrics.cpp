#include "PeerMetrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

namespace coulomb::peers {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDeg = 180.0 / std::numbers::pi;

bool startsWith(const std::string& s, const char* prefix) {
  return s.rfind(prefix, 0) == 0;
}

/// The sample at t = x (|k dt - x| < dt/2), or nullptr if the run stopped before.
const std::vector<BodySample>* at(const PeerScene& scene, const Trajectory& s, double x) {
  const auto k = static_cast<std::size_t>(std::llround(x / scene.dt));
  return k < s.size() ? &s[k] : nullptr;
}

double maxDisplacement(const PeerScene& scene, const Trajectory& s, bool lastOnly) {
  double worst = 0.0;
  for (std::size_t k = lastOnly ? s.size() - 1 : 0; k < s.size(); ++k)
    for (std::size_t i = 0; i < scene.bodies.size(); ++i)
      if (!scene.bodies[i].isStatic)
        worst = std::max(worst, (s[k][i].position - s[0][i].position).norm());
  return worst;
}

double fallenCount(const PeerScene& scene, const Trajectory& s) {
  int n = 0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    if (!scene.bodies[i].isStatic && (s.back()[i].position - s[0][i].position).norm() > 0.1) ++n;
  return n;
}

// A3: boxes 1..N above the ground (body 0), the top one last.
std::vector<Metric> stackMetrics(const PeerScene& scene, const Trajectory& s) {
  const std::size_t top = scene.bodies.size() - 1;
  double drift = 0.0;
  double pen = kNaN;
  bool standing = true;
  for (std::size_t k = 0; k < s.size(); ++k) {
    drift = std::max(drift, (s[k][top].position - s[0][top].position).head<2>().norm());
    for (std::size_t i = 1; i <= top; ++i)
      standing = standing && (s[k][i].position - s[0][i].position).norm() <= 0.1;
    if (!standing || k * scene.dt < 1.0 - scene.dt / 2) continue;
    for (std::size_t i = 1; i <= top; ++i) {
      const double below = i == 1 ? 0.0 : s[k][i - 1].position.z();
      const double p = (i == 1 ? 0.1 : 0.2) - (s[k][i].position.z() - below);
      pen = std::isnan(pen) ? p : std::max(pen, p);
    }
  }
  return {{"max_disp", maxDisplacement(scene, s, false)},
          {"top_drift_max", drift},
          {"max_pen_after_1s", pen},
          {"top_height_err", s[0][top].position.z() - s.back()[top].position.z()},
          {"n_fallen", fallenCount(scene, s)}};
}

// A4: the last body is the top box.
std::vector<Metric> pyramidMetrics(const PeerScene& scene, const Trajectory& s) {
  const std::size_t top = scene.bodies.size() - 1;
  return {{"max_disp", maxDisplacement(scene, s, false)},
          {"max_disp_end", maxDisplacement(scene, s, true)},
          {"top_height_err", s[0][top].position.z() - s.back()[top].position.z()},
          {"n_fallen", fallenCount(scene, s)}};
}

// A2: ground (body 0) rotated R_y(20 deg): n = R z, downhill d = R x; the box is body 1.
std::vector<Metric> inclineMetrics(const PeerScene& scene, const Trajectory& s) {
  const Eigen::Vector3d n = scene.bodies[0].rotation * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d d = scene.bodies[0].rotation * Eigen::Vector3d::UnitX();
  const Eigen::Vector3d p0 = s[0][1].position;
  const auto slope = [&](double t) {
    const auto* x = at(scene, s, t);
    return x ? ((*x)[1].position - p0).dot(d) : kNaN;
  };
  if (startsWith(scene.name, "box_incline_A")) {
    const auto* end = at(scene, s, 5.0);
    return {{"slope_disp", slope(5.0)},
            {"creep_1_5s", slope(5.0) - slope(1.0)},
            {"normal_sink", end ? 0.1 - (*end)[1].position.dot(n) : kNaN}};
  }
  const double g = scene.gravity.norm();
  const double mu = scene.bodies[1].friction;
  const double theta = std::acos(n.z());
  const double exact = g * (std::sin(theta) - mu * std::cos(theta));
  const auto velocity = [&](double t) {
    const auto* x = at(scene, s, t);
    return x ? (*x)[1].linearVelocity.dot(d) : kNaN;
  };
  const double acc = (velocity(2.0) - velocity(0.5)) / 1.5;
  return {{"acc", acc}, {"acc_exact", exact}, {"acc_rel_err", std::abs(acc - exact) / exact}};
}

// A2 C: the push at 22.5 deg on flat ground; the box is body 1, starting at the origin.
std::vector<Metric> pushMetrics(const PeerScene& scene, const Trajectory& s) {
  const Eigen::Vector3d v0 = scene.bodies[1].linearVelocity;
  const double aim = std::atan2(v0.y(), v0.x());
  const auto deviation = [&](double angle) {
    return std::abs(std::remainder(angle - aim, 2 * std::numbers::pi)) * kDeg;
  };
  double finalDir = kNaN;
  for (const auto& x : s)
    if (x[1].linearVelocity.head<2>().norm() >= 0.05)
      finalDir = deviation(std::atan2(x[1].linearVelocity.y(), x[1].linearVelocity.x()));
  const Eigen::Vector2d disp = (s.back()[1].position - s[0][1].position).head<2>();
  const double mu = scene.bodies[1].friction;
  const double g = scene.gravity.norm();
  return {{"final_dir_dev_deg", finalDir},
          {"disp_dir_dev_deg", deviation(std::atan2(disp.y(), disp.x()))},
          {"stop_dist_err", disp.norm() - v0.squaredNorm() / (2 * mu * g)},
          {"final_speed", s.back()[1].linearVelocity.norm()}};
}

// A5: ground, light box (body 1), heavy box (body 2).
std::vector<Metric> massRatioMetrics(const PeerScene& scene, const Trajectory& s) {
  const double zl = s.back()[1].position.z();
  const double zh = s.back()[2].position.z();
  double lightMax = 0.0;
  for (const auto& x : s) lightMax = std::max(lightMax, (x[1].position - s[0][1].position).norm());
  return {{"max_disp", maxDisplacement(scene, s, false)},
          {"sink_light", 0.1 - zl},
          {"sink_heavy", 0.2 - (zh - zl)},
          {"heavy_z_err", 0.3 - zh},
          {"light_disp_max", lightMax}};
}

// A6: ball joints; energy relative to S = m g L N^2 / 2 with L = 0.1 m, the link length.
std::vector<Metric> chainMetrics(const PeerScene& scene, const Trajectory& s) {
  const auto anchor = [&](const std::vector<BodySample>& x, int body, const Eigen::Vector3d& a) {
    if (body < 0) return a;
    const BodySample& b = x[static_cast<std::size_t>(body)];
    return Eigen::Vector3d(b.position + b.rotation * a);
  };
  const auto energy = [&](const std::vector<BodySample>& x) {
    double e = 0.0;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const PeerBody& b = scene.bodies[i];
      if (b.isStatic) continue;
      const Eigen::Matrix3d R = x[i].rotation.toRotationMatrix();
      const Eigen::Matrix3d I = R * b.inertia.asDiagonal() * R.transpose();
      e += 0.5 * b.mass * x[i].linearVelocity.squaredNorm() +
           0.5 * x[i].angularVelocity.dot(I * x[i].angularVelocity) -
           b.mass * scene.gravity.dot(x[i].position);
    }
    return e;
  };
  double gapMax = 0.0, gapSum = 0.0, driftMax = 0.0;
  const double n = static_cast<double>(scene.bodies.size());
  const double scale = scene.bodies[0].mass * scene.gravity.norm() * 0.1 * n * n / 2;
  const double e0 = energy(s[0]);
  for (const auto& x : s) {
    for (const PeerJoint& j : scene.joints) {
      const double gap = (anchor(x, j.bodyA, j.anchorA) - anchor(x, j.bodyB, j.anchorB)).norm();
      gapMax = std::max(gapMax, gap);
      gapSum += gap;
    }
    driftMax = std::max(driftMax, std::abs(energy(x) - e0) / scale);
  }
  return {{"max_joint_gap", gapMax},
          {"mean_joint_gap", gapSum / static_cast<double>(s.size() * scene.joints.size())},
          {"energy_drift_end", (energy(s.back()) - e0) / scale},
          {"energy_drift_maxabs", driftMax}};
}

// A7: final x velocities, kinetic energy ratio, largest off-axis speed.
std::vector<Metric> cradleMetrics(const PeerScene& scene, const Trajectory& s) {
  std::vector<Metric> out;
  double ke = 0.0, ke0 = 0.0, offAxis = 0.0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const double m = scene.bodies[i].mass;
    char name[32];  // v1 ... v5 (snprintf: GCC 12 warns falsely on "v" + std::to_string)
    std::snprintf(name, sizeof name, "v%zu", i + 1);
    out.push_back({name, s.back()[i].linearVelocity.x()});
    ke += 0.5 * m * s.back()[i].linearVelocity.squaredNorm();
    ke0 += 0.5 * m * s[0][i].linearVelocity.squaredNorm();
    for (const auto& x : s) offAxis = std::max(offAxis, x[i].linearVelocity.tail<2>().norm());
  }
  out.push_back({"ke_ratio", ke / ke0});
  out.push_back({"off_axis_speed", offAxis});
  return out;
}

}  // namespace

std::vector<Metric> sceneMetrics(const PeerScene& scene, const Trajectory& samples) {
  const std::string& name = scene.name;
  if (startsWith(name, "box_stack")) return stackMetrics(scene, samples);
  if (startsWith(name, "pyramid")) return pyramidMetrics(scene, samples);
  if (startsWith(name, "box_incline_C")) return pushMetrics(scene, samples);
  if (startsWith(name, "box_incline")) return inclineMetrics(scene, samples);
  if (startsWith(name, "mass_ratio")) return massRatioMetrics(scene, samples);
  if (startsWith(name, "chain")) return chainMetrics(scene, samples);
  if (startsWith(name, "newton_cradle")) return cradleMetrics(scene, samples);
  return {{"max_disp", maxDisplacement(scene, samples, false)}};
}

std::vector<std::string> keyMetrics(const std::string& name) {
  if (startsWith(name, "box_stack") || startsWith(name, "pyramid")) return {"max_disp", "n_fallen"};
  if (startsWith(name, "box_incline_A")) return {"slope_disp", "creep_1_5s"};
  if (startsWith(name, "box_incline_B")) return {"acc_rel_err"};
  if (startsWith(name, "box_incline_C")) return {"final_dir_dev_deg", "disp_dir_dev_deg"};
  if (startsWith(name, "mass_ratio")) return {"max_disp", "sink_heavy"};
  if (startsWith(name, "chain")) return {"max_joint_gap", "energy_drift_end"};
  if (startsWith(name, "newton_cradle")) return {"v5", "ke_ratio"};
  return {"max_disp"};
}

}  // namespace coulomb::peers
