#include "entries/FuzzEntries.hpp"

#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/urdf/UrdfLoader.hpp>

#include <cmath>
#include <exception>

namespace coulomb::fuzz {

std::string urdfEntry(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  engine::io::UrdfOptions options;
  options.loadCollisionMeshes = false;  // no file access: meshes are listed, not read
  try {
    const engine::io::UrdfModel model =
        engine::io::parseUrdf(text, "fuzz.urdf", "/nonexistent-fuzz", options);
    // The loader repairs or refuses bad inertias: what it returns is finite (UrdfLoader.hpp).
    for (const engine::io::UrdfBody& body : model.bodies) {
      const geometry::SpatialInertia& m = body.inertia;
      if (!std::isfinite(m.mass) || !m.centerOfMass.allFinite() || !m.inertiaAboutCom.allFinite())
        return "body '" + body.name + "': non-finite inertia in the loaded model";
    }
    (void)engine::io::toArticulation(model);
    (void)engine::io::toArticulationDesc(model, "fuzz");
  } catch (const engine::CoulombError&) {
    // refused with a message: the documented outcome of bad input
  } catch (const std::exception& e) {
    return std::string("exception other than CoulombError: ") + e.what();
  }
  return {};
}

}  // namespace coulomb::fuzz
