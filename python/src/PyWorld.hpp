#pragma once
// The World behind coulomb.World (WorldBindings.cpp), shared with run_batch (RunBindings.cpp),
// which steps worlds given to it in place.
#include <coulomb/engine/World.hpp>

#include <utility>

namespace coulomb::python {

struct PyWorld {
  explicit PyWorld(engine::World w) : world(std::move(w)) {}
  engine::World world;
};

}  // namespace coulomb::python
