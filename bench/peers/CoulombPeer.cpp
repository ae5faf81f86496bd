// Coulomb as it is used by default: the built-in scene through engine::io::buildWorld, with the
// scene's own settings (solver auto unless the scene names one).
#include "PeerEngine.hpp"

#include <coulomb/engine/World.hpp>

namespace coulomb::peers {
namespace {

class CoulombPeer final : public PeerEngine {
 public:
  explicit CoulombPeer(const PeerScene& scene) : world_(engine::io::buildWorld(scene.source)) {}
  void step() override { world_.step(); }
  void read(std::vector<BodySample>& out) const override {
    const geometry::BodyState& state = world_.state();
    out.resize(state.size());
    for (std::size_t i = 0; i < state.size(); ++i)
      out[i] = {state.poses[i].position, state.poses[i].rotation, state.linearVelocities[i],
                state.angularVelocities[i]};
  }

 private:
  engine::World world_;
};

}  // namespace

std::unique_ptr<PeerEngine> makeCoulomb(const PeerScene& scene) {
  return std::make_unique<CoulombPeer>(scene);
}

}  // namespace coulomb::peers
