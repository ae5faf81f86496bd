#pragma once
// How a caller lends its threads to a stage (the World's StepExecutor, WorldSettings::threads):
// parallel(count, task) calls task(i) for every i in [0, count), in any order and on any thread,
// and returns when all are done. Empty: the stage runs its loop on the calling thread.
#include <cstddef>
#include <functional>
#include <type_traits>

namespace coulomb::geometry {

/// A non-owning reference to a callable `void(std::size_t)`, valid while the call that receives
/// it runs: unlike std::function it never allocates (a steady step allocates nothing).
class TaskRef {
 public:
  template <class F, class = std::enable_if_t<!std::is_same_v<std::decay_t<F>, TaskRef>>>
  TaskRef(F&& task)  // NOLINT(google-explicit-constructor): lambdas convert in place
      : object_(const_cast<void*>(static_cast<const void*>(&task))),
        call_([](void* object, std::size_t i) {
          (*static_cast<std::remove_reference_t<F>*>(object))(i);
        }) {}
  void operator()(std::size_t i) const { call_(object_, i); }

 private:
  void* object_;
  void (*call_)(void*, std::size_t);
};

using ParallelFor = std::function<void(std::size_t count, TaskRef task)>;

}  // namespace coulomb::geometry
