// ODE 0.16 (Debian's libode-dev, double precision) as a user sets it up: a world and a hash
// space, dSpaceCollide with up to 8 contacts per geom pair (demo_boxstack's count), contact
// joints with dContactApprox1 (friction pyramid scaled by the normal force, so mu is Coulomb's
// coefficient and not a force limit), the world's default ERP 0.2 and CFM, auto-disable off (the
// default), no damping (the default). Stepper: dWorldQuickStep (default 20 SOR-LCP iterations)
// or dWorldStep (the Dantzig LCP stepper). Material: min of the two geoms' mu and e (one value
// per scene anyway); bounce only when e > 0, with bounce_vel 0. QuickStep reorders its rows with
// ODE's global random generator: the seed is reset for every run so a scene's result does not
// depend on the runs before it. ODE's messages (dWorldStep's "LCP internal error") are counted
// and reported in the note column instead of printed.
#include "PeerEngine.hpp"

#include <ode/ode.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdarg>

namespace coulomb::peers {
namespace {

std::atomic<int> odeMessages{0};
void countMessage(int, const char*, va_list) {
  ++odeMessages;
}

struct OdeLibrary {
  OdeLibrary() {
    dInitODE2(0);
    dSetMessageHandler(countMessage);
  }
  ~OdeLibrary() { dCloseODE(); }
  OdeLibrary(const OdeLibrary&) = delete;
  OdeLibrary& operator=(const OdeLibrary&) = delete;
};

class OdePeer final : public PeerEngine {
 public:
  OdePeer(const PeerScene& scene, bool quickStep) : dt_(scene.dt), quickStep_(quickStep) {
    dRandSetSeed(0);
    messagesAtStart_ = odeMessages;
    dWorldSetGravity(world_, scene.gravity.x(), scene.gravity.y(), scene.gravity.z());
    for (const PeerBody& b : scene.bodies) {
      materials_.push_back(&b);
      dBodyID body = nullptr;
      if (!b.isStatic) {
        body = dBodyCreate(world_);
        dMass mass;
        dMassSetParameters(&mass, b.mass, 0, 0, 0, b.inertia.x(), b.inertia.y(), b.inertia.z(), 0,
                           0, 0);
        dBodySetMass(body, &mass);
        dBodySetPosition(body, b.position.x(), b.position.y(), b.position.z());
        const dQuaternion q = {b.rotation.w(), b.rotation.x(), b.rotation.y(), b.rotation.z()};
        dBodySetQuaternion(body, q);
        dBodySetLinearVel(body, b.linearVelocity.x(), b.linearVelocity.y(), b.linearVelocity.z());
        dBodySetAngularVel(body, b.angularVelocity.x(), b.angularVelocity.y(),
                           b.angularVelocity.z());
      }
      bodies_.push_back(body);
      dGeomID geom = makeGeom(b.shape);
      if (body != nullptr) dGeomSetBody(geom, body);
      if (b.shape.kind == PeerShape::Kind::Capsule) {  // ODE's capsule lies along its local z
        const Eigen::Quaterniond r =
            Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), b.shape.capsuleAxis);
        const dQuaternion q = {r.w(), r.x(), r.y(), r.z()};
        dGeomSetOffsetQuaternion(geom, q);
      }
      if (!b.shape.collides) {
        dGeomSetCategoryBits(geom, 0);
        dGeomSetCollideBits(geom, 0);
      }
      dGeomSetData(geom, const_cast<PeerBody*>(&b));
    }
    for (const PeerJoint& j : scene.joints) {
      const auto body = [&](int i) {
        return i < 0 ? nullptr : bodies_[static_cast<std::size_t>(i)];
      };
      const Eigen::Vector3d anchor =
          j.bodyB >= 0 ? scene.bodies[static_cast<std::size_t>(j.bodyB)].position +
                             scene.bodies[static_cast<std::size_t>(j.bodyB)].rotation * j.anchorB
                       : j.anchorB;
      dJointID joint = dJointCreateBall(world_, nullptr);
      dJointAttach(joint, body(j.bodyA), body(j.bodyB));
      dJointSetBallAnchor(joint, anchor.x(), anchor.y(), anchor.z());
    }
  }
  ~OdePeer() override {
    dJointGroupDestroy(contacts_);
    dSpaceDestroy(space_);  // destroys its geoms
    dWorldDestroy(world_);  // destroys bodies and joints
  }
  OdePeer(const OdePeer&) = delete;
  OdePeer& operator=(const OdePeer&) = delete;

