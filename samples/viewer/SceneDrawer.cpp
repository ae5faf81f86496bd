#include "SceneDrawer.hpp"

#include <GL/gl.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <variant>

namespace coulomb::viewer {
namespace {

using Colour = std::array<float, 3>;

// Distinct, light-friendly colours for dynamic bodies, picked by body index (deterministic).
constexpr std::array<Colour, 8> kPalette{{{0.90f, 0.49f, 0.13f},
                                          {0.20f, 0.55f, 0.85f},
                                          {0.30f, 0.70f, 0.35f},
                                          {0.85f, 0.30f, 0.35f},
                                          {0.60f, 0.45f, 0.80f},
                                          {0.95f, 0.75f, 0.20f},
                                          {0.25f, 0.70f, 0.70f},
                                          {0.80f, 0.50f, 0.65f}}};

Colour bodyColour(const geometry::BodyState& state, std::size_t i) {
  switch (state.motionTypes[i]) {
    case geometry::MotionType::Static:
      return {0.62f, 0.63f, 0.66f};
    case geometry::MotionType::Kinematic:
      return {0.55f, 0.62f, 0.75f};
    default:
      break;
  }
  const Colour c = kPalette[i % kPalette.size()];
  if (state.asleep[i] != 0) return {0.6f * c[0], 0.6f * c[1], 0.6f * c[2]};  // sleeping: darker
  return c;
}

void loadPose(const geometry::Pose& pose) {
  Eigen::Affine3d t = Eigen::Affine3d::Identity();
  t.linear() = pose.rotation.normalized().toRotationMatrix();
  t.translation() = pose.position;
  glMultMatrixd(t.data());
}

void vertex(const Eigen::Vector3d& p) {
  glVertex3d(p.x(), p.y(), p.z());
}

void drawAxes(const Eigen::Vector3d& origin, const Eigen::Matrix3d& axes, double length) {
  const Colour colours[3] = {{0.9f, 0.1f, 0.1f}, {0.1f, 0.75f, 0.1f}, {0.1f, 0.2f, 0.95f}};
  for (int k = 0; k < 3; ++k) {
    glColor3fv(colours[k].data());
    vertex(origin);
    vertex(origin + length * axes.col(k));
  }
}

void setUpLighting() {
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  glEnable(GL_LIGHT1);
  glEnable(GL_COLOR_MATERIAL);
  glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
  glEnable(GL_NORMALIZE);
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);  // open or inward-facing triangles stay lit
  const float ambient[4] = {0.30f, 0.30f, 0.32f, 1.0f};
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);
  // Directional lights (w = 0) fixed in the world: a key light from above and a weaker fill.
  const float key[4] = {0.4f, -0.6f, 1.0f, 0.0f};
  const float keyColour[4] = {0.75f, 0.75f, 0.72f, 1.0f};
  const float fill[4] = {-0.6f, 0.5f, 0.3f, 0.0f};
  const float fillColour[4] = {0.25f, 0.25f, 0.30f, 1.0f};
  glLightfv(GL_LIGHT0, GL_POSITION, key);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, keyColour);
  glLightfv(GL_LIGHT1, GL_POSITION, fill);
  glLightfv(GL_LIGHT1, GL_DIFFUSE, fillColour);
}

}  // namespace

const Mesh& SceneDrawer::meshFor(const geometry::Collider& collider) {
  auto it = meshes_.find(collider.shape.get());
  if (it == meshes_.end()) {
    MeshDetail detail;
    // Thin capsules (the double loop's 1720 rail segments) get fewer triangles.
    if (const auto* capsule = std::get_if<geometry::Capsule>(collider.shape.get());
        capsule != nullptr && capsule->radius < 0.02) {
      detail.slices = 8;
      detail.stacks = 4;
    }
    it = meshes_
             .emplace(collider.shape.get(),
                      CachedMesh{collider.shape, meshShape(*collider.shape, detail)})
             .first;
  }
  return it->second.mesh;
}

