// A user's program, compiled against the installed headers and libraries only: the README's
// falling box. It checks that the box comes to rest on the floor, at its half height.
#include <coulomb/engine/World.hpp>

#include <cmath>
#include <cstdio>

int main() {
  using namespace coulomb;
  engine::World world;  // gravity -9.81 z, solver "auto"

  engine::BodyDesc floor;
  floor.motionType = geometry::MotionType::Static;
  floor.shapes.push_back({geometry::Plane{}, {}, {0.5, 0.0}, {}});
  world.createBody(floor);

  engine::BodyDesc box;  // a 0.2 m cube of water density, dropped from 1 m
  box.pose.position = {0.0, 0.0, 1.0};
  box.shapes.push_back({geometry::Box{Eigen::Vector3d::Constant(0.1)}, {}, {0.5, 0.0}, {}});
  const geometry::BodyId id = world.createBody(box);

  for (int step = 0; step < 200; ++step) world.step(0.01);
  const double height = world.pose(id).position.z();
  std::printf("box at z = %.6f m after 2 s\n", height);
  if (std::abs(height - 0.1) > 1e-3) return 1;
  std::printf("coulomb consumer ok\n");
  return 0;
}
