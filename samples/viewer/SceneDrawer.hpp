#pragma once
// Draws a World with legacy (compatibility-profile) OpenGL into whatever context is current: the
// viewer's GLFW window or the renderer's OSMesa buffer, so one drawing code serves both.
// Bodies from their colliders' shapes, contact points and normals, joint frames.
#include <coulomb/engine/World.hpp>

#include <map>
#include <memory>

#include "Camera.hpp"
#include "ShapeMesh.hpp"

namespace coulomb::viewer {

struct DrawOptions {
  bool contacts = true;      // points (red: touching, orange: speculative gap) and normals
  bool joints = true;        // joint frames (axis red, normal green, binormal blue) and anchors
  bool linkFrames = false;   // axes at every kinematic body (robot links are kinematic proxies)
  double markerScale = 0.0;  // [m] length of normals and frame axes; 0 = 6 % of camera distance
};

/// The clear colour; tests count pixels that differ from it.
inline constexpr std::uint8_t kBackground[3] = {235, 238, 243};

class SceneDrawer {
 public:
  /// Clears and draws the whole frame for a viewport of width x height pixels.
  void draw(const engine::World& world, const Camera& camera, int width, int height,
            const DrawOptions& options);
  /// Drops the cached meshes (e.g. after the World was rebuilt).
  void clear() { meshes_.clear(); }

 private:
  struct CachedMesh {
    std::shared_ptr<const geometry::Shape> shape;  // held so the address is never reused
    Mesh mesh;
  };
  const Mesh& meshFor(const geometry::Collider& collider);
  void drawBodies(const engine::World& world);
  void drawContacts(const engine::World& world, double scale);
  void drawJoints(const engine::World& world, double scale);
  void drawLinkFrames(const engine::World& world, double scale);

  std::map<const geometry::Shape*, CachedMesh> meshes_;
};

}  // namespace coulomb::viewer
