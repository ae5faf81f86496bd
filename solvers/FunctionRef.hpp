#pragma once
// A non-owning reference to a callable, valid while the call that receives it runs: unlike
// std::function it never allocates and costs one indirect call, so it can sit in a solver's inner
// loop (one call per block per sweep) and a steady step allocates nothing.
#include <type_traits>
#include <utility>

namespace coulomb::solvers {

template <class Signature>
class FunctionRef;

template <class R, class... Args>
class FunctionRef<R(Args...)> {
 public:
  template <class F, class = std::enable_if_t<!std::is_same_v<std::decay_t<F>, FunctionRef>>>
  explicit FunctionRef(F& callable)
      : object_(const_cast<void*>(static_cast<const void*>(&callable))),
        call_([](void* object, Args... args) -> R {
          return (*static_cast<F*>(object))(std::forward<Args>(args)...);
        }) {}
  R operator()(Args... args) const { return call_(object_, std::forward<Args>(args)...); }

 private:
  void* object_;
  R (*call_)(void*, Args...);
};

}  // namespace coulomb::solvers
