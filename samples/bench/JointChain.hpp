#pragma once
// The maximal-coordinate chain of docs/scene-specifications.md A6 (capsule links 0.1 m, 0.1 kg,
// ball joints, released horizontal), built for any length, solver and stabilization policy: shared
// by bench/JointChainBench and `coulomb bench --parts joints`.
#include <coulomb/engine/World.hpp>

#include <string>
#include <vector>

namespace coulomb::samples {

struct BallChain {
  engine::World world;
  std::vector<geometry::JointId> joints;  // joint i holds link i to link i - 1 (0: the world)
};

/// `links` links along +x from the origin, the first hung from a world point at the origin.
BallChain buildBallChain(int links, double timeStep, const std::string& solver,
                         joints::StabilizationMethod policy,
                         joints::EnergyTarget energy = joints::EnergyTarget::None);

/// Largest anchor separation over the chain's joints [m].
double maxAnchorGap(const BallChain& chain);

/// S = m g L N^2 / 2 [J]: the energy a chain of `links` releases falling from horizontal to
/// hanging straight (docs/scene-specifications.md A6 normalises the energy drift by it).
double chainReleasedEnergy(int links);

}  // namespace coulomb::samples
