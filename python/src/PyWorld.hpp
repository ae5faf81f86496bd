#pragma once
// The World behind coulomb.World (WorldBindings.cpp), shared with run_batch (RunBindings.cpp),
// which steps worlds given to it in place.
#include <coulomb/engine/World.hpp>

#include <atomic>
#include <utility>

namespace coulomb::python {

struct PyWorld {
  explicit PyWorld(engine::World w) : world(std::move(w)) {}
  engine::World world;
  // Set while step() or run_batch steps the world with the GIL released: another Python thread
  // touching the world meanwhile gets an error instead of a data race.
  std::atomic<bool> stepping{false};
};

/// The world, or CoulombError when another thread is stepping it.
engine::World& use(PyWorld& w);
const engine::World& use(const PyWorld& w);

/// Marks the world as stepping for its lifetime (CoulombError if it already is).
class SteppingGuard {
 public:
  explicit SteppingGuard(PyWorld& w);
  ~SteppingGuard() { world_.stepping = false; }
  SteppingGuard(const SteppingGuard&) = delete;
  SteppingGuard& operator=(const SteppingGuard&) = delete;

 private:
  PyWorld& world_;
};

}  // namespace coulomb::python
