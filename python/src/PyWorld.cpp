#include "PyWorld.hpp"

#include <coulomb/engine/CoulombError.hpp>

namespace coulomb::python {
namespace {
constexpr const char* kBusy = "this World is being stepped by another thread";
}

engine::World& use(PyWorld& w) {
  if (w.stepping) throw engine::CoulombError(kBusy);
  return w.world;
}

const engine::World& use(const PyWorld& w) {
  if (w.stepping) throw engine::CoulombError(kBusy);
  return w.world;
}

SteppingGuard::SteppingGuard(PyWorld& w) : world_(w) {
  if (world_.stepping.exchange(true)) throw engine::CoulombError(kBusy);
}

}  // namespace coulomb::python
