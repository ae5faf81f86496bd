// Bullet (Debian's libbullet-dev 3.24, single precision) as a user sets it up: a
// btDiscreteDynamicsWorld with btDbvtBroadphase and btSequentialImpulseConstraintSolver, all
// solver settings at their defaults, one stepSimulation(dt, 0) per step (exactly one internal
// step of dt, no sub-stepping, no interpolation). docs/benchmarks.md "Peers in the same run"
// changes three things: explicit inertias, no deactivation, and the friction/restitution combine
// rule min instead of Bullet's product (which would give mu^2), set through the contact-added
// callback as the peers' harness did.
#include "PeerEngine.hpp"

#include <coulomb/engine/CoulombError.hpp>

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>

namespace coulomb::peers {
namespace {

btVector3 bt(const Eigen::Vector3d& v) {
  return {btScalar(v.x()), btScalar(v.y()), btScalar(v.z())};
}
Eigen::Vector3d eigen(const btVector3& v) {
  return {v.x(), v.y(), v.z()};
}

// Called for every new manifold point of a body flagged CF_CUSTOM_MATERIAL_CALLBACK.
bool combineMin(btManifoldPoint& point, const btCollisionObjectWrapper* a, int, int,
                const btCollisionObjectWrapper* b, int, int) {
  const btCollisionObject* objA = a->getCollisionObject();
  const btCollisionObject* objB = b->getCollisionObject();
  point.m_combinedFriction = std::min(objA->getFriction(), objB->getFriction());
  point.m_combinedRestitution = std::min(objA->getRestitution(), objB->getRestitution());
  return true;
}

std::unique_ptr<btCollisionShape> makeShape(const PeerShape& s) {
  switch (s.kind) {
    case PeerShape::Kind::Plane:  // body frame = world; the plane is given in world
      return std::make_unique<btStaticPlaneShape>(bt(s.planeNormal), btScalar(s.planeOffset));
    case PeerShape::Kind::Box:
      return std::make_unique<btBoxShape>(bt(s.halfExtents));
    case PeerShape::Kind::Sphere:
      return std::make_unique<btSphereShape>(btScalar(s.radius));
    case PeerShape::Kind::Capsule: {
      const auto r = btScalar(s.radius);
      const auto height = btScalar(2.0 * s.halfLength);  // Bullet takes the cylinder length
      const auto along = [&](int axis) { return std::abs(s.capsuleAxis[axis]) > 1.0 - 1e-12; };
      if (along(0)) return std::make_unique<btCapsuleShapeX>(r, height);
      if (along(1)) return std::make_unique<btCapsuleShape>(r, height);
      if (along(2)) return std::make_unique<btCapsuleShapeZ>(r, height);
      break;
    }
  }
  throw engine::CoulombError("BulletPeer: capsule axis not along a body axis");
}

class BulletPeer final : public PeerEngine {
 public:
  explicit BulletPeer(const PeerScene& scene) : dt_(scene.dt) {
    gContactAddedCallback = combineMin;
    world_.setGravity(bt(scene.gravity));
    for (const PeerBody& b : scene.bodies) {
      shapes_.push_back(makeShape(b.shape));
      btRigidBody::btRigidBodyConstructionInfo info(btScalar(b.mass), nullptr, shapes_.back().get(),
                                                    bt(b.inertia));
      info.m_friction = btScalar(b.friction);
      info.m_restitution = btScalar(b.restitution);
      if (b.shape.kind != PeerShape::Kind::Plane)
        info.m_startWorldTransform =
            btTransform(btQuaternion(btScalar(b.rotation.x()), btScalar(b.rotation.y()),
                                     btScalar(b.rotation.z()), btScalar(b.rotation.w())),
                        bt(b.position));
      auto body = std::make_unique<btRigidBody>(info);
      body->setCollisionFlags(body->getCollisionFlags() |
                              btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
      body->setActivationState(DISABLE_DEACTIVATION);
      body->setLinearVelocity(bt(b.linearVelocity));
      body->setAngularVelocity(bt(b.angularVelocity));
      if (b.shape.collides)
        world_.addRigidBody(body.get());
      else
        world_.addRigidBody(body.get(), 1, 0);  // empty mask: touches nothing
      bodies_.push_back(std::move(body));
    }
    for (const PeerJoint& j : scene.joints) {
      // btPoint2PointConstraint: pivots in the bodies' COM frames; with one body it pins the
      // pivot to its current world position (the world anchor, since the scene starts closed).
      const auto body = [&](int i) { return bodies_[static_cast<std::size_t>(i)].get(); };
      std::unique_ptr<btPoint2PointConstraint> c;
      if (j.bodyA < 0)
        c = std::make_unique<btPoint2PointConstraint>(*body(j.bodyB), bt(j.anchorB));
      else if (j.bodyB < 0)
        c = std::make_unique<btPoint2PointConstraint>(*body(j.bodyA), bt(j.anchorA));
      else
        c = std::make_unique<btPoint2PointConstraint>(*body(j.bodyA), *body(j.bodyB), bt(j.anchorA),
                                                      bt(j.anchorB));
      world_.addConstraint(c.get(), true);
      joints_.push_back(std::move(c));
    }
  }
  ~BulletPeer() override {
    for (auto& j : joints_) world_.removeConstraint(j.get());
    for (auto& b : bodies_) world_.removeRigidBody(b.get());
  }
  BulletPeer(const BulletPeer&) = delete;
  BulletPeer& operator=(const BulletPeer&) = delete;

  void step() override { world_.stepSimulation(btScalar(dt_), 0); }
  void read(std::vector<BodySample>& out) const override {
    out.resize(bodies_.size());
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const btRigidBody& b = *bodies_[i];
      const btQuaternion q = b.getOrientation();
      out[i] = {eigen(b.getCenterOfMassPosition()), Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()),
                eigen(b.getLinearVelocity()), eigen(b.getAngularVelocity())};
    }
  }

 private:
  double dt_;
  btDefaultCollisionConfiguration config_;
  btCollisionDispatcher dispatcher_{&config_};
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btDiscreteDynamicsWorld world_{&dispatcher_, &broadphase_, &solver_, &config_};
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  std::vector<std::unique_ptr<btTypedConstraint>> joints_;
};

}  // namespace

std::unique_ptr<PeerEngine> makeBullet(const PeerScene& scene) {
  return std::make_unique<BulletPeer>(scene);
}

}  // namespace coulomb::peers