  void step() override {
    dSpaceCollide(space_, this, &OdePeer::nearCallback);
    if (quickStep_)
      dWorldQuickStep(world_, dt_);
    else
      dWorldStep(world_, dt_);
    dJointGroupEmpty(contacts_);
  }
  [[nodiscard]] std::string note() const override {
    const int n = odeMessages - messagesAtStart_;
    return n == 0 ? std::string() : "ODE messages: " + std::to_string(n) + "x LCP internal error";
  }
  void read(std::vector<BodySample>& out) const override {
    out.resize(bodies_.size());
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      dBodyID b = bodies_[i];
      if (b == nullptr) continue;  // static: never moves (out keeps what it had, set below once)
      const dReal* p = dBodyGetPosition(b);
      const dReal* q = dBodyGetQuaternion(b);
      const dReal* v = dBodyGetLinearVel(b);
      const dReal* w = dBodyGetAngularVel(b);
      out[i] = {{p[0], p[1], p[2]},
                Eigen::Quaterniond(q[0], q[1], q[2], q[3]),
                {v[0], v[1], v[2]},
                {w[0], w[1], w[2]}};
    }
    for (std::size_t i = 0; i < bodies_.size(); ++i)
      if (bodies_[i] == nullptr)
        out[i] = {materials_[i]->position, materials_[i]->rotation, Eigen::Vector3d::Zero(),
                  Eigen::Vector3d::Zero()};
  }

 private:
  dGeomID makeGeom(const PeerShape& s) {
    switch (s.kind) {
      case PeerShape::Kind::Plane:
        return dCreatePlane(space_, s.planeNormal.x(), s.planeNormal.y(), s.planeNormal.z(),
                            s.planeOffset);
      case PeerShape::Kind::Box:
        return dCreateBox(space_, 2 * s.halfExtents.x(), 2 * s.halfExtents.y(),
                          2 * s.halfExtents.z());
      case PeerShape::Kind::Sphere:
        return dCreateSphere(space_, s.radius);
      case PeerShape::Kind::Capsule:
        return dCreateCapsule(space_, s.radius, 2 * s.halfLength);  // cylinder length
    }
    return nullptr;
  }

  static void nearCallback(void* data, dGeomID g1, dGeomID g2) {
    auto* self = static_cast<OdePeer*>(data);
    dBodyID b1 = dGeomGetBody(g1);
    dBodyID b2 = dGeomGetBody(g2);
    const auto* m1 = static_cast<const PeerBody*>(dGeomGetData(g1));
    const auto* m2 = static_cast<const PeerBody*>(dGeomGetData(g2));
    std::array<dContact, 8> contacts{};
    const int n =
        dCollide(g1, g2, static_cast<int>(contacts.size()), &contacts[0].geom, sizeof(dContact));
    for (int i = 0; i < n; ++i) {
      dContact& c = contacts[static_cast<std::size_t>(i)];
      const double e = std::min(m1->restitution, m2->restitution);
      c.surface.mode = dContactApprox1 | (e > 0 ? dContactBounce : 0);
      c.surface.mu = std::min(m1->friction, m2->friction);
      c.surface.bounce = e;
      c.surface.bounce_vel = 0;
      dJointID joint = dJointCreateContact(self->world_, self->contacts_, &c);
      dJointAttach(joint, b1, b2);
    }
  }

  double dt_;
  bool quickStep_;
  int messagesAtStart_ = 0;
  static dWorldID createWorld() {
    static const OdeLibrary library;  // dInitODE2 before the first world
    return dWorldCreate();
  }
  dWorldID world_ = createWorld();
  dSpaceID space_ = dHashSpaceCreate(nullptr);
  dJointGroupID contacts_ = dJointGroupCreate(0);
  std::vector<dBodyID> bodies_;             // nullptr for static bodies
  std::vector<const PeerBody*> materials_;  // the scene's bodies (outlive this engine)
};

}  // namespace

std::unique_ptr<PeerEngine> makeOde(const PeerScene& scene, bool quickStep) {
  return std::make_unique<OdePeer>(scene, quickStep);
}

}  // namespace coulomb::peers
