// FunctionRef<R(Args...)>: a non-owning reference to a callable, for functions that call a callback before they
// return (ThreadPool::run). Unlike std::function it never allocates: a lambda with a large capture passed to it
// stays where the caller made it. The callable must outlive the FunctionRef (a temporary argument does).
#pragma once

#include <memory>
#include <type_traits>
#include <utility>

namespace tilevk::rast {

template <class Signature>
class FunctionRef;

template <class R, class... Args>
class FunctionRef<R(Args...)> {
  public:
    template <class F, class = std::enable_if_t<!std::is_same_v<std::decay_t<F>, FunctionRef> &&
                                                std::is_invocable_r_v<R, F&, Args...>>>
    FunctionRef(F&& f) noexcept  // NOLINT(google-explicit-constructor): made implicitly at the call site
        : obj_(const_cast<void*>(static_cast<const void*>(std::addressof(f)))), call_([](void* obj, Args... args) -> R {
              return (*static_cast<std::remove_reference_t<F>*>(obj))(std::forward<Args>(args)...);
          }) {}

    R operator()(Args... args) const { return call_(obj_, std::forward<Args>(args)...); }

  private:
    void* obj_;
    R (*call_)(void*, Args...);
};

}  // namespace tilevk::rast
