// A user's program, compiled against the installed public headers (<coulomb/coulomb.hpp>) and
// linked with coulomb::core only: the README's falling box, with a contact event and a ray cast.
// It checks that the box comes to rest on the floor, at its half height.
#include <coulomb/coulomb.hpp>

#include <cmath>
#include <cstdio>

int main() {
  coulomb::World world;  // gravity -9.81 z, solver "auto"

  coulomb::BodyDesc floor;
  floor.motionType = coulomb::MotionType::Static;
  floor.shapes.push_back({coulomb::Plane{}, {}, {0.5, 0.0}, {}});
  world.createBody(floor);

  coulomb::BodyDesc box;  // a 0.2 m cube of water density, dropped from 1 m
  box.pose.position = {0.0, 0.0, 1.0};
  box.shapes.push_back({coulomb::Box{Eigen::Vector3d::Constant(0.1)}, {}, {0.5, 0.0}, {}});
  const coulomb::BodyId id = world.createBody(box);

  int landings = 0;
  for (int step = 0; step < 200; ++step) {
    world.step(0.01);
    for (const coulomb::ContactEvent& e : world.contactEvents())
      landings += e.type == coulomb::ContactEventType::Begin ? 1 : 0;
  }
  const double height = world.pose(id).position.z();
  coulomb::WorldQueries queries(world);
  const auto hit = queries.castRay({0.0, 0.0, 5.0}, {0.0, 0.0, -10.0});
  std::printf("box at z = %.6f m after 2 s, %d landing, ray hits z = %.6f\n", height, landings,
              hit ? hit->point.z() : -1.0);
  if (std::abs(height - 0.1) > 1e-3 || landings != 1 || !hit ||
      std::abs(hit->point.z() - 0.2) > 1e-3)
    return 1;
  std::printf("coulomb consumer ok\n");
  return 0;
}
