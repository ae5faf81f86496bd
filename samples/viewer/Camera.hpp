#pragma once
// Orbit camera for the viewer and the offscreen renderer: it looks at `target` from `distance`
// along the direction given by `yaw` (about the world z axis, which is up) and `pitch` (above the
// xy plane). Produces the OpenGL projection and view matrices (column-major, as glLoadMatrixd
// expects), so the same camera serves the window and the offscreen context.
#include <Eigen/Core>

namespace coulomb::viewer {

struct BoundingSphere;

struct Camera {
  Eigen::Vector3d target = Eigen::Vector3d::Zero();  // [m] the point orbited
  double distance = 5.0;                             // [m] from target to eye
  double yaw = -1.2;                                 // [rad] eye direction about +z
  double pitch = 0.45;                               // [rad] eye elevation above the xy plane
  double fovY = 0.7;                                 // [rad] vertical field of view

  [[nodiscard]] Eigen::Vector3d eye() const;
  [[nodiscard]] Eigen::Matrix4d view() const;                     // world -> eye
  [[nodiscard]] Eigen::Matrix4d projection(double aspect) const;  // eye -> clip
  /// Places the target at the sphere's centre and backs off until the whole sphere is inside
  /// both the vertical and the horizontal field of view (aspect = width / height).
  void frame(const BoundingSphere& sphere, double aspect);
  /// Mouse: drag by (dx, dy) pixels rotates; a wheel tick (> 0 towards the screen) zooms.
  void orbit(double dxPixels, double dyPixels);
  void zoom(double wheelTicks);
  /// Moves the target in the view plane by a drag of (dx, dy) pixels in a viewport `height` tall.
  void pan(double dxPixels, double dyPixels, double heightPixels);
};

}  // namespace coulomb::viewer
