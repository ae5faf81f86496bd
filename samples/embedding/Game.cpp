#include "Game.hpp"

#include <algorithm>
#include <cmath>

namespace coulomb::samples {
namespace {

constexpr double kBoxHalf = 0.2;  // tower boxes and the crate [m]
constexpr int kTowerHeight = 6;

ShapeDesc boxShape(const Eigen::Vector3d& half, double friction = 0.6) {
  return {Box{half}, {}, {friction, 0.0}, {}};
}

BodyId addStatic(World& world, const std::string& name, const Eigen::Vector3d& at,
                 ShapeDesc shape) {
  BodyDesc desc;
  desc.name = name;
  desc.motionType = MotionType::Static;
  desc.pose.position = at;
  desc.shapes.push_back(std::move(shape));
  return world.createBody(desc);
}

BodyId addDynamic(World& world, const std::string& name, const Eigen::Vector3d& at, ShapeDesc shape,
                  double density) {
  BodyDesc desc;
  desc.name = name;
  desc.pose.position = at;
  desc.density = density;
  desc.shapes.push_back(std::move(shape));
  return world.createBody(desc);
}

}  // namespace

World makeGameWorld(GameBodies& bodies, const GameSettings& settings) {
  WorldSettings worldSettings;
  worldSettings.timeStep = settings.frameTime;
  World world(worldSettings);
  BodyDesc floor;
  floor.name = "floor";
  floor.motionType = MotionType::Static;
  floor.shapes.push_back({Plane{}, {}, {0.6, 0.0}, {}});
  world.createBody(floor);

  bodies.tower.clear();
  for (int k = 0; k < kTowerHeight; ++k)
    bodies.tower.push_back(addDynamic(world, "tower" + std::to_string(k),
                                      {0, 0, kBoxHalf * (2 * k + 1)},
                                      boxShape(Eigen::Vector3d::Constant(kBoxHalf)), 300.0));

  // Behind the tower: a trigger volume that counts what the shots knock into it.
  ShapeDesc volume = boxShape({1.0, 2.0, 1.0});
  volume.sensor = true;
  bodies.zone = addStatic(world, "zone", {3.0, 0, 1.0}, volume);

  // One-way platform, 1.2 m up: it pushes only upwards, so the jumper below passes through it.
  bodies.platform = addStatic(world, "platform", {-3.0, 3.0, 1.2}, boxShape({0.5, 0.5, 0.03}));
  bodies.jumper = addDynamic(world, "jumper", {-3.0, 3.0, 0.15}, {Sphere{0.15}, {}, {}, {}}, 500.0);
  world.setVelocity(bodies.jumper, {0, 0, 6.5}, Eigen::Vector3d::Zero());  // apex ~2.3 m
  const BodyId platform = bodies.platform;
  world.setPreSolveHook([platform](ContactModification& c) {
    if (c.manifold.bodyA != platform && c.manifold.bodyB != platform) return;
    const Eigen::Vector3d up =
        c.manifold.bodyA == platform ? c.manifold.normal : Eigen::Vector3d(-c.manifold.normal);
    if (up.z() < 0.7) c.enabled = false;
  });

  // A kinematic lift with a crate on it.
  BodyDesc lift;
  lift.name = "lift";
  lift.motionType = MotionType::Kinematic;
  lift.pose.position = {3.0, -3.0, GameDirector::liftHeight(0.0)};
  lift.shapes.push_back(boxShape({0.6, 0.6, 0.05}));
  bodies.lift = world.createBody(lift);
  bodies.crate =
      addDynamic(world, "crate", {3.0, -3.0, GameDirector::liftHeight(0.0) + 0.05 + kBoxHalf},
                 boxShape(Eigen::Vector3d::Constant(kBoxHalf)), 300.0);
  return world;
}

GameDirector::GameDirector(GameBodies bodies, GameSettings settings)
    : bodies_(std::move(bodies)), settings_(settings) {}

double GameDirector::liftHeight(double t) {
  return 0.1 + 0.4 * (1.0 - std::cos(1.5 * t));  // peak acceleration 0.9 m/s^2 << mu g
}

void GameDirector::tally(const World& world) {
  if (world.stepCount() == tallied_) return;  // these events were counted
  tallied_ = world.stepCount();
  auto isSphere = [&](BodyId b) {
    return std::find(spheres_.begin(), spheres_.end(), b) != spheres_.end();
  };
  auto isTower = [&](BodyId b) {
    return std::find(bodies_.tower.begin(), bodies_.tower.end(), b) != bodies_.tower.end();
  };
  for (const ContactEvent& e : world.contactEvents()) {
    if (e.bodyA == bodies_.zone || e.bodyB == bodies_.zone) ++stats_.zoneContacts;
    if (e.type != ContactEventType::Begin) continue;
    stats_.hardestImpulse = std::max(stats_.hardestImpulse, e.normalImpulse);
    if ((isSphere(e.bodyA) && isTower(e.bodyB)) || (isTower(e.bodyA) && isSphere(e.bodyB))) {
      if (stats_.towerHits == 0) stats_.firstHitSpeed = e.approachSpeed;
      ++stats_.towerHits;
    }
  }
  for (const SensorEvent& e : world.sensorEvents()) {
    if (!e.begin) {
      ++stats_.sensorExits;
      continue;
    }
    ++stats_.sensorBegins;
    const auto key =
        static_cast<std::uint64_t>(e.visitorBody.generation) << 32 | e.visitorBody.index;
    if (entered_.insert(key).second) ++stats_.sensorEntries;
  }
}

void GameDirector::beforeStep(World& world) {
  tally(world);
  const double h = settings_.frameTime;
  const double t = world.time();
  // A shot when due: heavy spheres at the tower, one box higher each time.
  const auto due = static_cast<int>(std::floor(t / settings_.shotInterval + 1e-9));
  if (stats_.shots < std::min(due, settings_.maxShots)) {
    BodyDesc shot;
    shot.name = "shot" + std::to_string(stats_.shots);
    shot.pose.position = {-6.0, 0.0, kBoxHalf * (2 * (stats_.shots % kTowerHeight) + 1)};
    shot.linearVelocity = {settings_.shotSpeed, 0.0, 0.0};
    shot.density = 7800.0;  // steel
    shot.continuousCollision = true;
    shot.shapes.push_back({Sphere{0.08}, {}, {0.4, 0.0}, {}});
    spheres_.push_back(world.createBody(shot));
    ++stats_.shots;
  }
  // The lift: where it must be at the end of this step.
  world.setKinematicTarget(bodies_.lift, Pose::translation({3.0, -3.0, liftHeight(t + h)}), h);
}

void GameDirector::run(World& world, int frames) {
  for (int k = 0; k < frames; ++k) {
    beforeStep(world);
    world.step(settings_.frameTime);
  }
  tally(world);
}

std::optional<std::string> GameDirector::pick(const World& world, const Eigen::Vector3d& origin,
                                              const Eigen::Vector3d& direction) {
  WorldQueries queries(world);
  const auto hit = queries.castRay(origin, 100.0 * direction.normalized());
  if (!hit) return std::nullopt;
  return world.name(hit->body);
}

}  // namespace coulomb::samples