void SceneDrawer::draw(const engine::World& world, const Camera& camera, int width, int height,
                       const DrawOptions& options) {
  glViewport(0, 0, width, height);
  glClearColor(kBackground[0] / 255.0f, kBackground[1] / 255.0f, kBackground[2] / 255.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDisable(GL_CULL_FACE);
  glDisable(GL_TEXTURE_2D);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glShadeModel(GL_SMOOTH);

  glMatrixMode(GL_PROJECTION);
  const Eigen::Matrix4d projection =
      camera.projection(static_cast<double>(width) / std::max(1, height));
  glLoadMatrixd(projection.data());
  glMatrixMode(GL_MODELVIEW);
  const Eigen::Matrix4d view = camera.view();
  glLoadMatrixd(view.data());

  setUpLighting();
  drawBodies(world);

  glDisable(GL_LIGHTING);
  const double scale = options.markerScale > 0.0 ? options.markerScale : 0.06 * camera.distance;
  if (options.contacts) drawContacts(world, scale);
  if (options.joints) drawJoints(world, scale);
  if (options.linkFrames) drawLinkFrames(world, scale);
}

void SceneDrawer::drawBodies(const engine::World& world) {
  const geometry::BodyState& state = world.state();
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  for (const geometry::Collider& c : world.colliders()) {
    const std::size_t i = c.body.index;
    if (i >= state.size() || state.alive[i] == 0 || !c.shape) continue;
    const geometry::Pose pose = state.poses[i] * c.localPose;
    if (!pose.allFinite()) continue;  // a quarantined body may be non-finite: skip, never crash
    const Mesh& mesh = meshFor(c);
    if (mesh.vertexCount() == 0) continue;
    const bool plane = std::holds_alternative<geometry::Plane>(*c.shape);
    const Colour colour = plane ? Colour{0.80f, 0.78f, 0.72f} : bodyColour(state, i);
    glColor3fv(colour.data());
    glPushMatrix();
    loadPose(pose);
    glVertexPointer(3, GL_FLOAT, 0, mesh.positions.data());
    glNormalPointer(GL_FLOAT, 0, mesh.normals.data());
    if (plane) {  // push the floor back so the grid lines drawn on it win the depth test
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(1.0f, 1.0f);
    }
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(mesh.vertexCount()));
    if (plane) {
      glDisable(GL_POLYGON_OFFSET_FILL);
      // Grid lines every metre on the square, unlit.
      glDisable(GL_LIGHTING);
      glColor3f(0.68f, 0.66f, 0.60f);
      const auto& p = mesh.positions;  // first triangle: corners (-,-), (+,-), (+,+)
      const Eigen::Vector3d a(p[0], p[1], p[2]), b(p[3], p[4], p[5]), d(p[6], p[7], p[8]);
      const int lines = static_cast<int>(std::min(200.0, (b - a).norm()));
      glBegin(GL_LINES);
      for (int k = 0; k <= lines; ++k) {
        const double s = lines > 0 ? static_cast<double>(k) / lines : 0.0;
        vertex(a + s * (b - a));
        vertex(a + s * (b - a) + (d - b));
        vertex(a + s * (d - b));
        vertex(b + s * (d - b));
      }
      glEnd();
      glEnable(GL_LIGHTING);
    }
    glPopMatrix();
  }
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

void SceneDrawer::drawContacts(const engine::World& world, double scale) {
  glPointSize(5.0f);
  glBegin(GL_POINTS);
  for (const geometry::ContactManifold& m : world.contacts())
    for (const geometry::ContactPoint& p : m.activePoints()) {
      if (p.depth >= 0.0)
        glColor3f(0.85f, 0.05f, 0.05f);
      else
        glColor3f(1.0f, 0.6f, 0.1f);
      vertex(p.position);
    }
  glEnd();
  glLineWidth(1.5f);
  glBegin(GL_LINES);
  glColor3f(0.85f, 0.05f, 0.6f);
  for (const geometry::ContactManifold& m : world.contacts())
    for (const geometry::ContactPoint& p : m.activePoints()) {
      vertex(p.position);
      vertex(p.position + 0.3 * scale * m.normal);
    }
  glEnd();
}

void SceneDrawer::drawJoints(const engine::World& world, double scale) {
  const geometry::BodyState& state = world.state();
  // World has no joint iterator: in a World whose joints were never removed (every scene as
  // built) the live ids are the slots 0..jointCount()-1 with generation 0; probe a little beyond.
  const std::size_t count = world.jointCount();
  std::size_t found = 0;
  glLineWidth(2.0f);
  glBegin(GL_LINES);
  for (std::uint32_t slot = 0; found < count && slot < 2 * count + 16; ++slot) {
    const geometry::JointId id{slot, 0};
    if (!world.contains(id)) continue;
    ++found;
    const joints::JointDef& def = world.joint(id);
    auto frameOf = [&](geometry::BodyId body, const joints::JointFrame& f) {
      geometry::Pose pose;  // the world for an invalid id
      if (body.valid() && body.index < state.size()) pose = state.poses[body.index];
      Eigen::Matrix3d axes;
      axes.col(0) = pose.rotation * f.axis;
      axes.col(1) = pose.rotation * f.normal;
      axes.col(2) = pose.rotation * f.binormal();
      return std::pair{pose.apply(f.anchor), axes};
    };
    const auto [anchorA, axesA] = frameOf(def.bodyA, def.frameA);
    const auto [anchorB, axesB] = frameOf(def.bodyB, def.frameB);
    if (!anchorA.allFinite() || !anchorB.allFinite()) continue;
    drawAxes(anchorA, axesA, scale);
    drawAxes(anchorB, axesB, 0.6 * scale);
    glColor3f(0.95f, 0.85f, 0.1f);  // the anchors' gap (drift), if any
    vertex(anchorA);
    vertex(anchorB);
  }
  glEnd();
}

void SceneDrawer::drawLinkFrames(const engine::World& world, double scale) {
  const geometry::BodyState& state = world.state();
  glLineWidth(2.0f);
  glBegin(GL_LINES);
  for (std::size_t i = 0; i < state.size(); ++i) {
    if (state.alive[i] == 0 || state.motionTypes[i] != geometry::MotionType::Kinematic) continue;
    if (!state.poses[i].allFinite()) continue;
    drawAxes(state.poses[i].position, state.poses[i].rotationMatrix(), 0.7 * scale);
  }
  glEnd();
}

}  // namespace coulomb::viewer
