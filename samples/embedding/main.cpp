// sample_embedding: the game-like scene of samples/embedding/Game.hpp, headless. Runs N frames
// (default 300: 5 s at 60 frames per second) and prints what the game saw through the embedding
// API: contact events, sensor entries, the one-way platform, the lift and a ray-cast pick.
// `coulomb view embedding` shows it in the viewer when that is built.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "Game.hpp"

int main(int argc, char** argv) {
  try {
    const int frames = argc > 1 ? std::stoi(argv[1]) : 300;
    coulomb::samples::GameBodies bodies;
    coulomb::World world = coulomb::samples::makeGameWorld(bodies);
    coulomb::samples::GameDirector director(bodies);
    director.run(world, frames);
    const coulomb::samples::GameStats& s = director.stats();
    std::printf("%d frames (%.2f s): %d shots, %d hits on the tower (first at %.1f m/s)\n", frames,
                world.time(), s.shots, s.towerHits, s.firstHitSpeed);
    std::printf("sensor: %d bodies entered, %d exits; hardest impact %.2f N s\n", s.sensorEntries,
                s.sensorExits, s.hardestImpulse);
    std::printf("jumper at z = %.3f m (platform top 1.230 m); crate %.3f m above the lift\n",
                world.pose(bodies.jumper).position.z(),
                world.pose(bodies.crate).position.z() - world.pose(bodies.lift).position.z());
    const auto picked =
        coulomb::samples::GameDirector::pick(world, {3.0, -3.0, 5.0}, {0.0, 0.0, -1.0});
    std::printf("ray pick straight down over the lift: %s\n", picked ? picked->c_str() : "nothing");
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sample_embedding: %s\n", e.what());
    return 1;
  }
}
