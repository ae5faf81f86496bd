#include "Camera.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "SceneBounds.hpp"

namespace coulomb::viewer {

Eigen::Vector3d Camera::eye() const {
  const Eigen::Vector3d direction(std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw),
                                  std::sin(pitch));
  return target + distance * direction;
}

// gluLookAt's matrix (OpenGL 2.1 reference pages) with z up.
Eigen::Matrix4d Camera::view() const {
  const Eigen::Vector3d e = eye();
  const Eigen::Vector3d f = (target - e).normalized();
  Eigen::Vector3d s = f.cross(Eigen::Vector3d::UnitZ());
  if (s.norm() < 1e-9) s = Eigen::Vector3d::UnitX();  // looking straight down or up
  s.normalize();
  const Eigen::Vector3d u = s.cross(f);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(e);
  m(1, 3) = -u.dot(e);
  m(2, 3) = f.dot(e);
  return m;
}

// gluPerspective's matrix; near and far follow the distance so depth precision stays useful.
Eigen::Matrix4d Camera::projection(double aspect) const {
  const double zNear = std::max(1e-3, 0.01 * distance);
  const double zFar = 200.0 * distance + 100.0;
  const double f = 1.0 / std::tan(0.5 * fovY);
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m(0, 0) = f / aspect;
  m(1, 1) = f;
  m(2, 2) = (zFar + zNear) / (zNear - zFar);
  m(2, 3) = 2.0 * zFar * zNear / (zNear - zFar);
  m(3, 2) = -1.0;
  return m;
}

void Camera::frame(const BoundingSphere& sphere, double aspect) {
  target = sphere.center;
  const double halfY = 0.5 * fovY;
  const double halfX = std::atan(std::tan(halfY) * aspect);
  const double half = std::min(halfX, halfY);
  distance = 0.9 * std::max(sphere.radius, 1e-3) / std::sin(half);
}

void Camera::orbit(double dxPixels, double dyPixels) {
  constexpr double kRadPerPixel = 0.005;
  constexpr double kMaxPitch = 1.55;  // just short of the pole, where the up vector degenerates
  yaw -= kRadPerPixel * dxPixels;
  pitch = std::clamp(pitch + kRadPerPixel * dyPixels, -kMaxPitch, kMaxPitch);
}

void Camera::zoom(double wheelTicks) {
  distance = std::clamp(distance * std::pow(0.9, wheelTicks), 1e-3, 1e5);
}

void Camera::pan(double dxPixels, double dyPixels, double heightPixels) {
  const Eigen::Matrix4d v = view();
  const Eigen::Vector3d right = v.block<1, 3>(0, 0).transpose();
  const Eigen::Vector3d up = v.block<1, 3>(1, 0).transpose();
  const double metresPerPixel = 2.0 * distance * std::tan(0.5 * fovY) / std::max(1.0, heightPixels);
  target += metresPerPixel * (-dxPixels * right + dyPixels * up);
}

}  // namespace coulomb::viewer
