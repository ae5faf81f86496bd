#pragma once
// The World behind coulomb.World (WorldBindings.cpp), shared with run_batch (RunBindings.cpp),
// which steps worlds given to it in place.
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/engine/WorldQueries.hpp>

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

namespace coulomb::python {

struct PyWorld {
  explicit PyWorld(engine::World w) : world(std::move(w)) {}
  engine::World world;
  // Set while step() or run_batch steps the world with the GIL released: another Python thread
  // touching the world meanwhile gets an error instead of a data race.
  std::atomic<bool> stepping{false};
  std::optional<engine::WorldQueries> queries;  // made at the first scene query (QueryBindings)
};

/// The world, or CoulombError when another thread is stepping it.
engine::World& use(PyWorld& w);
const engine::World& use(const PyWorld& w);

/// Handles are (generation << 32 | slot): an id of the engine packed into one Python int.
template <class Id>
std::int64_t handleOf(Id id) {
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(id.generation) << 32 | id.index);
}

/// The live id of a handle, or CoulombError naming it (`what`: "body", "joint").
template <class Id>
Id idOf(const PyWorld& w, std::int64_t handle, const char* what) {
  const auto bits = static_cast<std::uint64_t>(handle);
  const Id id{static_cast<std::uint32_t>(bits & 0xffffffffu),
              static_cast<std::uint32_t>(bits >> 32)};
  if (handle < 0 || !use(w).contains(id))
    throw engine::CoulombError(std::string(what) + " handle " + std::to_string(handle) +
                               " is stale or invalid");
  return id;
}

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
